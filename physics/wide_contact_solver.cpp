#include "physics/wide_contact_solver.h"

#include <cstring>

#include "physics/solver_row.h"
#include "physics/wide_contact_block.h"

namespace zonesim::physics {

namespace {

// The soft spring of one sub-step in float.
wide::SoftLanes lanesOf(const Softness& s) {
  return {static_cast<float>(s.bias_rate), static_cast<float>(s.mass_scale),
          static_cast<float>(s.impulse_scale)};
}

void put(wide::Lanes* lanes, int lane, const Vec3& v) {
  for (int k = 0; k < 3; ++k) lanes[k][lane] = static_cast<float>(v[k]);
}

// xx yy zz xy xz yz of a symmetric inverse inertia.
void putSymmetric(wide::Lanes* lanes, int lane, const Eigen::Matrix3d& m) {
  const double parts[6] = {m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2)};
  for (int k = 0; k < 6; ++k) lanes[k][lane] = static_cast<float>(parts[k]);
}

}  // namespace

WideContactSolver::WideContactSolver() = default;
WideContactSolver::~WideContactSolver() = default;
WideContactSolver::WideContactSolver(const WideContactSolver&) = default;
WideContactSolver::WideContactSolver(WideContactSolver&&) noexcept = default;
WideContactSolver& WideContactSolver::operator=(const WideContactSolver&) = default;
WideContactSolver& WideContactSolver::operator=(WideContactSolver&&) noexcept = default;

void WideContactSolver::prepare(const BodyStorage& bodies, std::span<const BodyContact> contacts,
                                const SolverSettings& settings) {
  settings_ = settings;
  lanes_ = wide::supportedLanes(settings.wide_lanes);
  const std::size_t n = bodies.size();
  constraint_bodies_.resize(contacts.size());
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const BodyContact& bc = contacts[c];
    constraint_bodies_[c] = {bc.a, bc.b, bodies.inv_mass[bc.a] > 0.0, bodies.inv_mass[bc.b] > 0.0};
  }
  colouring_.build(constraint_bodies_, n);
  const std::span<const std::uint32_t> lanes = colouring_.lanes();
  blocks_.resize(colouring_.blockCount());
  // Padding lanes read the zero body and write the sink; all their rows stay zero.
  const auto zero_slot = static_cast<std::uint32_t>(n), sink_slot = zero_slot + 1;
  any_restitution_ = false;
  for (std::size_t block = 0; block < blocks_.size(); ++block) {
    wide::BlockLanes& b = blocks_[block];
    std::memset(static_cast<void*>(&b), 0, sizeof b);
    for (int lane = 0; lane < kBlockLanes; ++lane) {
      const std::uint32_t c = lanes[block * kBlockLanes + lane];
      if (c == kEmptyLane) {
        b.read_a[lane] = b.read_b[lane] = zero_slot;
        b.write_a[lane] = b.write_b[lane] = sink_slot;
        continue;
      }
      const BodyContact& bc = contacts[c];
      const ConstraintBodies& k = constraint_bodies_[c];
      b.read_a[lane] = bc.a;
      b.read_b[lane] = bc.b;
      b.write_a[lane] = k.a_moves ? bc.a : sink_slot;
      b.write_b[lane] = k.b_moves ? bc.b : sink_slot;
      const double ma = bodies.inv_mass[bc.a], mb = bodies.inv_mass[bc.b];
      b.inv_mass_a[lane] = static_cast<float>(ma);
      b.inv_mass_b[lane] = static_cast<float>(mb);
      const Eigen::Matrix3d& ia = bodies.inv_inertia_world[bc.a];
      const Eigen::Matrix3d& ib = bodies.inv_inertia_world[bc.b];
      putSymmetric(b.inv_inertia_a, lane, ia);
      putSymmetric(b.inv_inertia_b, lane, ib);
      const Vec3 normal = bc.manifold.normal;
      const Vec3 t0 = solver_row::orthogonal(normal);
      const Vec3 t1 = normal.cross(t0);
      put(b.normal, lane, normal);
      put(b.tangent[0], lane, t0);
      put(b.tangent[1], lane, t1);
      b.friction[lane] = static_cast<float>(bc.friction);
      b.restitution[lane] = static_cast<float>(bc.restitution);
      any_restitution_ |= bc.restitution != 0.0;
      b.fixed[lane] = (ma == 0.0 || mb == 0.0) ? 1.0f : 0.0f;
      b.points = std::max(b.points, bc.manifold.count);
      const Vec3& va = bodies.linear_velocity[bc.a];
      const Vec3& wa = bodies.angular_velocity[bc.a];
      const Vec3& vb = bodies.linear_velocity[bc.b];
      const Vec3& wb = bodies.angular_velocity[bc.b];
      for (int i = 0; i < bc.manifold.count; ++i) {
        const ContactPoint& cp = bc.manifold.points[i];
        wide::PointLanes& p = b.point[i];
        const Vec3 ra = cp.position - bodies.position[bc.a];
        const Vec3 rb = cp.position - bodies.position[bc.b];
        // Effective mass along a tangent d: the rows are built in double, then rounded once.
        const auto mass = [&](const Vec3& d) {
          const Vec3 ca = ra.cross(d), cb = rb.cross(d);
          const double inv = ma + mb + ca.dot(ia * ca) + cb.dot(ib * cb);
          return inv > 0.0 ? 1.0 / inv : 0.0;
        };
        const Vec3 ca = ra.cross(normal), cb = rb.cross(normal);
        const Vec3 ia_ca = ia * ca, ib_cb = ib * cb;
        put(p.ca, lane, ca);
        put(p.cb, lane, cb);
        put(p.ia_ca, lane, ia_ca);
        put(p.ib_cb, lane, ib_cb);
        put(p.ra, lane, ra);
        put(p.rb, lane, rb);
        const double normal_inv = ma + mb + ca.dot(ia_ca) + cb.dot(ib_cb);
        p.normal_mass[lane] = static_cast<float>(normal_inv > 0.0 ? 1.0 / normal_inv : 0.0);
        p.tangent_mass[0][lane] = static_cast<float>(mass(t0));
        p.tangent_mass[1][lane] = static_cast<float>(mass(t1));
        p.separation[lane] = static_cast<float>(-cp.depth);
        p.approach[lane] = static_cast<float>(normal.dot(vb - va) + cb.dot(wb) - ca.dot(wa));
        if (settings.warm_starting) {
          p.normal_impulse[lane] = static_cast<float>(bc.impulse[i][0]);
          p.tangent_impulse[0][lane] = static_cast<float>(bc.impulse[i][1]);
          p.tangent_impulse[1][lane] = static_cast<float>(bc.impulse[i][2]);
        }
      }
    }
  }
}

