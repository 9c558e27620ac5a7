#include "crowd/flow_field_file.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace zonesim::crowd {

namespace {

constexpr char kMagic[8] = {'Z', 'S', 'F', 'L', 'O', 'W', '1', '\n'};
static_assert(std::endian::native == std::endian::little, "fields files are little-endian");

template <typename T>
void put(std::ofstream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <typename T>
T get(std::ifstream& in, const std::string& path) {
  T v{};
  if (!in.read(reinterpret_cast<char*>(&v), sizeof(T)))
    throw std::runtime_error(path + ": flow fields file is cut short");
  return v;
}

template <typename T>
std::vector<T> getArray(std::ifstream& in, std::size_t n, const std::string& path) {
  std::vector<T> v(n);
  if (!in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(T))))
    throw std::runtime_error(path + ": flow fields file is cut short");
  return v;
}

}  // namespace

std::uint64_t mapFingerprint(const ai::GridMap& map) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto mix = [&](std::uint64_t byte) {
    h ^= byte;
    h *= 1099511628211ULL;
  };
  for (int v : {map.width(), map.height()})
    for (int b = 0; b < 4; ++b) mix((std::uint32_t(v) >> (8 * b)) & 0xff);
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x) mix(map.passable(x, y) ? 1 : 0);
  return h;
}

void writeFlowFields(const std::string& path, const ai::GridMap& map,
                     std::span<const FlowField* const> fields) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(path + ": cannot write flow fields file");
  out.write(kMagic, sizeof(kMagic));
  put(out, std::uint32_t(map.width()));
  put(out, std::uint32_t(map.height()));
  put(out, mapFingerprint(map));
  put(out, std::uint32_t(fields.size()));
  for (const FlowField* f : fields) {
    put(out, std::int32_t(f->goal().x));
    put(out, std::int32_t(f->goal().y));
    out.write(reinterpret_cast<const char*>(f->distances().data()),
              std::streamsize(f->distances().size() * sizeof(float)));
    out.write(reinterpret_cast<const char*>(f->directions().data()),
              std::streamsize(f->directions().size()));
  }
  if (!out.flush()) throw std::runtime_error(path + ": writing flow fields failed");
}

std::vector<std::unique_ptr<FlowField>> readFlowFields(const std::string& path,
                                                       const ai::GridMap& map) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open flow fields file");
  char magic[sizeof(kMagic)] = {};
  if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
    throw std::runtime_error(path + ": not a flow fields file");
  const auto width = get<std::uint32_t>(in, path), height = get<std::uint32_t>(in, path);
  const auto fingerprint = get<std::uint64_t>(in, path);
  if (int(width) != map.width() || int(height) != map.height() ||
      fingerprint != mapFingerprint(map)) {
    throw std::runtime_error(path + ": built for another map (" + std::to_string(width) + " x " +
                             std::to_string(height) +
                             " cells, or the same size with other cells blocked); build it "
                             "again with bake_fields");
  }
  const auto count = get<std::uint32_t>(in, path);
  const std::size_t n = std::size_t(width) * height;
  std::vector<std::unique_ptr<FlowField>> fields;
  for (std::uint32_t i = 0; i < count; ++i) {
    const ai::Cell goal{get<std::int32_t>(in, path), get<std::int32_t>(in, path)};
    std::vector<float> distance = getArray<float>(in, n, path);
    std::vector<std::int8_t> dir = getArray<std::int8_t>(in, n, path);
    try {
      fields.push_back(std::make_unique<FlowField>(map, goal, std::move(distance), std::move(dir)));
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(path + ": field " + std::to_string(i) + ": " + e.what());
    }
  }
  if (in.peek() != std::char_traits<char>::eof())
    throw std::runtime_error(path + ": flow fields file has bytes after its last field");
  return fields;
}

}  // namespace zonesim::crowd
