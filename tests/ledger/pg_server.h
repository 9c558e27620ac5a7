#pragma once
// A real PostgreSQL server for one test binary, from Debian's postgresql package: initdb in a
// fresh temporary folder, the server on a Unix socket in that folder only (no TCP port, so
// parallel tests and other runs never meet), trust authentication. As root it runs as the
// package's `postgres` user (the server refuses root). The destructor stops it and removes the
// folder; the server also gets SIGKILL should the test process die first (PR_SET_PDEATHSIG).

#include <sys/types.h>

#include <string>
#include <vector>

namespace zonesim::ledger::test {

class PgServer {
 public:
  /// initdb and start; throws std::runtime_error saying what failed and why (the log's tail).
  PgServer();
  ~PgServer();
  PgServer(const PgServer&) = delete;
  PgServer& operator=(const PgServer&) = delete;

  /// Starts the server on the existing data folder and waits until it accepts connections.
  void start();
  /// Immediate shutdown (SIGQUIT): no checkpoint, crash recovery at the next start, as after
  /// a crash. Waits until the process is gone.
  void kill();
  bool running() const { return pid_ > 0; }

  /// A libpq connection string for database `dbname` on this server.
  std::string conninfo(const std::string& dbname = "postgres") const;
  /// CREATE DATABASE; throws std::runtime_error.
  void createDatabase(const std::string& dbname);
  const std::string& folder() const { return dir_; }

 private:
  void stop();
  pid_t spawn(const std::string& program, const std::vector<std::string>& args,
              const std::string& log, bool die_with_parent);
  std::string logTail() const;

  std::string bindir_;
  std::string dir_;
  uid_t uid_ = 0;
  gid_t gid_ = 0;
  bool switch_user_ = false;
  pid_t pid_ = -1;
};

/// The one server of this test binary, started on first use; throws like PgServer().
PgServer& sharedServer();

}  // namespace zonesim::ledger::test
