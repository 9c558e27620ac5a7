#include "physics/world.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/timer.h"
#include "physics/compound.h"
#include "physics/manifold_order.h"
#include "physics/mass_properties.h"
#include "physics/narrowphase.h"
#include "physics/soft_joint_anchor.h"

namespace zonesim::physics {

namespace {
// A contact point within this distance (m) of last step's point inherits its impulses.
constexpr double kPreserveDistance = 0.02;
// A recycled pair's bodies turn at most this far (cosine of the angle: 11.5 degrees, as Box2D)
// since its manifold was computed: the kept normal is fixed in the world.
constexpr double kRecycleTurnCos = 0.98;
// Newton steps of the gyroscopic midpoint rule: the residual falls quadratically, and from the
// last step's spin 3 reach round-off at the spins a game sees (|w| dt < 1).
constexpr int kGyroscopicNewtonSteps = 3;
// The soft step's joint springs are held below this fraction of the sub-step rate.
constexpr double kJointRateFraction = 0.25;
// Key of an unordered body pair in World::ignored_pairs_.
std::uint64_t pairKey(BodyIndex a, BodyIndex b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}
}  // namespace

World::World(const WorldSettings& settings)
    : settings_(settings), broadphase_(settings.broadphase, 2.0, settings.broadphase_keep_margin) {}

BodyIndex World::addBody(const BodyDesc& desc) {
  if (!(desc.rolling_resistance >= 0.0) || !std::isfinite(desc.rolling_resistance)) {
    throw std::invalid_argument("rolling_resistance must be finite and >= 0");
  }
  // Projection derives velocities from corrected displacements and has no rows to bound.
  if (desc.rolling_resistance > 0.0 && settings_.solver.kind == SolverKind::Projection) {
    throw std::invalid_argument(
        "rolling_resistance needs a velocity solver; SolverKind::Projection has none");
  }
  if (desc.rolling_resistance > 0.0 && settings_.solver.kind == SolverKind::SoftStepWide) {
    throw std::invalid_argument(
        "rolling_resistance is not solved by SolverKind::SoftStepWide; use SoftStep");
  }
  if (desc.shape.type == ShapeType::Compound && desc.type == BodyType::Dynamic) {
    // A body turns about its origin: a compound off its centre of mass would turn wrongly.
    const MassProperties mp = computeMassProperties(desc.shape, desc.density);
    const double size = shapeBounds(desc.shape, Vec3::Zero(), Quat::Identity()).area();
    if (mp.centre.squaredNorm() > 1e-18 * size) {
      throw std::invalid_argument(
          "a dynamic compound's origin must be its parts' centre of mass, which lies at (" +
          std::to_string(mp.centre.x()) + ", " + std::to_string(mp.centre.y()) + ", " +
          std::to_string(mp.centre.z()) + "); build it with centreCompound()");
    }
  }
  const BodyIndex i = bodies_.add(desc);
  bounding_radius_.push_back(boundingRadius(desc.shape));
  islands_.resize(bodies_.size());
  lod_.resize(bodies_.size());
  return i;
}

void World::step(double dt) {
  profile_ = {};
  recycled_ = computed_ = 0;
  if (lod_.idle()) {
    stepAll(dt);
  } else {
    stepLevels(dt);
  }
  if (settings_.contact_events) events_.update(contacts_, sleeping_contacts_);
  ++steps_;
}

void World::stepLevels(double dt) {
  const std::size_t n = bodies_.size();
  const double longest = settings_.lod_longest_step;
  const int longest_period =
      longest > 0.0 ? std::max(1, static_cast<int>(std::floor(longest / dt * (1.0 + 1e-9)))) : 64;
  lod_.plan(bodies_, contacts_, joints_, rigid_joints_, islands_.asleepMask(), steps_,
            longest_period);
  stepped_.assign(n, 0);
  held_.assign(n, 0);
  // A lasting blast acts in every pass and is counted down once, by the tick's dt.
  const std::vector<Blast> blasts = forces_.blasts;
  const std::span<const int> ticks = lod_.passTicks();
  for (std::size_t p = 0; p < ticks.size(); ++p) {
    forces_.blasts = blasts;
    holdAllBut(static_cast<int>(p), ticks[p]);
    // A debt longer than the longest step (a period just cut, or an island just brought near)
    // is paid in equal steps that fit.
    const double length = dt * ticks[p];
    const int pieces =
        longest > 0.0 ? std::max(1, static_cast<int>(std::ceil(length / longest - 1e-9))) : 1;
    for (int piece = 0; piece < pieces; ++piece) stepAll(length / pieces);
    // Bodies woken by a touch in this pass stepped in it too.
    for (std::size_t i = 0; i < n; ++i)
      stepped_[i] |= bodies_.type[i] != BodyType::Static && !held_[i] && !islands_.asleep(i);
    releaseHeld();
  }
  forces_.blasts = blasts;
  for (Blast& blast : forces_.blasts) blast.remaining -= dt;
  std::erase_if(forces_.blasts, [](const Blast& b) { return b.remaining <= 1e-12; });
  lod_.finish(bodies_, stepped_, islands_.asleepMask());
}

void World::holdAllBut(int pass, int ticks) {
  const std::size_t n = bodies_.size();
  held_list_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const auto b = static_cast<BodyIndex>(i);
    if (bodies_.type[i] == BodyType::Static || islands_.asleep(i)) continue;
    if (lod_.passOf(b) == pass) {
      // Forces gathered over the ticks it was held act over the whole longer step: their
      // impulse is the sum of each tick's.
      if (ticks > 1) {
        bodies_.force[i] /= ticks;
        bodies_.torque[i] /= ticks;
      }
      continue;
    }
    held_[i] = 1;
    held_list_.push_back(b);
  }
  // Held bodies keep their state aside and stand as immovable, unmoving obstacles.
  const std::size_t h = held_list_.size();
  held_inv_mass_.resize(h);
  held_inv_inertia_local_.resize(h);
  held_inv_inertia_world_.resize(h);
  held_linear_velocity_.resize(h);
  held_angular_velocity_.resize(h);
  for (std::size_t k = 0; k < h; ++k) {
    const BodyIndex i = held_list_[k];
    held_inv_mass_[k] = std::exchange(bodies_.inv_mass[i], 0.0);
    held_inv_inertia_local_[k] = bodies_.inv_inertia_local[i];
    held_inv_inertia_world_[k] = bodies_.inv_inertia_world[i];
    bodies_.inv_inertia_local[i].setZero();
    bodies_.inv_inertia_world[i].setZero();
    held_linear_velocity_[k] = std::exchange(bodies_.linear_velocity[i], Vec3::Zero());
    held_angular_velocity_[k] = std::exchange(bodies_.angular_velocity[i], Vec3::Zero());
  }
  // The pass finds again every contact of a body it steps; the others keep their last ones
  // (warm starts for their own pass, and the islands of the next plan).
  held_contacts_.clear();
  for (const BodyContact& c : contacts_) {
    const bool a_steps = bodies_.type[c.a] != BodyType::Static && !still(c.a);
    const bool b_steps = bodies_.type[c.b] != BodyType::Static && !still(c.b);
    if (!a_steps && !b_steps) held_contacts_.push_back(c);
  }
}

