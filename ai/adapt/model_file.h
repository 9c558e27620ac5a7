#pragma once
// The model file: small text a scene names (adaptation.model). Line 1 is the version line;
// then one `key value...` per line, `#` comments and blank lines allowed:
//   zonesim-adapt-model 1
//   basis cubic-hd
//   weights w0 ... w9
//   trained_rounds N
//   seed S
//   smoothing A
// Weights are written with 17 significant digits, so a model reads back bit for bit.

#include <iosfwd>
#include <string>

#include "ai/adapt/duel_model.h"

namespace zonesim::ai::adapt {

/// The version line this code reads and writes.
inline constexpr const char* kModelVersionLine = "zonesim-adapt-model 1";

/// Writes `model` as model-file text.
void writeModel(std::ostream& out, const DuelModel& model);
/// Writes `model` to `path`; throws std::runtime_error naming the path on failure.
void saveModel(const std::string& path, const DuelModel& model);
/// Reads model-file text; throws ai::ParseError naming `name`, the line and what is wrong.
DuelModel readModel(std::istream& in, const std::string& name);
/// Reads the model file at `path` (ai::ParseError, line 0, when it cannot be opened).
DuelModel loadModel(const std::string& path);

}  // namespace zonesim::ai::adapt
