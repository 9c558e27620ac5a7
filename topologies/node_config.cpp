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

std::string Cheats::names() const {
  std::string out;
  for (Cheat c : {Cheat::Teleport, Cheat::Speed, Cheat::Hit})
    if (has(c)) out += (out.empty() ? "" : ",") + std::string(cheatName(c));
  return out.empty() ? "none" : out;
}

Cheats parseCheats(const std::string& text) {
  Cheats out;
  std::size_t at = 0;
  for (;;) {
    std::size_t comma = text.find(',', at);
    Cheat c =
        parseCheat(text.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
    out.teleport |= c == Cheat::Teleport;
    out.speed |= c == Cheat::Speed;
    out.hit |= c == Cheat::Hit;
    if (comma == std::string::npos) return out;
    at = comma + 1;
  }
}

}  // namespace zonesim::topo
