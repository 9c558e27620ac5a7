#include "ai/adapt/model_file.h"

#include <cstdio>
#include <fstream>
#include <istream>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "ai/parse_error.h"
#include "ai/text_lines.h"

namespace zonesim::ai::adapt {

namespace {

constexpr std::string_view kBasisName = "cubic-hd";

std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::uint64_t parseCount(std::string_view s, const std::string& name, int line,
                         std::string_view key) {
  std::uint64_t v = 0;
  auto res = std::from_chars(s.data(), s.data() + s.size(), v);
  if (res.ec != std::errc() || res.ptr != s.data() + s.size())
    throw ParseError(
        name, line,
        std::string(key) + ": '" + std::string(s) + "' is not a non-negative whole number");
  return v;
}

}  // namespace

void writeModel(std::ostream& out, const DuelModel& model) {
  out << kModelVersionLine << "\n";
  out << "# P(player wins | measured hit rate h, NPC difficulty d) = logistic(w . basis(h, d))\n";
  out << "basis " << kBasisName << "\nweights";
  for (double w : model.weights) out << " " << exact(w);
  out << "\ntrained_rounds " << model.trained_rounds << "\nseed " << model.seed << "\nsmoothing "
      << exact(model.smoothing) << "\n";
}

void saveModel(const std::string& path, const DuelModel& model) {
  std::ofstream out(path);
  writeModel(out, model);
  out.flush();
  if (!out) throw std::runtime_error(path + ": cannot write the model file");
}

DuelModel readModel(std::istream& in, const std::string& name) {
  DuelModel model;
  std::set<std::string, std::less<>> seen;
  std::string text;
  int line = 0;
  bool versioned = false;
  while (readLine(in, text)) {
    ++line;
    std::vector<std::string_view> f = splitFields(text);
    if (f.empty() || f[0][0] == '#') continue;
    if (!versioned) {
      if (f.size() != 2 || f[0] != "zonesim-adapt-model")
        throw ParseError(name, line,
                         std::string("expected the version line '") + kModelVersionLine +
                             "', got '" + text + "'");
      if (f[1] != "1")
        throw ParseError(
            name, line,
            "model version " + std::string(f[1]) + " is not supported (this build reads 1)");
      versioned = true;
      continue;
    }
    const std::string key(f[0]);
    if (!seen.insert(key).second) throw ParseError(name, line, key + ": given twice");
    auto one = [&] {
      if (f.size() != 2) throw ParseError(name, line, key + ": expected one value");
      return f[1];
    };
    if (key == "basis") {
      if (one() != kBasisName)
        throw ParseError(name, line,
                         "basis: '" + std::string(f[1]) +
                             "' is unknown (allowed: " + std::string(kBasisName) + ")");
    } else if (key == "weights") {
      if (f.size() != kBasisSize + 1)
        throw ParseError(name, line,
                         "weights: expected " + std::to_string(kBasisSize) + " numbers, got " +
                             std::to_string(f.size() - 1));
      for (std::size_t i = 0; i < kBasisSize; ++i)
        if (!parseDouble(f[i + 1], model.weights[i]))
          throw ParseError(name, line,
                           "weights: value " + std::to_string(i + 1) + " '" +
                               std::string(f[i + 1]) + "' is not a finite number");
    } else if (key == "trained_rounds") {
      model.trained_rounds = parseCount(one(), name, line, key);
    } else if (key == "seed") {
      model.seed = parseCount(one(), name, line, key);
    } else if (key == "smoothing") {
      if (!parseDouble(one(), model.smoothing) || !(model.smoothing > 0 && model.smoothing <= 1))
        throw ParseError(name, line,
                         "smoothing: '" + std::string(f[1]) + "' is not a number in (0, 1]");
    } else {
      throw ParseError(name, line,
                       "unknown key '" + key +
                           "' (allowed: basis, weights, trained_rounds, seed, "
                           "smoothing)");
    }
  }
  if (!versioned) throw ParseError(name, line, "empty model file: no version line");
  for (const char* key : {"basis", "weights", "smoothing"})
    if (!seen.count(key)) throw ParseError(name, line, std::string(key) + ": missing");
  return model;
}

DuelModel loadModel(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ParseError(path, 0, "cannot open the model file");
  return readModel(in, path);
}

}  // namespace zonesim::ai::adapt
