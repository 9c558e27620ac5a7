#include "topologies/node_config.h"

#include <stdexcept>

namespace zonesim::topo {

const char* cheatName(Cheat cheat) {
  switch (cheat) {
    case Cheat::None:
      return "none";
    case Cheat::Teleport:
      return "teleport";
    case Cheat::Speed:
      return "speed";
    case Cheat::Hit:
      return "hit";
  }
  return "?";
}

Cheat parseCheat(const std::string& text) {
  for (Cheat c : {Cheat::None, Cheat::Teleport, Cheat::Speed, Cheat::Hit})
    if (text == cheatName(c)) return c;
  throw std::invalid_argument("cheat '" + text + "' is not one of none, teleport, speed, hit");
}

}  // namespace zonesim::topo
