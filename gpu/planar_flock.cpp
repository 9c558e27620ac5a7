#include "gpu/planar_flock.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gpu/cl_error.h"
#include "gpu/cl_runtime.h"
#include "gpu/default_runtime.h"

namespace zonesim::gpu {
namespace {

// Grids with more cells than this (and than four per entry) get larger cells: a sparse zone
// would otherwise spend its step clearing empty cell ranges.
constexpr std::size_t kMinCellBudget = std::size_t(1) << 16;

cl_float4 float4(double x, double y, double z, double w) {
  return {{cl_float(x), cl_float(y), cl_float(z), cl_float(w)}};
}

void requirePositive(double value, const char* name) {
  if (!std::isfinite(value) || !(value > 0.0))
    throw std::invalid_argument(std::string("planar flock ") + name +
                                " must be > 0 and finite, not " + std::to_string(value));
}

}  // namespace

/// The device side: the kernel, buffers grown to the largest step seen, host staging.
struct PlanarFlock::Device {
  Device(const PlanarFlockParams& p, std::shared_ptr<const ClRuntime> rt)
      : params(p),
        runtime(std::move(rt)),
        program(runtime->buildEmbeddedProgram("planar_flock")),
        step_kernel(program.createKernel("planar_step")) {}
  ~Device() {
    // No throwing from a destructor: a failed finish has nothing left to protect.
    clFinish(runtime->queue());
  }

  void reserve(std::size_t total, std::size_t owned, std::size_t cells);
  void step(std::span<const std::uint64_t> ids, std::span<Vec2d> pos, std::span<Vec2d> vel,
            const PlanarAgents& ghosts, double dt, const PlanarControls& controls);