void World::releaseHeld() {
  for (std::size_t k = 0; k < held_list_.size(); ++k) {
    const BodyIndex i = held_list_[k];
    held_[i] = 0;
    bodies_.inv_mass[i] = held_inv_mass_[k];
    bodies_.inv_inertia_local[i] = held_inv_inertia_local_[k];
    bodies_.inv_inertia_world[i] = held_inv_inertia_world_[k];
    bodies_.linear_velocity[i] = held_linear_velocity_[k];
    bodies_.angular_velocity[i] = held_angular_velocity_[k];
  }
  held_list_.clear();
  merged_contacts_.clear();
  std::merge(contacts_.begin(), contacts_.end(), held_contacts_.begin(), held_contacts_.end(),
             std::back_inserter(merged_contacts_),
             [](const BodyContact& x, const BodyContact& y) { return x < y; });
  contacts_.swap(merged_contacts_);
  held_contacts_.clear();  // their origins are no longer kept apart
}

void World::stepAll(double dt) {
  const int n = std::max(1, settings_.substeps);
  // A lasting blast wakes what it reaches (sleeping bodies are not integrated).
  for (const Blast& blast : forces_.blasts) {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if ((bodies_.position[i] - blast.centre).norm() < blast.radius) {
        islands_.wake(static_cast<BodyIndex>(i));
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    substep(dt / n);
    // Blasts act for whole substeps and are counted down; spent ones go.
    for (Blast& blast : forces_.blasts) blast.remaining -= dt / n;
    std::erase_if(forces_.blasts, [](const Blast& b) { return b.remaining <= 1e-12; });
  }
}

void World::applyExplosionImpulse(const Vec3& centre, double impulse, double radius,
                                  Falloff falloff) {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.type[i] != BodyType::Dynamic && bodies_.type[i] != BodyType::Particle) continue;
    const Vec3 d = bodies_.position[i] - centre;
    const double r = d.norm();
    if (r == 0.0 || r >= radius) continue;
    islands_.wake(static_cast<BodyIndex>(i));
    const double j = impulse * falloffFactor(falloff, r, radius);
    bodies_.linear_velocity[i] += (bodies_.inv_mass[i] * j / r) * d;
  }
}

