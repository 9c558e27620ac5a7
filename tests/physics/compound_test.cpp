// Compound bodies against results that do not use the code under test: mass properties
// against integration over a voxel grid (the full tensor, products of inertia included), the
// tipping point of an L-shaped body from where its centre of mass lies over its foot, resting
// heights from the geometry, and free rotation against Euler's equations' invariants.

#include "physics/compound.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "physics/mass_properties.h"
#include "physics/world.h"

namespace zonesim::physics {
namespace {

constexpr double kDt = 1.0 / 60.0;

ShapePart part(const Shape& shape, const Vec3& position, const Quat& q = Quat::Identity()) {
  return ShapePart{shape, position, q};
}

/// True when p (in the compound's frame) lies inside a sphere, box or capsule part: written
/// from the shapes' definitions, not from the collision code.
bool insidePart(const ShapePart& part, const Vec3& p) {
  const Vec3 local = part.orientation.conjugate() * (p - part.position);
  const Shape& s = part.shape;
  switch (s.type) {
    case ShapeType::Sphere:
      return local.squaredNorm() <= s.radius * s.radius;
    case ShapeType::Box:
      return (local.cwiseAbs() - s.half_extents).maxCoeff() <= 0.0;
    case ShapeType::Capsule: {
      const Vec3 axis(0, std::clamp(local.y(), -s.half_height, s.half_height), 0);
      return (local - axis).squaredNorm() <= s.radius * s.radius;
    }
    default:
      return false;
  }
}

/// Mass, centre and inertia tensor of the union of the parts by the midpoint rule on an n^3
/// grid over [lo, hi] (overlaps counted once, so test shapes keep their parts apart).
MassProperties voxelProperties(const std::vector<ShapePart>& parts, const Vec3& lo, const Vec3& hi,
                               int n, double density) {
  const Vec3 size = hi - lo;
  const double dv = size.prod() / (double(n) * n * n);
  MassProperties out;
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vec3 p =
            lo + Vec3((i + 0.5) / n * size.x(), (j + 0.5) / n * size.y(), (k + 0.5) / n * size.z());
        for (const ShapePart& q : parts) {
          if (!insidePart(q, p)) continue;
          points.push_back(p);
          break;
        }
      }
  out.mass = density * dv * double(points.size());
  for (const Vec3& p : points) out.centre += p;
  out.centre /= double(points.size());
  for (const Vec3& p : points) {
    const Vec3 d = p - out.centre;
    out.inertia +=
        density * dv * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return out;
}

TEST(Compound, MassPropertiesMatchVoxelIntegrationWithProductsOfInertia) {
  // A box turned 30 degrees about z and 20 about x, a sphere and a tilted capsule, apart.
  const Quat turn =
      Quat(Eigen::AngleAxisd(0.52, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(0.35, Vec3::UnitX()));
  const std::vector<ShapePart> parts = {
      part(Shape::box(Vec3(0.6, 0.2, 0.3)), Vec3(0.2, 0.1, -0.1), turn),
      part(Shape::sphere(0.35), Vec3(1.3, 0.9, 0.4)),
      part(Shape::capsule(0.15, 0.4), Vec3(-0.9, 0.3, 0.6),
           Quat(Eigen::AngleAxisd(0.8, Vec3(1, 0, 1).normalized())))};
  const double density = 700.0;
  const MassProperties mp = computeMassProperties(makeCompound(parts), density);
  const MassProperties ref =
      voxelProperties(parts, Vec3(-1.6, -0.7, -1.0), Vec3(1.7, 1.3, 1.3), 240, density);
  EXPECT_NEAR(mp.mass / ref.mass, 1.0, 2e-3);
  EXPECT_LT((mp.centre - ref.centre).norm(), 2e-3);
  // Off-diagonal terms are a sizeable share of the tensor: this checks them, not just the axes.
  const Eigen::Matrix3d off = mp.inertia - Eigen::Matrix3d(mp.inertia.diagonal().asDiagonal());
  EXPECT_GT(off.norm(), 0.05 * mp.inertia.norm());
  EXPECT_LT((mp.inertia - ref.inertia).norm(), 3e-3 * ref.inertia.norm());
  std::printf(
      "compound: mass %.4f (voxels %.4f), |I - I_voxels| / |I| = %.2e, off-diagonal "
      "share %.2f\n",
      mp.mass, ref.mass, (mp.inertia - ref.inertia).norm() / ref.inertia.norm(),
      off.norm() / mp.inertia.norm());
}

TEST(Compound, CentringMovesPartsToTheCentreOfMass) {
  const std::vector<ShapePart> parts = {part(Shape::sphere(0.5), Vec3(0, 0, 0)),
                                        part(Shape::sphere(0.5), Vec3(2, 0, 0)),
                                        part(Shape::box(Vec3(0.5, 0.5, 0.5)), Vec3(0, 3, 0))};
  const CentredCompound c = centreCompound(parts);
  const double sphere = 4.0 / 3.0 * M_PI * 0.125, cube = 1.0;
  const double m = 2 * sphere + cube;
  EXPECT_NEAR(c.centre.x(), 2 * sphere / m, 1e-12);
  EXPECT_NEAR(c.centre.y(), 3 * cube / m, 1e-12);
  EXPECT_LT(computeMassProperties(c.shape, 1.0).centre.norm(), 1e-12);
}

TEST(Compound, BadPartsAreRefusedByName) {
  const auto message = [](const std::vector<ShapePart>& parts) {
    try {
      makeCompound(parts);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({}).find("at least one part"), std::string::npos);
  EXPECT_NE(message({part(Shape::sphere(1), Vec3::Zero()), part(Shape::plane(), Vec3::Zero())})
                .find("part 1: a plane"),
            std::string::npos);
  const Shape inner = makeCompound({part(Shape::sphere(1), Vec3::Zero())});
  EXPECT_NE(message({part(inner, Vec3::Zero())}).find("another compound"), std::string::npos);
  EXPECT_NE(message({part(Shape::sphere(0), Vec3::Zero())}).find("radius"), std::string::npos);
  EXPECT_NE(message({part(Shape::box(Vec3(1, 0, 1)), Vec3::Zero())}).find("half extent"),
            std::string::npos);
  EXPECT_NE(message({part(Shape::sphere(1), Vec3(NAN, 0, 0))}).find("not finite"),
            std::string::npos);
  EXPECT_NE(message(std::vector<ShapePart>(65537, part(Shape::sphere(1), Vec3::Zero())))
                .find("at most 65536 parts"),
            std::string::npos);

  // A dynamic body turns about its origin: an uncentred compound is refused, a static one not.
  World world;
  BodyDesc d;
  d.shape = makeCompound({part(Shape::sphere(0.5), Vec3(1, 0, 0))});
  try {
    world.addBody(d);
    ADD_FAILURE() << "an uncentred dynamic compound was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("centreCompound"), std::string::npos) << e.what();
  }
  EXPECT_EQ(world.bodies().size(), 0u);
  d.type = BodyType::Static;
  EXPECT_NO_THROW(world.addBody(d));
}

BodyDesc ground() {
  BodyDesc g;
  g.type = BodyType::Static;
  g.shape = Shape::plane();
  return g;
}

/// The tilt of body i from upright (its local y against world y), radians.
double tilt(const World& w, BodyIndex i) {
  const Vec3 up = w.bodies().orientation[i] * Vec3::UnitY();
  return std::acos(std::clamp(up.y(), -1.0, 1.0));
}

/// An L on its foot: a 1 x 0.1 x 1 m foot, a 1 m post at its centre, and an arm of length
/// `arm` along +x from the post's top. It stands while its centre of mass lies over the
/// foot (x < 0.5) and tips over once the arm carries it past the edge, onto the arm's tip.
struct Gallows {
  World world;
  BodyIndex body = 0;
  double centre_x = 0.0;  // Of the body's mass, measured from the post, in the parts' frame.

  explicit Gallows(double arm) {
    world.addBody(ground());
    const CentredCompound c =
        centreCompound({part(Shape::box(Vec3(0.5, 0.05, 0.5)), Vec3(0, 0.05, 0)),
                        part(Shape::box(Vec3(0.05, 0.5, 0.05)), Vec3(0, 0.6, 0)),
                        part(Shape::box(Vec3(0.5 * arm, 0.05, 0.05)), Vec3(0.5 * arm, 1.05, 0))});
    centre_x = c.centre.x();
    BodyDesc d;
    d.shape = c.shape;
    d.position = c.centre + Vec3(0, 0.001, 0);
    d.friction = 0.8;
    body = world.addBody(d);
  }
};

TEST(Compound, AnLStandsWhileItsCentreOfMassIsOverItsFootAndTipsPastIt) {
  // Volumes 0.1 (foot), 0.01 (post) and 0.01 a (arm at a / 2): the centre reaches the foot's
  // edge at 0.005 a^2 = 0.5 (0.11 + 0.01 a), a = (1 + sqrt(45)) / 2 = 3.854 m.
  const double critical = 0.5 * (1.0 + std::sqrt(45.0));
  Gallows stands(critical - 0.25), tips(critical + 0.25);
  EXPECT_LT(stands.centre_x, 0.5);
  EXPECT_GT(tips.centre_x, 0.5);
  for (int k = 0; k < 480; ++k) {
    stands.world.step(kDt);
    tips.world.step(kDt);
  }
  std::printf(
      "L with arm %.3f m (centre x %.3f): tilt %.4f rad; arm %.3f m (centre x %.3f): "
      "tilt %.3f rad\n",
      critical - 0.25, stands.centre_x, tilt(stands.world, stands.body), critical + 0.25,
      tips.centre_x, tilt(tips.world, tips.body));
  EXPECT_LT(tilt(stands.world, stands.body), 0.01);
  // It turns about the foot's edge (x = 0.5, y = 0) until the arm's lower tip corner, 1 m up
  // and arm - 0.5 m out from that edge, reaches the ground: tan(tilt) = 1 / (arm - 0.5).
  EXPECT_NEAR(tilt(tips.world, tips.body), std::atan(1.0 / (critical + 0.25 - 0.5)), 0.005);
}

/// A table: a 2 x 0.1 x 1 m top on four 0.1 m square legs 0.8 m long at its corners.
CentredCompound table() {
  std::vector<ShapePart> parts = {part(Shape::box(Vec3(1.0, 0.05, 0.5)), Vec3(0, 0.85, 0))};
  for (double x : {-0.95, 0.95})
    for (double z : {-0.45, 0.45})
      parts.push_back(part(Shape::box(Vec3(0.05, 0.4, 0.05)), Vec3(x, 0.4, z)));
  return centreCompound(parts);
}

TEST(Compound, TablesStackAndRestOnTheirLegs) {
  World world;
  world.addBody(ground());
  const CentredCompound t = table();
  BodyDesc d;
  d.shape = t.shape;
  d.position = t.centre + Vec3(0, 0.01, 0);
  const BodyIndex lower = world.addBody(d);
  // The upper table's legs stand on the lower one's top, 0.9 m high.
  d.position = t.centre + Vec3(0, 0.91, 0);
  const BodyIndex upper = world.addBody(d);
  for (int k = 0; k < 300; ++k) world.step(kDt);
  const BodyStorage& b = world.bodies();
  // Each table rests on four legs: four leg-ground contacts under the lower, and the upper's
  // legs meet the lower's top, part 0, from their own part indices 1 to 4.
  int lower_legs = 0, upper_legs_on_top = 0;
  for (const BodyContact& c : world.contacts()) {
    if (c.a == 0 && c.b == lower && c.piece_b >= 1) ++lower_legs;
    if (c.a == lower && c.b == upper && c.piece_a == 0 && c.piece_b >= 1) ++upper_legs_on_top;
  }
  EXPECT_EQ(lower_legs, 4);
  EXPECT_GE(upper_legs_on_top, 2);
  const double rest_lower = t.centre.y(), rest_upper = t.centre.y() + 0.9;
  std::printf(
      "tables: lower centre %.4f m (geometry %.4f), upper %.4f m (geometry %.4f), "
      "tilts %.2e / %.2e rad\n",
      b.position[lower].y(), rest_lower, b.position[upper].y(), rest_upper, tilt(world, lower),
      tilt(world, upper));
  EXPECT_NEAR(b.position[lower].y(), rest_lower, 0.01);
  EXPECT_NEAR(b.position[upper].y(), rest_upper, 0.02);
  EXPECT_LT(tilt(world, lower), 0.01);
  EXPECT_LT(tilt(world, upper), 0.01);
  EXPECT_LT(b.linear_velocity[upper].norm(), 0.01);
}

/// A free body (no gravity) spinning at w0 (world frame) for `seconds`; returns the largest
/// relative change of its world angular momentum R I R^T w, and the final body-frame w.
struct FreeSpin {
  double momentum_drift = 0.0;
  double energy_change = 0.0;  ///< Relative, signed.
  Vec3 final_body_w = Vec3::Zero();
  double min_middle = 0.0;  ///< Lowest body-frame w along the intermediate axis.
};

FreeSpin spin(const Shape& shape, const Vec3& w0, bool gyroscopic, double seconds,
              int substeps = 1) {
  WorldSettings settings;
  settings.gyroscopic = gyroscopic;
  settings.substeps = substeps;
  World world(settings);
  world.forces().gravity = Vec3::Zero();
  BodyDesc d;
  d.shape = shape;
  d.angular_velocity = w0;
  const BodyIndex i = world.addBody(d);
  const Eigen::Matrix3d inertia = world.bodies().inv_inertia_local[i].inverse();
  const auto momentum = [&] {
    const Eigen::Matrix3d r = world.bodies().orientation[i].toRotationMatrix();
    return Vec3(r * inertia * r.transpose() * world.bodies().angular_velocity[i]);
  };
  const auto energy = [&] {
    const Vec3 wb = world.bodies().orientation[i].conjugate() * world.bodies().angular_velocity[i];
    return 0.5 * wb.dot(inertia * wb);
  };
  const Vec3 l0 = momentum();
  const double e0 = energy();
  FreeSpin out;
  out.min_middle = (world.bodies().orientation[i].conjugate() * w0).y();
  const int steps = int(std::lround(seconds / kDt));
  for (int k = 0; k < steps; ++k) {
    world.step(kDt);
    out.momentum_drift = std::max(out.momentum_drift, (momentum() - l0).norm() / l0.norm());
    const Vec3 wb = world.bodies().orientation[i].conjugate() * world.bodies().angular_velocity[i];
    out.min_middle = std::min(out.min_middle, wb.y());
  }
  out.energy_change = energy() / e0 - 1.0;
  out.final_body_w = world.bodies().orientation[i].conjugate() * world.bodies().angular_velocity[i];
  return out;
}

TEST(Compound, GyroscopicTermFlipsTheIntermediateAxisAndKeepsTheInvariants) {
  // A box of half sizes 0.5 x 0.3 x 0.1 has I_x < I_y < I_z. Spun about its intermediate
  // axis y with a small perturbation, it turns over and back (the Dzhanibekov effect). The
  // midpoint rule keeps its energy to round-off; the world angular momentum drifts at first
  // order in the step (the orientation update is first order).
  const Shape brick = Shape::box(Vec3(0.5, 0.3, 0.1));
  const Vec3 w0(0.01, 4.0, 0.01);
  const FreeSpin with = spin(brick, w0, true, 10.0);
  const FreeSpin without = spin(brick, w0, false, 10.0);
  const FreeSpin fine = spin(brick, w0, true, 10.0, 8);
  std::printf(
      "intermediate-axis spin, 10 s: energy change %.1e; lowest w_y %.3f (from %.3f; "
      "%.3f without the term); angular momentum drift %.2e at 1 substep, %.2e at 8\n",
      with.energy_change, with.min_middle, w0.y(), without.min_middle, with.momentum_drift,
      fine.momentum_drift);
  EXPECT_LT(with.min_middle, -0.9 * w0.y());     // It turned over...
  EXPECT_GT(without.min_middle, 0.99 * w0.y());  // ...which it cannot without the term.
  EXPECT_LT(std::abs(with.energy_change), 1e-9);
  EXPECT_LT(with.momentum_drift, 0.03);
  const double order = std::log2(with.momentum_drift / fine.momentum_drift) / 3.0;
  EXPECT_NEAR(order, 1.0, 0.15);

  // About the axis of largest inertia the spin is stable: it stays there.
  const FreeSpin major = spin(brick, Vec3(0.01, 0.01, 4.0), true, 10.0);
  EXPECT_NEAR(major.final_body_w.z(), 4.0, 0.01);
  EXPECT_LT(major.momentum_drift, 0.01);
}

TEST(Compound, AFullTensorPrecessesWithItsAngularMomentumKept) {
  // Two spheres on a tilted rod, spun about world y, which is not a principal axis: the body
  // wobbles, and its angular momentum must not change. Without the gyroscopic term the
  // angular velocity stays put instead, and the momentum swings with the body.
  const Quat tilted(Eigen::AngleAxisd(0.4, Vec3::UnitZ()));
  const CentredCompound dumbbell =
      centreCompound({part(Shape::sphere(0.3), tilted * Vec3(0, 0.8, 0)),
                      part(Shape::sphere(0.2), tilted * Vec3(0, -0.8, 0)),
                      part(Shape::capsule(0.05, 0.6), Vec3::Zero(), tilted)});
  const FreeSpin with = spin(dumbbell.shape, Vec3(0, 3.0, 0), true, 10.0);
  const FreeSpin without = spin(dumbbell.shape, Vec3(0, 3.0, 0), false, 10.0);
  // Stiff: the spin about the rod is 1 rad per step, and the energy still holds.
  const FreeSpin fast = spin(dumbbell.shape, Vec3(0, 60.0, 0), true, 10.0);
  std::printf(
      "tilted dumbbell, 10 s: angular momentum drift %.2e with the gyroscopic term, "
      "%.2e without; at 60 rad/s energy change %.1e, drift %.2e\n",
      with.momentum_drift, without.momentum_drift, fast.energy_change, fast.momentum_drift);
  EXPECT_LT(with.momentum_drift, 0.05);
  EXPECT_GT(without.momentum_drift, 1.0);
  EXPECT_LT(std::abs(with.energy_change), 1e-9);
  EXPECT_TRUE(fast.final_body_w.allFinite());
  EXPECT_LT(std::abs(fast.energy_change), 1e-6);
}

}  // namespace
}  // namespace zonesim::physics
