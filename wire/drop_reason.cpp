#include "wire/drop_reason.h"

namespace zonesim::gateway {

const char* dropReasonName(DropReason reason) {
  switch (reason) {
    case DropReason::TooLarge:
      return "too_large";
    case DropReason::Truncated:
      return "truncated";
    case DropReason::BadIdentifier:
      return "bad_identifier";
    case DropReason::Malformed:
      return "malformed";
    case DropReason::NoMessage:
      return "no_message";
    case DropReason::UnexpectedType:
      return "unexpected_type";
    case DropReason::OutOfRange:
      return "out_of_range";
    case DropReason::BadToken:
      return "bad_token";
    case DropReason::WrongAddress:
      return "wrong_address";
    case DropReason::NotReady:
      return "not_ready";
    case DropReason::StaleInput:
      return "stale_input";
    case DropReason::SessionLimit:
      return "session_limit";
    case DropReason::BadChecksum:
      return "bad_checksum";
    case DropReason::RateLimited:
      return "rate_limited";
    case DropReason::TokenMissing:
      return "token_missing";
    case DropReason::TokenForged:
      return "token_forged";
    case DropReason::TokenExpired:
      return "token_expired";
    case DropReason::TokenWrongGateway:
      return "token_wrong_gateway";
    case DropReason::TokenWrongAddress:
      return "token_wrong_address";
    case DropReason::TokenReused:
      return "token_reused";
    case DropReason::UnknownKind:
      return "unknown_kind";
    case DropReason::ResumeForged:
      return "resume_forged";
    case DropReason::ResumeExpired:
      return "resume_expired";
    case DropReason::ResumeWrongAddress:
      return "resume_wrong_address";
    case DropReason::Count:
      break;
  }
  return "unknown";
}

std::uint64_t DropCounters::total() const {
  std::uint64_t t = 0;
  for (std::uint64_t c : counts_) t += c;
  return t;
}

}  // namespace zonesim::gateway
