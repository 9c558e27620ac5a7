#include "pg_server.h"

#include <fcntl.h>
#include <grp.h>
#include <libpq-fe.h>
#include <pwd.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace zonesim::ledger::test {
namespace {

namespace fs = std::filesystem;

// Debian installs each major version's server under /usr/lib/postgresql/<major>/bin;
// ZONESIM_PG_BINDIR overrides. The newest one wins.
std::string findBindir() {
  if (const char* env = std::getenv("ZONESIM_PG_BINDIR")) return env;
  std::vector<fs::path> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/usr/lib/postgresql", ec)) {
    if (fs::exists(entry.path() / "bin" / "postgres")) found.push_back(entry.path() / "bin");
  }
  if (found.empty()) {
    throw std::runtime_error(
        "no PostgreSQL server under /usr/lib/postgresql/*/bin (install Debian's postgresql "
        "package: deploy/setup.sh), or set ZONESIM_PG_BINDIR");
  }
  std::sort(found.begin(), found.end(), [](const fs::path& a, const fs::path& b) {
    return std::stoi(a.parent_path().filename()) < std::stoi(b.parent_path().filename());
  });
  return found.back().string();
}

constexpr int kPort = 5432;  // only names the socket file inside our own folder
constexpr auto kReadyDeadline = std::chrono::seconds(60);
constexpr auto kStopDeadline = std::chrono::seconds(30);

// Waits for `pid` up to `deadline`; true if it exited.
bool waitExit(pid_t pid, std::chrono::steady_clock::duration deadline, int* status) {
  auto until = std::chrono::steady_clock::now() + deadline;
  for (;;) {
    pid_t r = waitpid(pid, status, WNOHANG);
    if (r == pid || (r < 0 && errno == ECHILD)) return true;
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

PgServer::PgServer() {
  bindir_ = findBindir();
  if (geteuid() == 0) {
    // The server refuses to run as root; Debian's package made this user.
    struct passwd* pw = getpwnam("postgres");
    if (!pw)
      throw std::runtime_error(
          "running as root and there is no 'postgres' user to run the server as");
    uid_ = pw->pw_uid;
    gid_ = pw->pw_gid;
    switch_user_ = true;
  }
  std::string tmpl = (fs::temp_directory_path() / "zonesim-pg-XXXXXX").string();
  if (!mkdtemp(tmpl.data())) {
    throw std::runtime_error("cannot make a temporary folder " + tmpl + ": " +
                             std::strerror(errno));
  }
  dir_ = tmpl;
  try {
    if (switch_user_ && chown(dir_.c_str(), uid_, gid_) != 0) {
      throw std::runtime_error("cannot give " + dir_ +
                               " to user postgres: " + std::strerror(errno));
    }
    int status = 0;
    pid_t init = spawn(bindir_ + "/initdb",
                       {"-D", dir_ + "/data", "-U", "postgres", "-A", "trust", "-E", "UTF8",
                        "--no-sync", "--no-instructions"},
                       dir_ + "/initdb.log", true);
    if (!waitExit(init, std::chrono::seconds(120), &status)) {
      ::kill(init, SIGKILL);
      waitpid(init, &status, 0);
      throw std::runtime_error("initdb did not finish in 120 s: " + logTail());
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::ifstream log(dir_ + "/initdb.log");
      std::stringstream text;
      text << log.rdbuf();
      throw std::runtime_error("initdb failed in " + dir_ + ": " + text.str());
    }
    start();
  } catch (...) {
    stop();
    std::error_code ec;
    fs::remove_all(dir_, ec);
    throw;
  }
}

PgServer::~PgServer() {
  stop();
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

pid_t PgServer::spawn(const std::string& program, const std::vector<std::string>& args,
                      const std::string& log, bool die_with_parent) {
  // Everything the child needs is made before fork: the test process may have other threads
  // (a committer's worker), so the child may only make async-signal-safe calls.
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t parent = getpid();
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid > 0) return pid;
  int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd >= 0) {
    dup2(fd, 1);
    dup2(fd, 2);
  }
  int null = open("/dev/null", O_RDONLY);
  if (null >= 0) dup2(null, 0);
  if (switch_user_) {
    if (fd >= 0) fchown(fd, uid_, gid_);
    if (setgroups(0, nullptr) != 0 || setgid(gid_) != 0 || setuid(uid_) != 0) _exit(126);
  }
  // After the user change, which would clear it.
  if (die_with_parent) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(125);
  }
  execv(program.c_str(), argv.data());
  _exit(127);
}

std::string PgServer::logTail() const {
  std::ifstream log(dir_ + "/server.log");
  std::string line, tail;
  std::vector<std::string> lines;
  while (std::getline(log, line)) lines.push_back(line);
  for (std::size_t i = lines.size() > 8 ? lines.size() - 8 : 0; i < lines.size(); ++i) {
    tail += lines[i] + " | ";
  }
  return tail.empty() ? "(server.log is empty)" : tail;
}

void PgServer::start() {
  if (pid_ > 0) return;
  pid_ = spawn(bindir_ + "/postgres",
               {"-D", dir_ + "/data", "-k", dir_, "-p", std::to_string(kPort), "-c",
                "listen_addresses=", "-c", "shared_buffers=16MB", "-c", "max_connections=30", "-c",
                "logging_collector=off"},
               dir_ + "/server.log", true);
  const std::string info = conninfo() + " connect_timeout=5";
  auto until = std::chrono::steady_clock::now() + kReadyDeadline;
  for (;;) {
    if (PQping(info.c_str()) == PQPING_OK) return;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      throw std::runtime_error("the PostgreSQL server in " + dir_ +
                               " exited at start: " + logTail());
    }
    if (std::chrono::steady_clock::now() >= until) {
      stop();
      throw std::runtime_error("the PostgreSQL server in " + dir_ +
                               " did not accept connections within 60 s: " + logTail());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

void PgServer::kill() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGQUIT);
  int status = 0;
  if (!waitExit(pid_, kStopDeadline, &status)) {
    ::kill(pid_, SIGKILL);
    waitpid(pid_, &status, 0);
  }
  pid_ = -1;
}

void PgServer::stop() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGINT);  // fast shutdown: ends sessions, checkpoints, removes its shared memory
  int status = 0;
  if (!waitExit(pid_, kStopDeadline, &status)) {
    ::kill(pid_, SIGKILL);
    waitpid(pid_, &status, 0);
  }
  pid_ = -1;
}

std::string PgServer::conninfo(const std::string& dbname) const {
  return "host=" + dir_ + " port=" + std::to_string(kPort) + " user=postgres dbname=" + dbname;
}

void PgServer::createDatabase(const std::string& dbname) {
  std::unique_ptr<PGconn, void (*)(PGconn*)> conn(PQconnectdb(conninfo().c_str()), PQfinish);
  if (PQstatus(conn.get()) != CONNECTION_OK) {
    throw std::runtime_error("cannot connect to create " + dbname + ": " +
                             PQerrorMessage(conn.get()));
  }
  std::string sql = "CREATE DATABASE " + dbname;
  std::unique_ptr<PGresult, void (*)(PGresult*)> res(PQexec(conn.get(), sql.c_str()), PQclear);
  if (PQresultStatus(res.get()) != PGRES_COMMAND_OK) {
    throw std::runtime_error(sql + ": " + PQresultErrorMessage(res.get()));
  }
}

PgServer& sharedServer() {
  static PgServer server;
  return server;
}

}  // namespace zonesim::ledger::test