void WideContactSolver::warmStart(SolverBodies& state) {
  wide::warmStart(lanes_, blocks_, state);
}

void WideContactSolver::solve(SolverBodies& state, const Softness& soft, const Softness& soft_fixed,
                              bool use_bias, double inv_h) {
  const wide::SoftPass pass{lanesOf(soft),
                            lanesOf(soft_fixed),
                            use_bias,
                            static_cast<float>(inv_h),
                            static_cast<float>(settings_.max_push_velocity),
                            any_restitution_};
  wide::solve(lanes_, blocks_, state, pass);
}

void WideContactSolver::applyRestitution(SolverBodies& state) {
  // Every lane's update would be masked off: skip the pass (the pyramids have none).
  if (!any_restitution_) return;
  wide::restitute(lanes_, blocks_, state, static_cast<float>(settings_.restitution_threshold));
}

void WideContactSolver::storeImpulses(std::span<BodyContact> contacts) const {
  const std::span<const std::uint32_t> lanes = colouring_.lanes();
  for (std::size_t block = 0; block < blocks_.size(); ++block) {
    const wide::BlockLanes& b = blocks_[block];
    for (int lane = 0; lane < kBlockLanes; ++lane) {
      const std::uint32_t c = lanes[block * kBlockLanes + lane];
      if (c == kEmptyLane) continue;
      BodyContact& bc = contacts[c];
      for (int i = 0; i < bc.manifold.count; ++i) {
        const wide::PointLanes& p = b.point[i];
        bc.impulse[i] = {p.normal_impulse[lane], p.tangent_impulse[0][lane],
                         p.tangent_impulse[1][lane]};
      }
    }
  }
}

}  // namespace zonesim::physics
