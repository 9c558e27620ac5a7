#pragma once
// The fleet summary's figures per player kind (walkers, riders, flyers): how many, what they
// received and how far off what they were shown was, so a benchmark tells a flyer's wide view
// apart from a walker's.

#include <memory>
#include <string>
#include <vector>

#include "clients/sim_player.h"

namespace zonesim::clients {

/// {"walker": {...}, ...}, one object per kind that has players, in id order: players,
/// kbps_in_p50 / kbps_in_max (each player's mean kbit/s received over duration_s),
/// dr_error_m_p50 / _p99 / _max (the corrections its players saw, merged), and
/// visible_entities_mean (the mean of the players' time-averaged views).
std::string kindsSummaryJson(const std::vector<std::unique_ptr<SimPlayer>>& players,
                             double duration_s);

}  // namespace zonesim::clients
