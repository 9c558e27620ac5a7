#include "physics/wide_contact_solver.h"

#include <algorithm>

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
  if (settings.wide_in_order) {
    colouring_.buildInOrder(constraint_bodies_, n);
  } else {
    colouring_.build(constraint_bodies_, n);
  }
  const std::span<const std::uint32_t> lanes = colouring_.lanes();
  blocks_.resize(colouring_.blockCount());
  // Padding lanes read the zero body and write the sink; all their rows stay zero.
  const auto zero_slot = static_cast<std::uint32_t>(n), sink_slot = zero_slot + 1;
  any_restitution_ = false;
  const bool warm = settings.warm_starting;
  for (std::size_t block = 0; block < blocks_.size(); ++block) {
    wide::BlockLanes& b = blocks_[block];
    const std::uint32_t* lane_of = lanes.data() + block * kBlockLanes;
    // Every field a pass reads is written here or in buildRows, lane by lane (an empty lane and
    // a lane's unused points get zeros), so the block needs no clearing first.
    b.points = 0;
    for (int lane = 0; lane < kBlockLanes; ++lane) {
      const std::uint32_t c = lane_of[lane];
      if (c == kEmptyLane) {
        b.read_a[lane] = b.read_b[lane] = zero_slot;
        b.write_a[lane] = b.write_b[lane] = sink_slot;
        b.inv_mass_a[lane] = b.inv_mass_b[lane] = 0.0f;
        put(b.normal, lane, Vec3::Zero());
        put(b.tangent[0], lane, Vec3::Zero());
        put(b.tangent[1], lane, Vec3::Zero());
        for (int k = 0; k < 6; ++k) b.inv_inertia_a[k][lane] = b.inv_inertia_b[k][lane] = 0.0f;
        b.friction[lane] = b.restitution[lane] = b.fixed[lane] = b.point_count[lane] = 0.0f;
        continue;
      }
      const BodyContact& bc = contacts[c];
      const double ma = bodies.inv_mass[bc.a], mb = bodies.inv_mass[bc.b];
      b.read_a[lane] = bc.a;
      b.read_b[lane] = bc.b;
      // As constraint_bodies_[c] says, without reading it again.
      b.write_a[lane] = ma > 0.0 ? bc.a : sink_slot;
      b.write_b[lane] = mb > 0.0 ? bc.b : sink_slot;
      b.inv_mass_a[lane] = static_cast<float>(ma);
      b.inv_mass_b[lane] = static_cast<float>(mb);
      putSymmetric(b.inv_inertia_a, lane, bodies.inv_inertia_world[bc.a]);
      putSymmetric(b.inv_inertia_b, lane, bodies.inv_inertia_world[bc.b]);
      const Vec3 normal = bc.manifold.normal;
      const Vec3 t0 = solver_row::orthogonal(normal);
      put(b.normal, lane, normal);
      put(b.tangent[0], lane, t0);
      put(b.tangent[1], lane, normal.cross(t0));
      b.friction[lane] = static_cast<float>(bc.friction);
      b.restitution[lane] = static_cast<float>(bc.restitution);
      any_restitution_ |= bc.restitution != 0.0;
      b.fixed[lane] = (ma == 0.0 || mb == 0.0) ? 1.0f : 0.0f;
      b.point_count[lane] = static_cast<float>(bc.manifold.count);
      b.points = std::max(b.points, bc.manifold.count);
    }
    for (int lane = 0; lane < kBlockLanes; ++lane) {
      const std::uint32_t c = lane_of[lane];
      const int count = c == kEmptyLane ? 0 : contacts[c].manifold.count;
      for (int i = count; i < b.points; ++i) {
        wide::PointLanes& p = b.point[i];
        put(p.ra, lane, Vec3::Zero());
        put(p.rb, lane, Vec3::Zero());
        p.separation[lane] = p.normal_impulse[lane] = 0.0f;
        p.tangent_impulse[0][lane] = p.tangent_impulse[1][lane] = 0.0f;
      }
      if (count == 0) continue;
      const BodyContact& bc = contacts[c];
      const Vec3& xa = bodies.position[bc.a];
      const Vec3& xb = bodies.position[bc.b];
      for (int i = 0; i < count; ++i) {
        const ContactPoint& cp = bc.manifold.points[i];
        wide::PointLanes& p = b.point[i];
        const Vec3 ra = cp.position - xa, rb = cp.position - xb;
        put(p.ra, lane, ra);
        put(p.rb, lane, rb);
        p.separation[lane] = static_cast<float>(-cp.depth);
        p.normal_impulse[lane] = warm ? static_cast<float>(bc.impulse[i][0]) : 0.0f;
        p.tangent_impulse[0][lane] = warm ? static_cast<float>(bc.impulse[i][1]) : 0.0f;
        p.tangent_impulse[1][lane] = warm ? static_cast<float>(bc.impulse[i][2]) : 0.0f;
      }
    }
    wide::buildRows(lanes_, b);
  }
  bounces_.clear();
  if (any_restitution_) prepareBounces(bodies, contacts);
}

void WideContactSolver::prepareBounces(const BodyStorage& bodies,
                                       std::span<const BodyContact> contacts) {
  const std::span<const std::uint32_t> lanes = colouring_.lanes();
  bounces_.assign(blocks_.size(), wide::BounceLanes{});
  for (std::size_t block = 0; block < blocks_.size(); ++block) {
    for (int lane = 0; lane < kBlockLanes; ++lane) {
      const std::uint32_t c = lanes[block * kBlockLanes + lane];
      if (c == kEmptyLane || contacts[c].restitution == 0.0) continue;
      const BodyContact& bc = contacts[c];
      for (int i = 0; i < bc.manifold.count; ++i) {
        const ContactPoint& cp = bc.manifold.points[i];
        const Vec3 ra = cp.position - bodies.position[bc.a];
        const Vec3 rb = cp.position - bodies.position[bc.b];
        // The relative normal velocity of the anchors.
        bounces_[block].approach[i][lane] = static_cast<float>(bc.manifold.normal.dot(
            (bodies.linear_velocity[bc.b] + bodies.angular_velocity[bc.b].cross(rb)) -
            (bodies.linear_velocity[bc.a] + bodies.angular_velocity[bc.a].cross(ra))));
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
                            !use_bias || settings_.friction_in_biased_pass,
                            static_cast<float>(inv_h),
                            static_cast<float>(settings_.max_push_velocity)};
  wide::solve(lanes_, blocks_, bounces_, state, pass);
}

void WideContactSolver::applyRestitution(SolverBodies& state) {
  // Every lane's update would be masked off: skip the pass (the pyramids have none).
  if (!any_restitution_) return;
  wide::restitute(lanes_, blocks_, bounces_, state,
                  static_cast<float>(settings_.restitution_threshold));
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