void World::substep(double dt) {
  {
    ScopedTimer t(profile_.integrate);
    bodies_.updateWorldInertia();
    integrateForces(dt);
    // Checked before the solve too: a NaN velocity in a contact would reach its partner.
    quarantineNonFinite();
  }
  findContacts(dt);
  SolverSettings solver = settings_.solver;
  {
    ScopedTimer t(profile_.prepare);
    wakeTouched();
    warmStartFromPrevious();
    // A body resting on a surface falls just past the contact margin, then gathers this tick's
    // gravity too before the solver sees it: up to 2 g dt of approach, which must not count as
    // an impact, or a bouncy body hops for ever (at 30 Hz: 0.65 m/s, a 1.1 cm hop every 3
    // ticks).
    solver.restitution_threshold =
        std::max(solver.restitution_threshold, 2.5 * forces_.gravity.norm() * dt);
    const bool soft = settings_.solver.kind == SolverKind::SoftStep ||
                      settings_.solver.kind == SolverKind::SoftStepWide;
    if (settings_.solver.kind == SolverKind::SoftStepWide) {
      wide_solver_.prepare(bodies_, contacts_, solver);
    } else {
      solver_.prepare(bodies_, contacts_, solver, dt);
    }
    // Contacts and joints share the Gauss-Seidel iterations, so each sees the other's impulses.
    // (The soft step rebuilds its joints at every pass instead.)
    if (!soft) {
      joints_.prepare(bodies_, dt, settings_.joint_beta);
      rigid_joints_.prepare(bodies_, dt, settings_.joint_beta);
    }
  }
  {
    ScopedTimer t(profile_.solve);
    switch (settings_.solver.kind) {
      case SolverKind::SoftStep:
        solveSoftStep(dt);
        break;
      case SolverKind::SoftStepWide:
        solveSoftStepWide(dt);
        break;
      case SolverKind::Projection:
        solveProjection(dt);
        break;
      default:
        solveIterative(dt);
    }
  }
  {
    ScopedTimer t(profile_.integrate);
    quarantineNonFinite();
  }
  {
    ScopedTimer t(profile_.islands);
    if (settings_.sleep.enabled) islands_.update(bodies_, contacts_, settings_.sleep, dt);
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    // A held body keeps what was applied to it for the step it will take.
    if (!held_.empty() && held_[i]) continue;
    bodies_.force[i].setZero();
    bodies_.torque[i].setZero();
  }
}

void World::integrateForces(double dt) {
  const std::size_t n = bodies_.size();
  for (auto* buffer : {&x_start_, &v_start_, &x_force_, &v_force_}) buffer->resize(n);
  std::copy(bodies_.position.begin(), bodies_.position.end(), x_start_.begin());
  std::copy(bodies_.linear_velocity.begin(), bodies_.linear_velocity.end(), v_start_.begin());
  // The Verlet history is rebuilt every step: contacts change velocities, which a two-step
  // position recurrence cannot see.
  const LinearStateView view{x_start_, v_start_,     bodies_.inv_mass,
                             x_force_, v_force_,     bodies_.position_prev,
                             false,    bodies_.force};
  integrator_.step(settings_.integrator, forces_, view, dt);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyType type = bodies_.type[i];
    if (type == BodyType::Static) continue;
    if (still(static_cast<BodyIndex>(i))) {
      // Sleeping bodies hold still: gravity is balanced by contacts that are not solved.
      v_force_[i].setZero();
      x_force_[i] = x_start_[i];
      continue;
    }
    if (type == BodyType::Kinematic) {
      v_force_[i] = v_start_[i];
      x_force_[i] = x_start_[i] + dt * v_start_[i];
      continue;
    }
    // Damping as 1 / (1 + c dt): unconditionally stable, unlike 1 - c dt.
    v_force_[i] /= 1.0 + dt * bodies_.linear_damping[i];
    bodies_.linear_velocity[i] = v_force_[i];
    if (type == BodyType::Dynamic) {
      Vec3& w = bodies_.angular_velocity[i];
      w += dt * (bodies_.inv_inertia_world[i] * bodies_.torque[i]);
      if (settings_.gyroscopic) w = gyroscopicStep(i, w, dt);
      w /= 1.0 + dt * bodies_.angular_damping[i];
    }
  }
}

