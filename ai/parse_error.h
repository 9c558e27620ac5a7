#pragma once
// Errors in map and scenario files: the message starts with `file:line:` so that a user can
// jump to the offending line.

#include <stdexcept>
#include <string>

namespace zonesim::ai {

/// A malformed input file; what() reads `file:line: message`.
class ParseError : public std::runtime_error {
 public:
  /// Builds the `file:line: message` text.
  ParseError(const std::string& file, int line, const std::string& message)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + message),
        file_(file),
        line_(line) {}
  /// The file the error is in.
  const std::string& file() const { return file_; }
  /// The 1-based line number of the error.
  int line() const { return line_; }

 private:
  std::string file_;
  int line_;
};

}  // namespace zonesim::ai
