#pragma once
// Another connection's exclusive transaction on a SQLite file: the ledger's writers get
// SQLITE_BUSY, a database that is "down" for them while readers go on.

#include <sqlite3.h>

#include <stdexcept>
#include <string>

namespace zonesim::ledger::test {

/// Another connection's exclusive transaction on a SQLite file: writers get SQLITE_BUSY.
class SqliteWriteLock {
 public:
  explicit SqliteWriteLock(const std::string& path) {
    if (sqlite3_open(path.c_str(), &db_) != SQLITE_OK ||
        sqlite3_exec(db_, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr) != SQLITE_OK) {
      throw std::runtime_error("cannot lock " + path + ": " + sqlite3_errmsg(db_));
    }
  }
  ~SqliteWriteLock() { release(); }
  SqliteWriteLock(const SqliteWriteLock&) = delete;
  SqliteWriteLock& operator=(const SqliteWriteLock&) = delete;
  void release() {
    if (!db_) return;
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    sqlite3_close(db_);
    db_ = nullptr;
  }

 private:
  sqlite3* db_ = nullptr;
};

}  // namespace zonesim::ledger::test
