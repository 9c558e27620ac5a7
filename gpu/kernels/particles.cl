// Particle integration for gpu/cl_particles.cpp. The CPU reference in gpu/cpu_particles.cpp
// runs the same scheme in double; keep the two in step (tests/gpu compares them).
//
// State is SoA, one float array per component, plus the remaining life in whole microseconds:
// an integer countdown is exact, so the host knows which slots are dead without reading back.
// A slot with life 0 is dead and is never touched again until the host re-emits into it.

// Contraction into fma would make results depend on the device; keep every product rounded.
#pragma OPENCL FP_CONTRACT OFF

typedef struct {
  uint slot;
  uint life_us;
  float px, py, pz;
  float vx, vy, vz;
} EmitRecord;

// Copies one upload batch into its (possibly scattered, recycled) slots.
__kernel void scatter_emitted(__global const EmitRecord* batch, uint count,
                              __global float* px, __global float* py, __global float* pz,
                              __global float* vx, __global float* vy, __global float* vz,
                              __global uint* life) {
  uint i = get_global_id(0);
  if (i >= count) return;
  EmitRecord r = batch[i];
  px[r.slot] = r.px;
  py[r.slot] = r.py;
  pz[r.slot] = r.pz;
  vx[r.slot] = r.vx;
  vy[r.slot] = r.vy;
  vz[r.slot] = r.vz;
  life[r.slot] = r.life_us;
}

// One semi-implicit Euler step: v += (g - drag v) dt, then x += v dt, with ground contact at
// y = 0 resolved at the time of impact inside the step:
//   f   = y / (y - y1)                    fraction of the step before contact (y1: no-contact y)
//   vc  = min(vy + ay f dt, 0)            vertical velocity at contact, never upward
//   out = -restitution vc, then gravity and drag for the rest of the step, (1 - f) dt
//   vy  = max(out, 0), y = vy (1 - f) dt  a bounce never ends below the plane or moving down
// This map is continuous in the state: a particle that rounding puts just above the plane
// bounces one step later and lands in the same place. A plain reflection (y = -e y, vy = -e vy)
// jumps by (1 + e) |g| dt in velocity there, so float and double runs would part for good.
__kernel void integrate_particles(__global float* px, __global float* py, __global float* pz,
                                  __global float* vx, __global float* vy, __global float* vz,
                                  __global uint* life, uint count, float dt, uint dt_us,
                                  float gx, float gy, float gz, float drag,
                                  float restitution) {
  uint i = get_global_id(0);
  if (i >= count) return;
  uint remaining = life[i];
  if (remaining == 0u) return;
  if (remaining <= dt_us) {
    life[i] = 0u;
    return;
  }
  life[i] = remaining - dt_us;

  float ux = vx[i] + (gx - drag * vx[i]) * dt;
  float uz = vz[i] + (gz - drag * vz[i]) * dt;
  px[i] += ux * dt;
  pz[i] += uz * dt;
  vx[i] = ux;
  vz[i] = uz;

  float y = py[i];
  float v = vy[i];
  float ay = gy - drag * v;
  float v1 = v + ay * dt;
  float y1 = y + v1 * dt;
  if (y1 >= 0.0f) {
    py[i] = y1;
    vy[i] = v1;
    return;
  }
  float f = y / (y - y1);
  float vc = fmin(v + ay * f * dt, 0.0f);
  float rest = (1.0f - f) * dt;
  float out = -restitution * vc;
  out = fmax(out + (gy - drag * out) * rest, 0.0f);
  py[i] = out * rest;
  vy[i] = out;
}