Vec3 World::gyroscopicStep(BodyIndex i, const Vec3& w, double dt) const {
  const Eigen::Matrix3d& inv_inertia = bodies_.inv_inertia_local[i];
  if (inv_inertia.isZero(0.0)) return w;
  // Euler's equations in the body frame, I dw/dt + w x I w = 0 (I constant there), by the
  // implicit midpoint rule: I (w1 - w0) + dt m x I m = 0 with m = (w0 + w1) / 2. It keeps
  // both of the motion's quadratic invariants, |I w| and w.I w, and is stable at any spin.
  // Newton on f(w1), whose Jacobian is I + dt/2 (skew(m) I - skew(I m)), from w1 = w0.
  const Quat& q = bodies_.orientation[i];
  const Eigen::Matrix3d inertia = inv_inertia.inverse();
  const auto skew = [](const Vec3& v) {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
  };
  const Vec3 w0 = q.conjugate() * w;
  Vec3 w1 = w0;
  for (int it = 0; it < kGyroscopicNewtonSteps; ++it) {
    const Vec3 m = 0.5 * (w0 + w1);
    const Vec3 im = inertia * m;
    const Vec3 f = inertia * (w1 - w0) + dt * m.cross(im);
    const Eigen::Matrix3d jacobian = inertia + 0.5 * dt * (skew(m) * inertia - skew(im));
    w1 -= jacobian.partialPivLu().solve(f);
  }
  return q * w1;
}

void World::findContacts(double dt) {
  {
    ScopedTimer t(profile_.broadphase);
    findPairs(dt);
  }
  ScopedTimer t(profile_.narrowphase);
  contactsOfPairs(dt);
}

void World::ignoreContactsBetween(BodyIndex a, BodyIndex b) {
  if (a >= bodies_.size() || b >= bodies_.size() || a == b) {
    throw std::invalid_argument("ignoreContactsBetween: bodies " + std::to_string(a) + " and " +
                                std::to_string(b) + " must be two distinct bodies of " +
                                std::to_string(bodies_.size()));
  }
  const std::uint64_t key = pairKey(a, b);
  const auto at = std::lower_bound(ignored_pairs_.begin(), ignored_pairs_.end(), key);
  if (at == ignored_pairs_.end() || *at != key) ignored_pairs_.insert(at, key);
}

bool World::contactIgnored(BodyIndex a, BodyIndex b) const {
  return !ignored_pairs_.empty() &&
         std::binary_search(ignored_pairs_.begin(), ignored_pairs_.end(), pairKey(a, b));
}

void World::findPairs(double dt) {
  const std::size_t n = bodies_.size();
  proxy_boxes_.clear();
  proxy_moving_.clear();
  proxy_body_.clear();
  planes_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (bodies_.shape[i].type == ShapeType::Plane) {
      planes_.push_back(static_cast<BodyIndex>(i));
      continue;
    }
    Aabb box = shapeBounds(bodies_.shape[i], bodies_.position[i], bodies_.orientation[i]);
    // Half the margin on each box makes up a pair's margin; the travel this step is added in
    // full, as the body may move that far in any direction.
    double grow = 0.5 * settings_.contact_margin;
    if (settings_.speculative) grow += bodies_.linear_velocity[i].norm() * dt;
    proxy_boxes_.push_back(box.expanded(grow));
    // Asleep or held counts as not moving: pairs of still and static bodies are never found.
    proxy_moving_.push_back(bodies_.type[i] != BodyType::Static && !still(BodyIndex(i)));
    proxy_body_.push_back(static_cast<BodyIndex>(i));
  }
  broadphase_.findPairs(proxy_boxes_, proxy_moving_, pairs_);
}

void World::contactsOfPairs(double dt) {
  const std::size_t n = bodies_.size();
  // Last step's contacts become the warm-start source; both buffers keep their capacity.
  previous_.swap(contacts_);
  contacts_.clear();
  previous_origins_.swap(origins_);
  origins_.clear();
  recycle_cursor_ = 0;
  carrySleepingContacts();
  for (const ProxyPair& pair : pairs_) {
    const BodyIndex a = proxy_body_[pair.first], b = proxy_body_[pair.second];
    if (contactIgnored(a, b)) continue;
    const double closing = (bodies_.linear_velocity[a] - bodies_.linear_velocity[b]).norm();
    addContact(a, b, settings_.contact_margin + (settings_.speculative ? closing * dt : 0.0));
  }
  for (BodyIndex plane : planes_) {
    for (std::size_t i = 0; i < n; ++i) {
      const auto b = static_cast<BodyIndex>(i);
      if (b == plane || bodies_.type[b] == BodyType::Static || still(b)) continue;
      if (contactIgnored(plane, b)) continue;
      const double speed = bodies_.linear_velocity[b].norm();
      addContact(std::min(plane, b), std::max(plane, b),
                 settings_.contact_margin + (settings_.speculative ? speed * dt : 0.0));
    }
  }
  // Pair order decides the Gauss-Seidel order: sort for determinism and warm-start lookup.
  // The broadphase's pairs come sorted (and proxies are in body order), so without planes the
  // list is already in order; checking is linear, moving ~350-byte contacts is not.
  const auto byPair = [](const BodyContact& x, const BodyContact& y) { return x < y; };
  if (!std::is_sorted(contacts_.begin(), contacts_.end(), byPair)) {
    std::sort(contacts_.begin(), contacts_.end(), byPair);
  }
  keepOrigins(sleeping_contacts_);
  keepOrigins(held_contacts_);
}

