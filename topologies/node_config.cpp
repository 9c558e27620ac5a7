#include "topologies/node_config.h"

#include <stdexcept>

namespace zonesim::topo {

namespace {
constexpr Cheat kCheats[] = {Cheat::None, Cheat::Teleport, Cheat::Speed,
                             Cheat::Hit,  Cheat::Vote,     Cheat::Equivocate};
}  // namespace

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
    case Cheat::Vote:
      return "vote";
    case Cheat::Equivocate:
      return "equivocate";
  }
  return "?";
}

Cheat parseCheat(const std::string& text) {
  for (Cheat c : kCheats)
    if (text == cheatName(c)) return c;
  throw std::invalid_argument("cheat '" + text +
                              "' is not one of none, teleport, speed, hit, vote, equivocate");
}

std::string Cheats::names() const {
  std::string out;
  for (Cheat c : kCheats)
    if (c != Cheat::None && has(c)) out += (out.empty() ? "" : ",") + std::string(cheatName(c));
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
    out.vote |= c == Cheat::Vote;
    out.equivocate |= c == Cheat::Equivocate;
    if (comma == std::string::npos) return out;
    at = comma + 1;
  }
}

}  // namespace zonesim::topo
