#pragma once
// The pace of a topology node's game and the size of its cheats, shared by the node's files
// (topology_node*.cpp).

#include <cstdint>
#include <ctime>

namespace zonesim::topo::rules {

// Registrations live this long unless refreshed; refreshed every kRefreshTicks ticks, so a
// node that dies leaves the list within a few seconds.
constexpr double kRegistrationTtlSeconds = 5;
// Discovery requests and refreshes once a second at the scene's 20 Hz.
constexpr std::uint64_t kRefreshTicks = 20;
// Views are written every other tick: 10 samples a second per pair is plenty for percentiles.
constexpr std::uint64_t kViewEveryTicks = 2;
// A "seen" event is written when a player's velocity changed by more than this since the last:
// one tick of the avatar's acceleration (24 m/s^2 x 0.05 s = 1.2 m/s) passes it, the codec's
// velocity rounding (1/256 m/s) never does.
constexpr double kSeenVelocityChange = 0.25;
// Cheats: how much faster a speed hacker goes, how far and how often a teleporter jumps, how
// often a hit cheater claims a hit on the farthest player.
constexpr double kSpeedHackFactor = 3;
constexpr double kTeleportMetres = 8;
constexpr std::uint64_t kTeleportEveryTicks = 40;
constexpr std::uint64_t kFakeHitEveryTicks = 10;
// Honest players claim a hit every second on the nearest player this much inside the reach, so
// that the judges' slightly different views never reject an honest hit.
constexpr std::uint64_t kHitEveryTicks = 20;
constexpr double kHonestHitMargin = 0.5;
// A hit is judged only from states at most this many ticks older than it: extrapolating a
// turning avatar (24 m/s^2) by 2 ticks errs by 0.12 m, well inside the honest margin.
constexpr std::uint64_t kHitJudgeMaxAgeTicks = 2;
// Correction: a rejected player's states that are plausible among themselves for 1 s re-anchor
// its judge on them, so a teleporter is shown where it now is, not frozen where it was.
constexpr std::uint64_t kProbationTicks = 20;
// Voting among peers (topologies/vote_tally.h). A peer holds a player caught lying for 2 s
// after the last lie it caught; it sends its verdict twice a second while it holds one against
// anyone, and once more when it no longer does (an honest game sends no votes). A vote counts
// for three vote periods after its tick, so one or two lost votes change nothing and a lost
// withdrawal lapses by itself. A vote stamped more than half a second ahead of the receiver's
// tick is refused: it would count long after its time.
constexpr std::uint64_t kVerdictTicks = 40;
constexpr std::uint64_t kVoteEveryTicks = 10;
constexpr std::uint64_t kVoteTtlTicks = 3 * kVoteEveryTicks;
constexpr std::uint64_t kVoteAheadTicks = 10;
// An equivocating peer shows its teleports to the lowest-numbered 3/5 of the others (9 of 15:
// more than the 8 votes that exclude it) and the truth to the rest, who never catch it
// themselves and exclude it on the others' word.
constexpr double kEquivocateShare = 0.6;

/// Wall-clock time: the start time and the logged events are compared across processes.
inline std::int64_t realtimeNs() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace zonesim::topo::rules