  PlanarFlockParams params;
  std::shared_ptr<const ClRuntime> runtime;
  ClProgram program;
  ClKernel step_kernel;
  std::size_t total_capacity = 0, owned_capacity = 0, cell_capacity = 0;
  ClBuffer state, ids_buffer, slots, starts, control, vel_out;
  std::vector<cl_float4> host_state, host_control;
  std::vector<cl_ulong> host_ids;
  std::vector<cl_uint2> host_slots;
  std::vector<cl_uint> host_starts, cell_of, next_slot;
  std::vector<cl_float2> host_vel;
};

void PlanarFlock::Device::reserve(std::size_t total, std::size_t owned, std::size_t cell_count) {
  if (total > total_capacity) {
    total_capacity = total;
    state = runtime->createBuffer(total * sizeof(cl_float4), CL_MEM_READ_ONLY);
    ids_buffer = runtime->createBuffer(total * sizeof(cl_ulong), CL_MEM_READ_ONLY);
    slots = runtime->createBuffer(total * sizeof(cl_uint2), CL_MEM_READ_ONLY);
  }
  if (owned > owned_capacity) {
    owned_capacity = owned;
    control = runtime->createBuffer(owned * sizeof(cl_float4), CL_MEM_READ_ONLY);
    vel_out = runtime->createBuffer(owned * sizeof(cl_float2), CL_MEM_WRITE_ONLY);
  }
  if (cell_count + 1 > cell_capacity) {
    cell_capacity = cell_count + 1;
    starts = runtime->createBuffer(cell_capacity * sizeof(cl_uint), CL_MEM_READ_ONLY);
  }
}

void PlanarFlock::Device::step(std::span<const std::uint64_t> ids, std::span<Vec2d> pos,
                               std::span<Vec2d> vel, const PlanarAgents& ghosts, double dt,
                               const PlanarControls& controls) {
  const std::size_t owned = ids.size();
  const std::size_t total = owned + ghosts.ids.size();
  auto entryPos = [&](std::size_t i) { return i < owned ? pos[i] : ghosts.pos[i - owned]; };

  // The grid covers every entry: cells of the neighbour radius on global coordinates
  // (floor(x / cell), as the crowd flock's grid), grown if there would be too many.
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x;
  double hi_x = -lo_x, hi_y = -lo_x;
  for (std::size_t i = 0; i < total; ++i) {
    Vec2d p = entryPos(i);
    lo_x = std::min(lo_x, p.x);
    lo_y = std::min(lo_y, p.y);
    hi_x = std::max(hi_x, p.x);
    hi_y = std::max(hi_y, p.y);
  }
  if (!std::isfinite(lo_x) || !std::isfinite(lo_y) || !std::isfinite(hi_x) || !std::isfinite(hi_y))
    throw std::invalid_argument("planar flock: a position is not finite");
  const std::size_t budget = std::max(kMinCellBudget, 4 * total);
  double cell = params.neighbour_radius;
  double gx0 = 0, gy0 = 0, nx = 1, ny = 1;
  for (;;) {
    gx0 = std::floor(lo_x / cell);
    gy0 = std::floor(lo_y / cell);
    nx = std::floor(hi_x / cell) - gx0 + 1;
    ny = std::floor(hi_y / cell) - gy0 + 1;
    if (nx * ny <= double(budget)) break;
    cell *= 2;
  }
  const auto cx_count = cl_uint(nx), cy_count = cl_uint(ny);
  const std::size_t cell_count = std::size_t(cx_count) * cy_count;
  reserve(total, owned, cell_count);

  // Counting sort into cells, then each cell by id: the kernel visits neighbours in cell rows,
  // then ids, and positions go up relative to their global cell's corner, so every sum is the
  // same whichever rank owns the agent and whatever else its grid holds (on one device).
  cell_of.resize(total);
  host_starts.assign(cell_count + 1, 0);
  for (std::size_t i = 0; i < total; ++i) {
    Vec2d p = entryPos(i);
    double fx = std::clamp(std::floor(p.x / cell) - gx0, 0.0, nx - 1);
    double fy = std::clamp(std::floor(p.y / cell) - gy0, 0.0, ny - 1);
    cell_of[i] = cl_uint(fy) * cx_count + cl_uint(fx);
    ++host_starts[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < cell_count; ++c) host_starts[c + 1] += host_starts[c];
  host_state.resize(total);
  host_ids.resize(total);
  host_slots.resize(total);
  next_slot.assign(host_starts.begin(), host_starts.end() - 1);
  for (std::size_t i = 0; i < total; ++i) {
    const cl_uint c = cell_of[i];
    const cl_uint k = next_slot[c]++;
    Vec2d p = entryPos(i);
    Vec2d v = i < owned ? vel[i] : ghosts.vel[i - owned];
    double corner_x = (gx0 + double(c % cx_count)) * cell;
    double corner_y = (gy0 + double(c / cx_count)) * cell;
    host_state[k] = float4(p.x - corner_x, p.y - corner_y, v.x, v.y);
    host_ids[k] = i < owned ? ids[i] : ghosts.ids[i - owned];
    host_slots[k] = {{cl_uint(i), c}};
  }
  // A cell holds a few entries: insertion sort by id.
  for (std::size_t c = 0; c < cell_count; ++c) {
    for (cl_uint k = host_starts[c] + 1; k < host_starts[c + 1]; ++k) {
      for (cl_uint j = k; j > host_starts[c] && host_ids[j - 1] > host_ids[j]; --j) {
        std::swap(host_ids[j - 1], host_ids[j]);
        std::swap(host_state[j - 1], host_state[j]);
        std::swap(host_slots[j - 1], host_slots[j]);
      }
    }
  }
  cl_uint mode = 0;
  if (!controls.goal.empty()) mode |= 1u;
  if (!controls.dt.empty()) mode |= 2u;
  if (mode != 0) {
    host_control.resize(owned);
    for (std::size_t i = 0; i < owned; ++i) {
      Vec2d g = controls.goal.empty() ? Vec2d{} : controls.goal[i];
      double h = controls.dt.empty() ? dt : controls.dt[i];
      bool steer = controls.steer.empty() || controls.steer[i] != 0;
      host_control[i] = float4(g.x, g.y, h, steer ? 1.0 : 0.0);
    }
  }

  cl_command_queue queue = runtime->queue();
  // Staging arrays stay untouched until the blocking read below, so the writes need not block.
  auto write = [&](const ClBuffer& buffer, std::size_t bytes, const void* data) {
    checkCl(
        clEnqueueWriteBuffer(queue, buffer.get(), CL_FALSE, 0, bytes, data, 0, nullptr, nullptr),
        "clEnqueueWriteBuffer");
  };
  write(state, total * sizeof(cl_float4), host_state.data());
  write(ids_buffer, total * sizeof(cl_ulong), host_ids.data());
  write(slots, total * sizeof(cl_uint2), host_slots.data());
  write(starts, (cell_count + 1) * sizeof(cl_uint), host_starts.data());
  if (mode != 0) write(control, owned * sizeof(cl_float4), host_control.data());

  step_kernel.setArg(0, state.get());
  step_kernel.setArg(1, ids_buffer.get());
  step_kernel.setArg(2, slots.get());
  step_kernel.setArg(3, starts.get());
  step_kernel.setArg(4, control.get());
  step_kernel.setArg(5, cl_float(cell));
  step_kernel.setArg(6, cl_uint2{{cx_count, cy_count}});
  step_kernel.setArg(7, cl_uint(total));
  step_kernel.setArg(8, cl_uint(owned));
  step_kernel.setArg(9, float4(params.neighbour_radius, params.separation_radius, params.max_speed,
                               params.max_force));
  step_kernel.setArg(10, float4(params.separation_weight, params.alignment_weight,
                                params.cohesion_weight, params.goal_weight));
  step_kernel.setArg(11, cl_float(dt));
  step_kernel.setArg(12, mode);
  step_kernel.setArg(13, vel_out.get());
  step_kernel.enqueue(queue, total);

  host_vel.resize(owned);
  checkCl(clEnqueueReadBuffer(queue, vel_out.get(), CL_TRUE, 0, owned * sizeof(cl_float2),
                              host_vel.data(), 0, nullptr, nullptr),
          "clEnqueueReadBuffer");
  // Positions in double on the host, with the velocity the agent ends the step with (the
  // crowd flock's semi-implicit Euler step).
  for (std::size_t i = 0; i < owned; ++i) {
    double h = controls.dt.empty() ? dt : controls.dt[i];
    if (!(h > 0.0)) continue;
    Vec2d v{host_vel[i].s[0], host_vel[i].s[1]};
    vel[i] = v;
    pos[i] = {pos[i].x + v.x * h, pos[i].y + v.y * h};
  }
}

PlanarFlock::PlanarFlock(const PlanarFlockParams& params, std::shared_ptr<ClRuntime> runtime) {
  requirePositive(params.neighbour_radius, "neighbour radius");
  if (!std::isfinite(params.separation_radius) || params.separation_radius < 0)
    throw std::invalid_argument("planar flock separation radius must be >= 0 and finite");
  if (!runtime) runtime = defaultRuntime();
  device_ = std::make_unique<Device>(params, std::move(runtime));
}

PlanarFlock::~PlanarFlock() = default;
PlanarFlock::PlanarFlock(PlanarFlock&&) noexcept = default;
PlanarFlock& PlanarFlock::operator=(PlanarFlock&&) noexcept = default;

void PlanarFlock::step(std::span<const std::uint64_t> ids, std::span<Vec2d> pos,
                       std::span<Vec2d> vel, const PlanarAgents& ghosts, double dt,
                       const PlanarControls& controls) {
  const std::size_t n = ids.size();
  if (pos.size() != n || vel.size() != n || ghosts.pos.size() != ghosts.ids.size() ||
      ghosts.vel.size() != ghosts.ids.size() ||
      (!controls.goal.empty() && controls.goal.size() != n) ||
      (!controls.dt.empty() && controls.dt.size() != n) ||
      (!controls.steer.empty() && controls.steer.size() != n) ||
      (controls.dt.empty() != controls.steer.empty()))
    throw std::invalid_argument("PlanarFlock::step: array sizes differ");
  if (n + ghosts.ids.size() > (std::size_t(1) << 30))
    throw std::invalid_argument("planar flock of more than 2^30 agents and ghosts");
  if (n == 0) return;
  device_->step(ids, pos, vel, ghosts, dt, controls);
}

const PlanarFlockParams& PlanarFlock::params() const {
  return device_->params;
}

std::string PlanarFlock::deviceDescription() const {
  return device_->runtime->description();
}

}  // namespace zonesim::gpu