void World::keepOrigins(std::vector<BodyContact>& kept) {
  for (BodyContact& c : kept) {
    if (c.origin == kNoOrigin) continue;
    const ManifoldOrigin& origin = previous_origins_[c.origin];
    c.origin = static_cast<std::uint32_t>(origins_.size());
    origins_.push_back(origin);
  }
}

void World::addContact(BodyIndex a, BodyIndex b, double margin) {
  // Two immovable bodies exchange no impulses.
  if (bodies_.inv_mass[a] == 0.0 && bodies_.inv_mass[b] == 0.0) return;
  const Pose pa{bodies_.position[a], bodies_.orientation[a]};
  const Pose pb{bodies_.position[b], bodies_.orientation[b]};
  const ShapeType ta = bodies_.shape[a].type, tb = bodies_.shape[b].type;
  const bool compound = ta == ShapeType::Compound || tb == ShapeType::Compound;
  // Only pairs with a box pay for their narrowphase (clipping); spheres, capsules and planes
  // collide in fewer operations than the recycling test takes.
  const bool recycling = settings_.contact_recycle_distance > 0.0 && !compound &&
                         (ta == ShapeType::Box || tb == ShapeType::Box);
  if (recycling && recycleContact(a, b, pa, pb, margin)) return;
  const double friction = std::sqrt(bodies_.friction[a] * bodies_.friction[b]);
  const double restitution = std::max(bodies_.restitution[a], bodies_.restitution[b]);
  const double rolling = std::max(bodies_.rolling_resistance[a], bodies_.rolling_resistance[b]);
  // One contact per touching pair of pieces (a compound's parts, or the shape itself), in
  // piece order: the contact list stays sorted by (a, b, piece a, piece b). The broadphase
  // paired the whole bodies; a compound's pieces whose bounds lie farther apart than the
  // margin cannot touch and skip the narrowphase.
  forEachPiece(bodies_.shape[a], pa, [&](unsigned ka, const Shape& sa, const Pose& qa) {
    forEachPiece(bodies_.shape[b], pb, [&](unsigned kb, const Shape& sb, const Pose& qb) {
      if (compound && sa.type != ShapeType::Plane && sb.type != ShapeType::Plane &&
          !shapeBounds(sa, qa.position, qa.orientation)
               .expanded(margin)
               .overlaps(shapeBounds(sb, qb.position, qb.orientation)))
        return;
      BodyContact contact;
      contact.a = a;
      contact.b = b;
      contact.piece_a = static_cast<std::uint16_t>(ka);
      contact.piece_b = static_cast<std::uint16_t>(kb);
      if (!collideShapes(sa, qa, sb, qb, margin, contact.manifold)) return;
      if (contact.manifold.count == 0) return;
      sortDeepestFirst(contact.manifold, [](int) {});
      contact.friction = friction;
      contact.restitution = restitution;
      contact.rolling = rolling * std::max(rollingRadius(sa), rollingRadius(sb));
      if (recycling) {
        contact.origin = static_cast<std::uint32_t>(origins_.size());
        origins_.push_back(originOf(contact.manifold, pa, pb));
      }
      ++computed_;
      contacts_.push_back(contact);
    });
  });
}

bool World::recycleContact(BodyIndex a, BodyIndex b, const Pose& pa, const Pose& pb,
                           double margin) {
  const auto before = [](const BodyContact& c, std::pair<BodyIndex, BodyIndex> key) {
    return c.a < key.first || (c.a == key.first && c.b < key.second);
  };
  // Pairs come in order, so the cursor (past the last match) is usually the pair's place;
  // else search.
  const std::pair key{a, b};
  auto old = previous_.begin() + std::min(recycle_cursor_, previous_.size());
  const bool in_place = (old == previous_.end() || !before(*old, key)) &&
                        (old == previous_.begin() || before(*(old - 1), key));
  if (!in_place) old = std::lower_bound(previous_.begin(), previous_.end(), key, before);
  recycle_cursor_ = static_cast<std::size_t>(old - previous_.begin());
  if (old != previous_.end() && old->a == a && old->b == b) ++recycle_cursor_;
  if (old == previous_.end() || old->a != a || old->b != b || old->origin == kNoOrigin)
    return false;
  const ManifoldOrigin& origin = previous_origins_[old->origin];
  if (!turnedLittle(origin, pa, pb, kRecycleTurnCos)) return false;
  const double moved = relativeMotionBound(origin, pa, pb, bounding_radius_[a], bounding_radius_[b],
                                           settings_.contact_recycle_distance);
  if (moved >= settings_.contact_recycle_distance) return false;
  // Each manifold point pairs a point of each surface, so the shapes were at most the
  // shallowest gap apart, and are now at most that plus `moved`: still within the margin, so
  // the narrowphase too would have found the pair.
  double deepest = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < old->manifold.count; ++i) deepest = std::max(deepest, origin.depth[i]);
  if (moved - deepest >= margin) return false;
  contacts_.push_back(*old);
  BodyContact& c = contacts_.back();
  carryManifold(origin, c.manifold.normal, c.manifold.count, pa, pb, c.manifold);
  c.origin = static_cast<std::uint32_t>(origins_.size());
  origins_.push_back(origin);
  sortDeepestFirst(c.manifold, origins_.back(), c.impulse);
  c.recycled = true;
  ++recycled_;
  return true;
}

