#pragma once
// Where particles are integrated, and zone_node's --gpu on|off|auto decision.

#include <cstddef>
#include <string_view>

namespace zonesim::gpu {

/// Where a ParticleSystem runs: the double-precision CPU reference or an OpenCL device (float).
enum class Backend { Cpu, OpenCl };

/// "cpu" or "opencl".
const char* backendName(Backend backend);

/// The --gpu setting.
enum class GpuMode { Off, On, Auto };

/// Parses "on", "off" or "auto"; throws std::invalid_argument naming the bad value otherwise.
GpuMode parseGpuMode(std::string_view text);

/// Below this many particles auto stays on the CPU: there a step costs less than an OpenCL
/// launch plus its synchronisation. Measured here (PoCL 3.1 on the shared 2-core Xeon,
/// RelWithDebInfo, dt = 1/60 s, drag and bounces on, best of 9 runs of 100 steps, two sessions;
/// ms per step):
///   particles   cpu (double)   opencl step+sync   opencl step+read-back of positions
///       1,000      0.005            0.019-0.020         0.025
///       4,000      0.019-0.020      0.018-0.028         0.06-0.07
///       8,000      0.040            0.028-0.031         0.062-0.065
///      10,000      0.045-0.060      0.035               0.063-0.078
///     100,000      0.53-0.91        0.26-0.29           0.59-0.61
///   1,000,000      5.3-5.9          2.6-3.3             10.3-10.5
/// The step+sync curves cross between 4,000 and 8,000. This assumes positions are read back
/// only when needed (metrics), not every tick; reading every tick moves the crossing to about
/// 15,000. No GPU was available to measure; its launch and sync cost is also tens of
/// microseconds, so the same N is used until a GPU measurement says otherwise.
inline constexpr std::size_t kAutoGpuThreshold = 8'000;

/// Off gives Cpu; On gives OpenCl; Auto gives OpenCl only for at least kAutoGpuThreshold
/// particles and only when an OpenCL device exists.
Backend chooseBackend(GpuMode mode, std::size_t particles, bool opencl_available);

/// The decision behind every chooseBackend: off is the CPU, on is OpenCL, auto is OpenCL only
/// when offloading pays (a device exists and the batch is past its threshold).
Backend chooseBackend(GpuMode mode, bool offload_pays);

/// True when an OpenCL GPU or CPU device can be opened (checked once per process).
bool openClAvailable();

/// chooseBackend(parseGpuMode(mode), particles, openClAvailable()), as zone_node calls it. It
/// keeps the fixed kAutoGpuThreshold rather than a probed one: every rank must make the same
/// choice, and a probe timed on each rank would not (gpu/offload_probe.h explains the probed
/// path and how ranks agree on it).
Backend selectBackend(std::string_view mode, std::size_t particles);

}  // namespace zonesim::gpu
