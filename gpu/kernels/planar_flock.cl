// Flocking on the ground plane with read-only ghosts, for gpu/planar_flock.cpp: the rules of the
// crowd library's flock (crowd/flock.cpp) in float, which is the double reference the
// tests compare against (tests/zone_node/test_flock_backend.cpp). Keep the two in step.
//
// The host uploads owned agents and ghosts already in cell order (it passes over every entry
// anyway to convert it, and a counting sort there is O(n): on PoCL the device's bitonic sort
// cost as much as the steering itself), with each cell's range; planar_step then computes every
// owned agent's new velocity from the old state (a Jacobi update, as on the CPU), and the host
// moves positions with that velocity in double. Cells are at least the neighbour radius, so
// the 3 x 3 cells around an agent hold every neighbour.
//
// Cells are global (floor(x / cell)) and each cell's entries sorted by id, so the sums run in
// cell rows, then ids, over in-range neighbours only: the same on every rank (see docs/gpu.md).
// Each entry's position is relative to its cell's corner: offsets between neighbours are then
// (cell difference) * cell + (local difference), exact to a float ulp of the cell size wherever
// the zone lies, instead of a ulp of the world's extent.
// state: local x, y, then vx, vy, in cell order. slot: (index of the entry, its cell); indices
// below `owned` are owned agents, the rest ghosts (seen, never moved). starts: cells + 1
// prefix sums, cell c holds slots starts[c] .. starts[c + 1].

#pragma OPENCL FP_CONTRACT OFF

inline float2 clamp_length(float2 v, float max_length) {
  float l2 = v.x * v.x + v.y * v.y;
  if (l2 <= max_length * max_length) return v;
  return v * (max_length / sqrt(l2));
}

// radii: neighbour radius, separation radius, max speed, max force.
// weights: separation, alignment, cohesion, goal.
// control (when mode has bit 0 or 1): per owned agent goal velocity x, y, its dt, steer (0/1);
// mode bit 0: goals given, bit 1: per-agent dt and steer given (else dt and full steering).
// Work item k steps the agent in slot k (neighbouring items share cells); vel_out is in index
// order. An agent with dt <= 0 keeps its velocity (the host leaves it in place).
__kernel void planar_step(__global const float4* state, __global const ulong* ids,
                          __global const uint2* slot, __global const uint* starts,
                          __global const float4* control, float cell, uint2 dims, uint count,
                          uint owned, float4 radii, float4 weights, float dt, uint mode,
                          __global float2* vel_out) {
  uint k = get_global_id(0);
  if (k >= count) return;
  uint2 own = slot[k];
  uint i = own.x;
  if (i >= owned) return;  // a ghost: seen, never moved
  float2 p = state[k].xy;
  float2 v = state[k].zw;
  bool has_goal = (mode & 1u) != 0u;
  float4 c = (mode & 3u) != 0u ? control[i] : (float4)(0.0f, 0.0f, dt, 1.0f);
  if ((mode & 2u) == 0u) {
    c.z = dt;
    c.w = 1.0f;
  }
  if (!(c.z > 0.0f)) {
    vel_out[i] = v;
    return;
  }
  float2 goal_pull = has_goal ? (c.xy - v) * weights.w : (float2)(0.0f);
  float2 acc = (float2)(0.0f);
  if (c.w != 0.0f) {
    float nr2 = radii.x * radii.x;
    float sr = radii.y;
    float sr2 = sr * sr;
    ulong self = ids[k];
    uint cx = own.y % dims.x;
    uint cy = own.y / dims.x;
    uint x1 = cx + 1u < dims.x ? cx + 1u : cx;
    uint y1 = cy + 1u < dims.y ? cy + 1u : cy;
    float count_in = 0.0f;
    float2 vel_sum = (float2)(0.0f), rel_sum = (float2)(0.0f), sep = (float2)(0.0f);
    for (uint y = cy > 0u ? cy - 1u : 0u; y <= y1; ++y) {
      for (uint x = cx > 0u ? cx - 1u : 0u; x <= x1; ++x) {
        uint cell_index = y * dims.x + x;
        float2 corner = (float2)((float)((int)x - (int)cx), (float)((int)y - (int)cy)) * cell;
        uint stop = starts[cell_index + 1u];
        for (uint m = starts[cell_index]; m < stop; ++m) {
          if (m == k) continue;
          float4 o = state[m];
          float2 rel = corner + (o.xy - p);
          float d2 = rel.x * rel.x + rel.y * rel.y;
          if (d2 < nr2) {
            count_in += 1.0f;
            vel_sum += o.zw;
            rel_sum += rel;
          }
          if (d2 < sr2) {
            if (d2 > 1e-18f) {
              float d = sqrt(d2);
              // Away from the other, scaled by (sr / d - 1): zero at the radius.
              sep += rel * (-(sr / d - 1.0f) / d);
            } else {
              // Exact overlap: split along x by id, as the CPU flock does.
              sep.x += self < ids[m] ? -1e3f : 1e3f;
            }
          }
        }
      }
    }
    acc = sep * weights.x;
    if (count_in > 0.0f) {
      float inv = 1.0f / count_in;
      acc += (vel_sum * inv - v) * weights.y;
      acc += rel_sum * (inv * weights.z);
    }
    acc += goal_pull;
  } else {
    acc = goal_pull;
  }
  acc = clamp_length(acc, radii.w);
  vel_out[i] = clamp_length(v + acc * c.z, radii.z);
}