void World::wakeTouched() {
  // A sleeping body in a contact was touched by an awake one: its island wakes. It joins the
  // solve at once; contacts with its still-sleeping neighbours start next step.
  for (const BodyContact& c : contacts_) {
    if (islands_.asleep(c.a)) islands_.wake(c.a);
    if (islands_.asleep(c.b)) islands_.wake(c.b);
  }
}

void World::carrySleepingContacts() {
  const auto byPair = [](const BodyContact& x, const BodyContact& y) { return x < y; };
  if (!sleeping_contacts_.empty()) {
    warm_source_.clear();
    std::merge(previous_.begin(), previous_.end(), sleeping_contacts_.begin(),
               sleeping_contacts_.end(), std::back_inserter(warm_source_), byPair);
    previous_.swap(warm_source_);
  }
  sleeping_contacts_.clear();
  if (!settings_.sleep.enabled) return;
  // Neither body moves this substep (asleep, or immovable and not held by the level of
  // detail): the pair is not looked for, and its impulses wait for the island to wake. An
  // island woken this substep keeps them one more, until its pairs are found.
  const auto resting = [&](BodyIndex i) {
    return islands_.asleep(i) || (bodies_.inv_mass[i] == 0.0 && (held_.empty() || !held_[i]));
  };
  for (const BodyContact& c : previous_)
    if (resting(c.a) && resting(c.b)) sleeping_contacts_.push_back(c);
}

void World::warmStarts(WarmStarts& out) const {
  out.contacts.clear();
  std::merge(contacts_.begin(), contacts_.end(), sleeping_contacts_.begin(),
             sleeping_contacts_.end(), std::back_inserter(out.contacts),
             [](const BodyContact& x, const BodyContact& y) { return x < y; });
  // Both lists index origins_ (held contacts exist only inside a step).
  out.origins = origins_;
}

void World::setWarmStarts(const WarmStarts& warm) {
  contacts_.assign(warm.contacts.begin(), warm.contacts.end());
  origins_ = warm.origins;
  for (BodyContact& c : contacts_)
    if (c.origin >= origins_.size()) c.origin = kNoOrigin;
  sleeping_contacts_.clear();
}

void World::warmStartFromPrevious() {
  // Both lists are sorted by pair: one merge walk finds each pair's previous impulses, and a
  // point inherits them when its feature id matches.
  std::size_t j = 0;
  for (BodyContact& c : contacts_) {
    if (c.recycled) continue;  // its impulses came with it
    while (j < previous_.size() && previous_[j] < c) ++j;
    if (j == previous_.size() || !samePieces(previous_[j], c)) continue;
    const BodyContact& old = previous_[j];
    c.rolling_impulse = old.rolling_impulse;
    for (int i = 0; i < c.manifold.count; ++i) {
      const ContactPoint& p = c.manifold.points[i];
      // Same feature, or else the nearest old point within kPreserveDistance: clipping
      // equal-sized aligned faces flips a point between "vertex" and "edge crossing" with
      // round-off, and losing its impulse for that would make stacks sag and walk.
      int match = -1;
      double nearest = kPreserveDistance * kPreserveDistance;
      for (int k = 0; k < old.manifold.count; ++k) {
        const ContactPoint& q = old.manifold.points[k];
        if (q.feature == p.feature) {
          match = k;
          break;
        }
        const double d2 = (q.position - p.position).squaredNorm();
        if (d2 < nearest) nearest = d2, match = k;
      }
      if (match >= 0) c.impulse[i] = old.impulse[match];
    }
  }
}

void World::integratePositions(double dt) {
  const std::size_t n = bodies_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const BodyType type = bodies_.type[i];
    if (type == BodyType::Static || still(BodyIndex(i))) continue;
    // The integrator's displacement, corrected by what the contact solve changed in velocity,
    // plus the split-impulse pseudo-velocity (which then vanishes).
    const Vec3 correction = bodies_.linear_velocity[i] - v_force_[i];
    bodies_.position[i] = x_force_[i] + dt * (correction + solver_.pseudoLinear(i));
    if (type == BodyType::Particle) continue;
    const Vec3 w = bodies_.angular_velocity[i] + solver_.pseudoAngular(i);
    bodies_.orientation[i] = integrateOrientation(bodies_.orientation[i], w, dt);
  }
}

