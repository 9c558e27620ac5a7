#pragma once
// Plain value types of the particle system's interface: no Eigen, no OpenCL, cheap to include.

#include <cstdint>

namespace zonesim::gpu {

/// A point or vector in world space (metres, y up; the ground plane is y = 0).
struct Vec3d {
  double x = 0;
  double y = 0;
  double z = 0;
};

/// Vector arithmetic for the double-precision CPU references.
constexpr Vec3d operator+(Vec3d a, Vec3d b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3d operator-(Vec3d a, Vec3d b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3d operator*(Vec3d a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
constexpr double dot(Vec3d a, Vec3d b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

/// One spray of particles: directions uniform over a cone around direction, all at one speed.
struct EmitSpec {
  Vec3d origin;                  ///< Where particles start; y must be >= 0 (above the ground).
  Vec3d direction{0, 1, 0};      ///< Cone axis; any non-zero length.
  double cone_half_angle = 0.5;  ///< Radians in [0, pi]: 0 is a jet along direction, pi a sphere.
  double speed = 1;              ///< Metres per second, >= 0.
  double lifetime = 1;           ///< Seconds, counted in whole microseconds (see ParticleLedger).
};

/// A static sphere that particles bounce off (a rock, a pillar top), with the step's restitution.
struct Sphere {
  Vec3d center;       ///< Centre in world space.
  double radius = 1;  ///< Metres, > 0.
};

/// Host-device traffic so far; the CPU backend reports zeros.
struct TransferStats {
  std::uint64_t writes = 0;         ///< Buffer writes (one per emit batch).
  std::uint64_t reads = 0;          ///< Buffer reads (only on read-back requests).
  std::uint64_t bytes_written = 0;  ///< Bytes sent to the device.
  std::uint64_t bytes_read = 0;     ///< Bytes read from the device.
  std::uint64_t launches = 0;       ///< Kernel launches.
};

}  // namespace zonesim::gpu
