// bake_fields: builds the flow fields of every flow destination of a scene on its map and
// writes them to one file (crowd/flow_field_file.h), which the scene then names as
// `map.fields` so that zones load them instead of building them at start. Prints how long
// building took, the fields' size, and how long reading the file back took (checked equal).
//
//   build/bin/bake_fields SCENE [--out FILE]   (FILE defaults to the scene's map.fields)

#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/scene.h"
#include "crowd/flow_field.h"
#include "crowd/flow_field_file.h"
#include "zone_node/world_map.h"
#include "zone_node/zone_map.h"

using namespace zonesim;

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int bake(const std::string& scene_path, std::string out) {
  const Scene scene = loadScene(scene_path);
  if (out.empty()) out = scene.map.fields;
  if (out.empty()) {
    std::fprintf(stderr, "%s: the scene names no map.fields; give --out FILE\n",
                 scene_path.c_str());
    return 2;
  }
  std::unique_ptr<zone::ZoneMap> map = zone::ZoneMap::load(scene);
  if (!map) {
    std::fprintf(stderr, "%s: the scene has no map\n", scene_path.c_str());
    return 2;
  }
  const zone::WorldMap& world = map->world();
  std::vector<ai::Cell> goals;
  for (std::size_t p = 0; p < scene.npcs.size(); ++p) {
    for (const NpcFlow::Destination& d : scene.npcs[p].flow.destinations) {
      const ai::Cell c = world.frame.cellOf({d.x, d.z});
      bool known = false;
      for (ai::Cell g : goals) known = known || (g.x == c.x && g.y == c.y);
      if (!known) goals.push_back(c);
    }
  }
  if (goals.empty()) {
    std::fprintf(stderr, "%s: no flow destinations to bake\n", scene_path.c_str());
    return 2;
  }
  auto t0 = std::chrono::steady_clock::now();
  std::vector<std::unique_ptr<crowd::FlowField>> fields;
  std::size_t bytes = 0;
  for (ai::Cell g : goals) {
    fields.push_back(std::make_unique<crowd::FlowField>(world.grid, g));
    bytes += fields.back()->bytes();
  }
  const double build_ms = msSince(t0);
  std::vector<const crowd::FlowField*> views;
  for (const auto& f : fields) views.push_back(f.get());
  crowd::writeFlowFields(out, world.grid, views);
  t0 = std::chrono::steady_clock::now();
  std::vector<std::unique_ptr<crowd::FlowField>> back = crowd::readFlowFields(out, world.grid);
  const double load_ms = msSince(t0);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (back[i]->distances() != fields[i]->distances() ||
        back[i]->directions() != fields[i]->directions()) {
      std::fprintf(stderr, "%s: field %zu reads back different\n", out.c_str(), i);
      return 1;
    }
  }
  std::printf(
      "%s: %zu fields on %d x %d cells, %zu bytes in memory, file %ju bytes; built in "
      "%.2f ms, read back in %.2f ms (%.1fx)\n",
      out.c_str(), fields.size(), world.grid.width(), world.grid.height(), bytes,
      std::uintmax_t(std::filesystem::file_size(out)), build_ms, load_ms, build_ms / load_ms);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help")) {
    std::fprintf(stderr, "usage: %s SCENE [--out FILE]\n", argv[0]);
    return 2;
  }
  std::string out;
  for (int i = 2; i + 1 < argc; i += 2)
    if (!std::strcmp(argv[i], "--out")) out = argv[i + 1];
  try {
    return bake(argv[1], out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