void World::warmStartJoints() {
  joints_.warmStart(bodies_);
  rigid_joints_.warmStart(bodies_);
}

void World::iterateJoints() {
  joints_.iterate(bodies_);
  rigid_joints_.iterate(bodies_);
}

void World::iterateJointsSoft(const Softness& soft, bool use_bias) {
  joints_.iterateSoft(bodies_, soft, use_bias);
  rigid_joints_.iterateSoft(bodies_, soft, use_bias);
}

void World::solveIterative(double dt) {
  const SolverKind kind = settings_.solver.kind;
  if (kind == SolverKind::Penalty) {
    // Forces, not constraints: one spring-damper evaluation, no warm start, no projection.
    solver_.applyPenalty(bodies_);
    warmStartJoints();
    for (int it = 0; it < settings_.solver.velocity_iterations; ++it) iterateJoints();
    solver_.storeImpulses(contacts_);
    solver_.clearPositionCorrection(bodies_.size());
    integratePositions(dt);
    return;
  }
  const double omega = kind == SolverKind::Sor ? settings_.solver.sor_omega : 1.0;
  solver_.warmStart(bodies_);
  warmStartJoints();
  const int iterations = settings_.solver.velocity_iterations;
  for (int it = 0; it < iterations; ++it) {
    if (kind == SolverKind::Jacobi) {
      solver_.iterateJacobi(bodies_);
    } else if (kind == SolverKind::ConjugateGradient) {
      solver_.iterateConjugateGradient(bodies_, it == 0, it + 1 == iterations);
    } else {
      solver_.iterate(bodies_, omega);
    }
    iterateJoints();
  }
  solver_.storeImpulses(contacts_);
  solver_.solvePositions(bodies_);
  integratePositions(dt);
}

void World::solveProjection(double dt) {
  // Position based: the free step's displacement is corrected by projection passes, and the
  // velocity becomes what the corrected displacement implies (inelastic by construction).
  // Joints keep their velocity rows, solved before the projection.
  warmStartJoints();
  for (int it = 0; it < settings_.solver.velocity_iterations; ++it) iterateJoints();
  SolverSettings cold = settings_.solver;
  cold.warm_starting = false;  // Projections do not carry over between steps.
  solver_.prepare(bodies_, contacts_, cold, dt);
  const std::size_t n = bodies_.size();
  soft_dp_.resize(n);
  soft_dtheta_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    // Joint impulses changed the velocity after the integrator ran: add that change.
    soft_dp_[i] = x_force_[i] - x_start_[i] + dt * (bodies_.linear_velocity[i] - v_force_[i]);
    soft_dtheta_[i] = dt * bodies_.angular_velocity[i];
  }
  soft_dv_.assign(soft_dp_.begin(), soft_dp_.end());
  for (int it = 0; it < settings_.solver.velocity_iterations; ++it) {
    solver_.projectPositions(soft_dp_, soft_dtheta_);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const BodyType type = bodies_.type[i];
    if (type == BodyType::Static || still(BodyIndex(i))) continue;
    bodies_.linear_velocity[i] += (soft_dp_[i] - soft_dv_[i]) / dt;
    bodies_.position[i] = x_start_[i] + soft_dp_[i];
    if (type == BodyType::Particle) continue;
    bodies_.angular_velocity[i] = soft_dtheta_[i] / dt;
    bodies_.orientation[i] =
        integrateOrientation(bodies_.orientation[i], bodies_.angular_velocity[i], dt);
  }
}

World::SoftSprings World::softSprings(double dt) const {
  // The velocity iterations are spent as sub-steps of one biased and one relax pass each.
  const int n_sub = std::max(1, (settings_.solver.velocity_iterations + 1) / 2);
  const double h = dt / n_sub;
  const SolverSettings& ss = settings_.solver;
  // Stiffer than a quarter of the sub-step rate goes unstable in Gauss-Seidel (measured: a
  // 20-box column falls at half); the sag of a soft contact is g / omega^2 per supported box.
  const double hertz = std::min(ss.contact_hertz, ss.contact_rate_fraction / h);
  const double static_hertz = std::min(ss.contact_hertz, ss.static_contact_rate_fraction / h);
  // Joints are springs too, rebuilt at each sub-step's anchors; their impulses are per
  // sub-step, so each sub-step starts from the last one's (a chain carries a heavy ball at once
  // instead of after sweeps down its links).
  // Capped at a quarter of the sub-step rate: at half (omega h = pi) the ball and chain
  // gained 1.5 kJ with 4 sub-steps.
  return SoftSprings{
      n_sub, h, makeSoftness(hertz, ss.contact_damping_ratio, h),
      makeSoftness(static_hertz, ss.contact_damping_ratio, h),
      makeSoftness(std::min(ss.joint_hertz, kJointRateFraction / h), ss.joint_damping_ratio, h)};
}

