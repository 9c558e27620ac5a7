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

// Sphere contact, after the ground: the step's path from x0 to x1 is swept against every sphere
// and the earliest entry point p (fraction t of the step) wins. There the normal velocity is
// reflected and scaled by restitution, and the particle travels the rest of the step, (1 - t) dt,
// with that velocity. A particle that ends a step just outside a sphere is hit at t = 0 in the
// next one, so float and double runs that disagree about the side stay within one step's
// gravity of each other. A particle that starts inside (emitted there) is pushed out to the
// surface along the radius. One sphere per step: a second contact waits for the next step.
// The response may not end below the ground plane.
void collide_spheres(float3 x0, float3* x1, float3* v, float dt, float restitution,
                     __global const float4* spheres, uint sphere_count) {
  float3 seg = *x1 - x0;
  float a = dot(seg, seg);
  float best_t = 2.0f;
  uint best = sphere_count;
  for (uint k = 0; k < sphere_count; ++k) {
    float3 c = spheres[k].xyz;
    float r = spheres[k].w;
    float3 d = x0 - c;
    float c0 = dot(d, d) - r * r;
    if (c0 < 0.0f) {
      float len = length(d);
      float3 n = len > 0.0f ? d / len : (float3)(0.0f, 1.0f, 0.0f);
      *x1 = c + n * r;
      float vn = dot(*v, n);
      if (vn < 0.0f) *v -= (1.0f + restitution) * vn * n;
      x1->y = fmax(x1->y, 0.0f);
      return;
    }
    float b = dot(d, seg);
    if (b >= 0.0f || a == 0.0f) continue;
    float disc = b * b - a * c0;
    if (disc < 0.0f) continue;
    float t = (-b - sqrt(disc)) / a;
    if (t <= 1.0f && t < best_t) {
      best_t = t;
      best = k;
    }
  }
  if (best == sphere_count) return;
  float3 p = x0 + seg * best_t;
  float3 n = (p - spheres[best].xyz) / spheres[best].w;
  float vn = dot(*v, n);
  if (vn < 0.0f) *v -= (1.0f + restitution) * vn * n;
  *x1 = p + *v * ((1.0f - best_t) * dt);
  x1->y = fmax(x1->y, 0.0f);
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
// Spheres come after the ground (collide_spheres).
__kernel void integrate_particles(__global float* px, __global float* py, __global float* pz,
                                  __global float* vx, __global float* vy, __global float* vz,
                                  __global uint* life, uint count, float dt, uint dt_us,
                                  float gx, float gy, float gz, float drag,
                                  float restitution, __global const float4* spheres,
                                  uint sphere_count) {
  uint i = get_global_id(0);
  if (i >= count) return;
  uint remaining = life[i];
  if (remaining == 0u) return;
  if (remaining <= dt_us) {
    life[i] = 0u;
    return;
  }
  life[i] = remaining - dt_us;

  float3 x0 = (float3)(px[i], py[i], pz[i]);
  float ux = vx[i] + (gx - drag * vx[i]) * dt;
  float uz = vz[i] + (gz - drag * vz[i]) * dt;
  float3 x1 = (float3)(x0.x + ux * dt, 0.0f, x0.z + uz * dt);
  float3 v1 = (float3)(ux, 0.0f, uz);

  float y = x0.y;
  float v = vy[i];
  float ay = gy - drag * v;
  v1.y = v + ay * dt;
  x1.y = y + v1.y * dt;
  if (x1.y < 0.0f) {
    float f = y / (y - x1.y);
    float vc = fmin(v + ay * f * dt, 0.0f);
    float rest = (1.0f - f) * dt;
    float out = -restitution * vc;
    out = fmax(out + (gy - drag * out) * rest, 0.0f);
    x1.y = out * rest;
    v1.y = out;
  }
  if (sphere_count > 0u) collide_spheres(x0, &x1, &v1, dt, restitution, spheres, sphere_count);
  px[i] = x1.x;
  py[i] = x1.y;
  pz[i] = x1.z;
  vx[i] = v1.x;
  vy[i] = v1.y;
  vz[i] = v1.z;
}
