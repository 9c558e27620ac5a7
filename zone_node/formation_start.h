#pragma once
// Where the members of a formation (populations[].formation) stand: slots around a centre that
// starts on the first route point facing the second. The initial population places members
// there, and the formation system steps them toward their slots, so both read this one rule.

#include <cstddef>

#include "crowd/formation.h"
#include "crowd/vec2.h"

namespace zonesim {
struct Scene;
struct NpcFormation;
}  // namespace zonesim

namespace zonesim::zone {

struct WorldMap;

/// The crowd library's settings of a scene formation.
crowd::FormationSettings formationSettings(const NpcFormation& f);

/// The heading the formation starts with: toward the second route point.
crowd::Vec2 formationHeading(const NpcFormation& f);

/// Slot offset (formation frame: x ahead, y to the left) of member `k` of a formation of
/// `count` members: rows of `columns` across the heading, `spacing` apart, centred on the
/// formation's centre.
crowd::Vec2 formationSlot(const NpcFormation& f, int count, int k);

/// Where member `k` of population `p` starts: its slot around the first route point, the
/// formation facing the second (the centre itself when the slot lies on a blocked cell).
crowd::Vec2 formationStart(const Scene& scene, const WorldMap& map, std::size_t p, int k);

}  // namespace zonesim::zone
