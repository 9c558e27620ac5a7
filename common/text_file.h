#pragma once
// Writing a small text file (a port file, a summary) so that a script polling for it never
// reads it half written: to a temporary name, then renamed.

#include <string>

namespace zonesim {

/// Writes text and a newline to path via path + ".tmp" and a rename; throws
/// std::runtime_error naming the file when it cannot be written.
void writeTextFileAtomically(const std::string& path, const std::string& text);

}  // namespace zonesim
