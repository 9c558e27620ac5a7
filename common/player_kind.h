#pragma once
// Player kinds: walkers, riders and flyers (the seed's behavioural interest: a plane sees
// farther than a jeep). A kind's id travels in the client's Hello, the zones' spawn request and
// the avatar's record, so each name has one fixed id whatever kinds a scene lists; a scene says
// which kinds it has and how fast and far-sighted each is (common/scene_clients.h).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace zonesim {

/// A kind's wire id; 0 is what a Hello without the field means (the walkers of before kinds).
enum class PlayerKindId : std::uint8_t { Walker = 0, Rider = 1, Flyer = 2 };

/// How many kinds exist: valid ids are 0 .. kPlayerKindCount - 1.
inline constexpr std::size_t kPlayerKindCount = 3;

/// The names scene files and options use, by id.
inline constexpr std::array<std::string_view, kPlayerKindCount> kPlayerKindNames{"walker", "rider",
                                                                                 "flyer"};

/// The name of a kind id; "unknown" for a byte that names none.
inline std::string_view playerKindName(std::uint8_t id) {
  return id < kPlayerKindCount ? kPlayerKindNames[id] : std::string_view("unknown");
}

/// The name of a kind.
inline std::string_view playerKindName(PlayerKindId id) {
  return playerKindName(std::uint8_t(id));
}

/// The kind a name stands for, or nothing.
inline std::optional<PlayerKindId> playerKindNamed(std::string_view name) {
  for (std::size_t i = 0; i < kPlayerKindCount; ++i)
    if (kPlayerKindNames[i] == name) return PlayerKindId(i);
  return std::nullopt;
}

}  // namespace zonesim
