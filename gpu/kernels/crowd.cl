// Batch integration of crowd agents for gpu/cl_crowd.cpp; gpu/crowd_batch.cpp runs the same
// step in double as the reference (tests/gpu compares them).

#pragma OPENCL FP_CONTRACT OFF

// Semi-implicit Euler toward a desired velocity with bounded acceleration:
//   dv = desired - v, shortened to at most max_acceleration * dt; v += dv; x += v dt.
// Velocities are updated first, so a position moves with the velocity it ends the step with.
__kernel void integrate_crowd(__global float4* pos, __global float4* vel,
                              __global const float4* desired, uint count, float dt,
                              float max_dv) {
  uint i = get_global_id(0);
  if (i >= count) return;
  float3 v = vel[i].xyz;
  float3 dv = desired[i].xyz - v;
  float len = sqrt(dv.x * dv.x + dv.y * dv.y + dv.z * dv.z);
  if (len > max_dv) dv *= max_dv / len;
  v += dv;
  vel[i] = (float4)(v, 0.0f);
  pos[i] = (float4)(pos[i].xyz + v * dt, 0.0f);
}
