// Flocking for gpu/cl_boids.cpp. The CPU reference in gpu/cpu_boids.cpp and gpu/boid_grid.cpp
// runs the same grid and rules in double, summing neighbours in the same order; keep them in
// step (tests/gpu compares them).
//
// Per step: boid_cells gives each boid its cell (padding entries get key 0xffffffff), sort.cl
// orders (cell, id) pairs, cell_bounds marks each cell's range in that order, and boid_step
// reads the old positions and velocities and writes the new ones into the other buffers, so no
// boid sees another's update within a step.

#pragma OPENCL FP_CONTRACT OFF

// floor((x - origin) / cell) clamped into [0, n - 1]; NaN goes to 0 as on the host.
inline uint cell_coordinate(float x, float origin, float cell, uint n) {
  float c = floor((x - origin) / cell);
  if (!(c > 0.0f)) return 0u;
  return c >= (float)(n - 1u) ? n - 1u : (uint)c;
}

// grid: origin xyz and cell edge; dims: nx, ny, nz and the boid count.
__kernel void boid_cells(__global const float4* pos, __global uint* keys, __global uint* vals,
                         float4 grid, uint4 dims) {
  uint i = get_global_id(0);
  vals[i] = i;
  if (i >= dims.w) {
    keys[i] = 0xffffffffu;
    return;
  }
  float4 p = pos[i];
  uint cx = cell_coordinate(p.x, grid.x, grid.w, dims.x);
  uint cy = cell_coordinate(p.y, grid.y, grid.w, dims.y);
  uint cz = cell_coordinate(p.z, grid.z, grid.w, dims.z);
  keys[i] = (cz * dims.y + cy) * dims.x + cx;
}

// Cells left out keep start = end = 0 from the fill before this launch: an empty range.
__kernel void cell_bounds(__global const uint* keys, uint count, __global uint* start,
                          __global uint* end) {
  uint i = get_global_id(0);
  if (i >= count) return;
  uint k = keys[i];
  if (i == 0u || keys[i - 1u] != k) start[k] = i;
  if (i + 1u == count || keys[i + 1u] != k) end[k] = i + 1u;
}

// Copies positions and velocities into grid order, so that a cell's boids sit together in
// memory for the neighbour loop (coalesced on a GPU, cache lines on a CPU).
__kernel void gather_boids(__global const float4* pos, __global const float4* vel,
                           __global const uint* order, uint count, __global float4* pos_sorted,
                           __global float4* vel_sorted) {
  uint k = get_global_id(0);
  if (k >= count) return;
  uint i = order[k];
  pos_sorted[k] = pos[i];
  vel_sorted[k] = vel[i];
}

// Separation pushes away from each neighbour with weight (r - dist) / r, which is continuous at
// the perception edge; alignment pulls toward the neighbours' mean velocity, cohesion toward
// their centre, and a boid outside the bounds is pulled back in. Speed ends in
// [min_speed, max_speed] (a boid at rest stays at rest: it has no direction to speed up in).
// weights: separation, alignment, cohesion, bounds. limits: radius, min speed, max speed, dt.
// Work item k steps the boid in grid slot k (neighbouring items share cells); pos_in and vel_in
// are in grid order, pos_out and vel_out in id order.
__kernel void boid_step(__global const float4* pos_in, __global const float4* vel_in,
                        __global const uint* order, __global const uint* start,
                        __global const uint* end, float4 grid, uint4 dims, float4 weights,
                        float4 limits, float4 lower, float4 upper, __global float4* pos_out,
                        __global float4* vel_out) {
  uint k = get_global_id(0);
  if (k >= dims.w) return;
  uint i = order[k];
  float3 xi = pos_in[k].xyz;
  float3 vi = vel_in[k].xyz;
  float r = limits.x;
  float r2 = r * r;
  uint cx = cell_coordinate(xi.x, grid.x, grid.w, dims.x);
  uint cy = cell_coordinate(xi.y, grid.y, grid.w, dims.y);
  uint cz = cell_coordinate(xi.z, grid.z, grid.w, dims.z);
  float3 separation = (float3)(0.0f);
  float3 offset_sum = (float3)(0.0f);
  float3 velocity_sum = (float3)(0.0f);
  uint count = 0u;
  uint z1 = cz + 1u < dims.z ? cz + 1u : cz;
  uint y1 = cy + 1u < dims.y ? cy + 1u : cy;
  uint x1 = cx + 1u < dims.x ? cx + 1u : cx;
  for (uint z = cz > 0u ? cz - 1u : 0u; z <= z1; ++z) {
    for (uint y = cy > 0u ? cy - 1u : 0u; y <= y1; ++y) {
      for (uint x = cx > 0u ? cx - 1u : 0u; x <= x1; ++x) {
        uint cell = (z * dims.y + y) * dims.x + x;
        uint stop = end[cell];
        for (uint m = start[cell]; m < stop; ++m) {
          if (m == k) continue;
          float3 d = pos_in[m].xyz - xi;
          float d2 = d.x * d.x + d.y * d.y + d.z * d.z;
          if (!(d2 < r2)) continue;
          ++count;
          offset_sum += d;
          velocity_sum += vel_in[m].xyz;
          if (d2 > 0.0f) {
            float dist = sqrt(d2);
            separation -= d * ((r - dist) / (r * dist));
          }
        }
      }
    }
  }
  float3 acc = (float3)(0.0f);
  if (count > 0u) {
    float inv = 1.0f / (float)count;
    acc = separation * weights.x + (velocity_sum * inv - vi) * weights.y +
          offset_sum * (inv * weights.z);
  }
  float3 inside = clamp(xi, lower.xyz, upper.xyz);
  acc += (inside - xi) * weights.w;
  float3 v = vi + acc * limits.w;
  float speed = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  if (speed > limits.z) {
    v *= limits.z / speed;
  } else if (speed < limits.y && speed > 0.0f) {
    v *= limits.y / speed;
  }
  vel_out[i] = (float4)(v, 0.0f);
  pos_out[i] = (float4)(xi + v * limits.w, 0.0f);
}