void World::solveSoftStep(double dt) {
  const SoftSprings springs = softSprings(dt);
  const int n_sub = springs.substeps;
  const double h = springs.h;
  const std::size_t n = bodies_.size();
  soft_dp_.assign(n, Vec3::Zero());
  soft_dtheta_.assign(n, Vec3::Zero());
  soft_dv_.resize(n);
  // The force-driven velocity change is spread over the sub-steps.
  for (std::size_t i = 0; i < n; ++i) {
    soft_dv_[i] = (v_force_[i] - v_start_[i]) / n_sub;
    if (bodies_.type[i] != BodyType::Static) bodies_.linear_velocity[i] = v_start_[i];
  }
  const Softness& soft = springs.contact;
  const Softness& soft_static = springs.contact_fixed;
  const Softness& joint_soft = springs.joint;
  const int relax_passes = std::max(1, settings_.solver.position_iterations);
  for (int sub = 0; sub < n_sub; ++sub) {
    for (std::size_t i = 0; i < n; ++i) bodies_.linear_velocity[i] += soft_dv_[i];
    joints_.prepareSoft(bodies_, soft_dp_, soft_dtheta_);
    rigid_joints_.prepareSoft(bodies_, soft_dp_, soft_dtheta_);
    solver_.warmStart(bodies_);
    iterateJointsSoft(joint_soft, true);
    solver_.solveSoft(bodies_, soft_dp_, soft_dtheta_, soft, soft_static, true, 1.0 / h);
    for (std::size_t i = 0; i < n; ++i) {
      soft_dp_[i] += h * bodies_.linear_velocity[i];
      soft_dtheta_[i] += h * bodies_.angular_velocity[i];
    }
    // The position iterations are spent as relax passes: one leaves a light body squeezed
    // under a heavy one rocking (a 100:1 pair walks 0.38 m in 30 s), two hold it (0.9 mm).
    for (int r = 0; r < relax_passes; ++r) {
      iterateJointsSoft(joint_soft, false);
      solver_.solveSoft(bodies_, soft_dp_, soft_dtheta_, soft, soft_static, false, 1.0 / h);
    }
  }
  solver_.applyRestitution(bodies_);
  solver_.storeImpulses(contacts_);
  // A body under a constraint moves as the sub-steps moved it; a free body keeps the selected
  // integrator's motion (mixing the two would leave a gravity residual of g dt h (N-1)/2).
  markConstrainedBodies();
  for (std::size_t i = 0; i < n; ++i) {
    const BodyType type = bodies_.type[i];
    if (type == BodyType::Static || still(BodyIndex(i))) continue;
    bodies_.position[i] = soft_touched_[i] ? Vec3(x_start_[i] + soft_dp_[i]) : x_force_[i];
    if (type == BodyType::Particle) continue;
    // Turned by exactly the rotation the joints saw (soft_joint_anchor.h): the first-order
    // update falls short by |dtheta|^3/12, a 0.2 rad gap at the 1.6 rad a whipping chain link
    // turns in one step, which the joints then pull back as a burst of energy.
    bodies_.orientation[i] = rotatedBy(soft_dtheta_[i], bodies_.orientation[i]);
  }
}

void World::markConstrainedBodies() {
  soft_touched_.assign(bodies_.size(), 0);
  for (const BodyContact& c : contacts_) soft_touched_[c.a] = soft_touched_[c.b] = 1;
  for (const DistanceJoint& j : joints_.joints()) {
    soft_touched_[j.a] = 1;
    if (j.b != kNoBody) soft_touched_[j.b] = 1;
  }
  rigid_joints_.markBodies(soft_touched_);
}

void World::quarantineNonFinite() {
  const std::size_t n = bodies_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (bodies_.type[i] == BodyType::Static) continue;
    const bool finite = bodies_.position[i].allFinite() && bodies_.linear_velocity[i].allFinite() &&
                        bodies_.angular_velocity[i].allFinite() &&
                        bodies_.orientation[i].coeffs().allFinite();
    if (finite) continue;
    // Frozen where it last was finite, with no mass: nothing it touches can catch the NaN.
    bodies_.position[i] = x_start_[i].allFinite() ? x_start_[i] : Vec3::Zero();
    if (!bodies_.orientation[i].coeffs().allFinite()) bodies_.orientation[i] = Quat::Identity();
    bodies_.linear_velocity[i].setZero();
    bodies_.angular_velocity[i].setZero();
    bodies_.inv_mass[i] = 0.0;
    bodies_.inv_inertia_local[i].setZero();
    bodies_.inv_inertia_world[i].setZero();
    bodies_.type[i] = BodyType::Static;
    quarantined_.push_back(static_cast<BodyIndex>(i));
  }
}

}  // namespace zonesim::physics
