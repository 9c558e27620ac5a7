#include "ledger/store.h"

#include "ledger/postgres_store.h"
#include "ledger/sqlite_store.h"

namespace zonesim::ledger {

std::string_view statusName(TxStatus status) {
  switch (status) {
    case TxStatus::Committed:
      return "committed";
    case TxStatus::AlreadyCommitted:
      return "already_committed";
    case TxStatus::Conflict:
      return "conflict";
    case TxStatus::Failed:
      return "failed";
  }
  return "unknown";
}

std::string_view failureName(StoreFailure failure) {
  switch (failure) {
    case StoreFailure::Unavailable:
      return "unavailable";
    case StoreFailure::Full:
      return "full";
    case StoreFailure::Error:
      return "error";
  }
  return "unknown";
}

StoreConfig parseStoreSpec(std::string_view spec) {
  std::size_t colon = spec.find(':');
  if (colon == std::string_view::npos)
    throw std::invalid_argument("ledger '" + std::string(spec) +
                                "': expected sqlite:PATH or postgres:CONNINFO");
  StoreConfig c{std::string(spec.substr(0, colon)), std::string(spec.substr(colon + 1))};
  if (c.backend != "sqlite" && c.backend != "postgres")
    throw std::invalid_argument("ledger '" + std::string(spec) + "': unknown back end '" +
                                c.backend + "' (sqlite or postgres)");
  if (c.target.empty())
    throw std::invalid_argument("ledger '" + std::string(spec) + "': no " +
                                (c.backend == "sqlite" ? "file path" : "connection string"));
  return c;
}

std::unique_ptr<LedgerStore> openStore(const StoreConfig& config) {
  if (config.backend == "sqlite") {
    if (config.target.empty()) {
      throw std::invalid_argument("ledger: the sqlite back end needs a file path");
    }
    return std::make_unique<SqliteStore>(SqliteOptions{.path = config.target});
  }
  if (config.backend == "postgres") {
    if (config.target.empty()) {
      throw std::invalid_argument("ledger: the postgres back end needs a connection string");
    }
    return std::make_unique<PostgresStore>(PostgresOptions{.conninfo = config.target});
  }
  throw std::invalid_argument("ledger: unknown back end '" + config.backend +
                              "' (sqlite or postgres)");
}

}  // namespace zonesim::ledger
