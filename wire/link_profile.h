#pragma once
// One direction of a network link, as parameters: delay with jitter, Gilbert–Elliott loss,
// reordering, duplication, corruption and a bandwidth cap behind a drop-tail queue. A profile
// comes from a named preset (lan, wifi, 4g, congested, satellite; their sources are in
// link_profile.cpp and docs/network.md) or from a file of `key: value` lines; anything that
// cannot be applied is refused with a one-line error naming the key.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace zonesim::gateway {

/// How the delay varies around its base.
enum class JitterShape { None, Uniform, Normal, Pareto };

/// One direction of a link. Probabilities are per datagram.
struct LinkProfile {
  std::string name = "none";  ///< the preset or file it came from, for errors and summaries
  double delay_ms = 0;        ///< one-way base delay
  JitterShape jitter = JitterShape::None;
  /// Uniform: width of [0, w); normal: standard deviation (the delay is clamped at 0);
  /// pareto: mean of the Lomax tail added to the base.
  double jitter_ms = 0;
  double pareto_shape = 2.5;  ///< pareto tail index alpha (> 1, so the mean exists)
  /// Jitter alone never reorders (queues on one path are FIFO): a datagram leaves no earlier
  /// than the one before it. false lets it reorder, as netem's jitter does.
  bool keep_order = true;
  // Gilbert–Elliott: a good and a bad state, each with its own loss probability.
  double ge_p = 0;              ///< good -> bad, per datagram
  double ge_r = 1;              ///< bad -> good, per datagram: bad sojourns last 1/r on average
  double loss_good = 0;         ///< loss probability in the good state
  double loss_bad = 1;          ///< loss probability in the bad state
  double reorder = 0;           ///< fraction held back by reorder_gap_ms, which later ones overtake
  double reorder_gap_ms = 0;    ///< the extra hold of a reordered datagram
  double duplicate = 0;         ///< fraction delivered twice
  double corrupt = 0;           ///< fraction with one random bit flipped
  double rate_kbps = 0;         ///< bandwidth cap in kbit/s (0: none)
  std::size_t queue_bytes = 0;  ///< the drop-tail queue in front of the cap, bytes

  /// True if the profile changes anything.
  bool active() const;
  /// True if all it does is lose datagrams (no delay, reordering, copies or corruption).
  bool lossOnly() const;
  /// The stationary loss probability: (r loss_good + p loss_bad) / (p + r).
  double meanLoss() const;
};

/// Throws std::invalid_argument("KEY: why") for the first parameter out of range.
void validateLinkProfile(const LinkProfile& p);

/// The built-in presets' names, in order.
const std::vector<std::string>& linkPresetNames();
/// A built-in preset, or nullopt.
std::optional<LinkProfile> linkPreset(std::string_view name);

/// Parses `key: value` lines (`#` starts a comment). A `preset: NAME` line takes that preset
/// as the base for the keys that follow; `loss: P` is Bernoulli loss (loss_good P, no bad
/// state). Unknown keys, bad values and ranges throw std::invalid_argument naming origin and key.
LinkProfile parseLinkProfile(std::string_view text, const std::string& origin);
/// A preset name, or else the path of a profile file.
LinkProfile loadLinkProfile(const std::string& preset_or_path);

/// One profile of a fleet's mix and the share of players that get it.
struct LinkShare {
  LinkProfile profile;
  double share = 1;
};
/// Parses "lan:0.5,4g:0.5" (shares must sum to 1 within 1e-6; each item a preset or a file).
std::vector<LinkShare> parseLinkMix(const std::string& text);
/// Which share player index of count gets: the shares' cumulative intervals over (i + 0.5) / n,
/// so the counts match the shares as closely as whole players allow.
std::size_t linkShareOf(const std::vector<LinkShare>& mix, std::size_t index, std::size_t count);

}  // namespace zonesim::gateway
