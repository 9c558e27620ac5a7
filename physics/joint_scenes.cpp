#include "physics/joint_scenes.h"

#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

namespace zonesim::physics {

double JointScene::worstGap() const {
  const BodyStorage& s = world_.bodies();
  double worst = 0.0;
  for (const Anchors& j : anchors_) {
    const Vec3 pa = s.position[j.a] + s.orientation[j.a] * j.local_a;
    const Vec3 pb =
        j.b == kNoBody ? j.local_b : Vec3(s.position[j.b] + s.orientation[j.b] * j.local_b);
    worst = std::max(worst, (pa - pb).norm());
  }
  return worst;
}

double JointScene::energy() const {
  const BodyStorage& s = world_.bodies();
  const Vec3 g = world_.forces().gravity;
  double e = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.inv_mass[i] == 0.0) continue;
    const double m = 1.0 / s.inv_mass[i];
    const Vec3& w = s.angular_velocity[i];
    const Eigen::Matrix3d inertia = s.inv_inertia_world[i].inverse();
    e += 0.5 * m * s.linear_velocity[i].squaredNorm() - m * g.dot(s.position[i]) +
         0.5 * w.dot(inertia * w);
  }
  return e;
}

double JointScene::fastestSpeed() const {
  const BodyStorage& s = world_.bodies();
  double v = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) v = std::max(v, s.linear_velocity[i].norm());
  return v;
}

void JointScene::addBall(BodyIndex a, BodyIndex b, const Vec3& local_a, const Vec3& local_b) {
  world_.addBallJoint(BallJoint{a, b, local_a, local_b});
  anchors_.push_back({a, b, local_a, local_b});
}

void JointScene::addHingeZ(BodyIndex a, BodyIndex b, const Vec3& at) {
  const BodyStorage& s = world_.bodies();
  const Vec3 local_b = s.orientation[b].conjugate() * (at - s.position[b]);
  const Vec3 axis_b = s.orientation[b].conjugate() * Vec3::UnitZ();
  if (a == kNoBody) {
    // The joint's first end is the moving one: b on the link, the world pivot as its other end.
    world_.addHingeJoint(HingeJoint{b, kNoBody, local_b, at, axis_b, Vec3::UnitZ()});
    anchors_.push_back({b, kNoBody, local_b, at});
    return;
  }
  const Vec3 local_a = s.orientation[a].conjugate() * (at - s.position[a]);
  const Vec3 axis_a = s.orientation[a].conjugate() * Vec3::UnitZ();
  world_.addHingeJoint(HingeJoint{a, b, local_a, local_b, axis_a, axis_b});
  world_.ignoreContactsBetween(a, b);
  anchors_.push_back({a, b, local_a, local_b});
}

BallAndChain::BallAndChain(const WorldSettings& settings) : JointScene(settings) {
  constexpr int kLinks = 30;
  constexpr double kHalf = 0.5, kRadius = 0.125, kBall = 4.0, kMassRatio = 170.0;
  const double y = kLinks * kHalf;
  const Quat along_x(Eigen::AngleAxisd(-std::numbers::pi / 2, Vec3::UnitZ()));
  BodyIndex previous = kNoBody;
  double link_mass = 0.0;
  for (int i = 0; i < kLinks; ++i) {
    BodyDesc link;
    link.shape = Shape::capsule(kRadius, kHalf);
    link.position = Vec3((1 + 2 * i) * kHalf, y, 0);
    link.orientation = along_x;
    link.density = 20.0;
    link.friction = 0.6;
    const BodyIndex body = world().addBody(link);
    link_mass = 1.0 / world().bodies().inv_mass[body];
    addHingeZ(previous, body, Vec3(2 * i * kHalf, y, 0));
    previous = body;
  }
  BodyDesc ball;
  ball.shape = Shape::sphere(kBall);
  ball.position = Vec3(2 * kLinks * kHalf + kBall, y, 0);
  ball.density = kMassRatio * link_mass / (4.0 / 3.0 * std::numbers::pi * std::pow(kBall, 3));
  addHingeZ(previous, world().addBody(ball), Vec3(2 * kLinks * kHalf, y, 0));
}

JointGrid::JointGrid(const WorldSettings& settings, int n) : JointScene(settings) {
  std::vector<BodyIndex> body(static_cast<std::size_t>(n) * n);
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      BodyDesc d;
      d.shape = Shape::sphere(0.4);
      d.position = Vec3(k, -i, 0);
      if (i == 0 && k >= n / 2 - 3 && k <= n / 2 + 3) d.type = BodyType::Static;
      const BodyIndex b = body[k * n + i] = world().addBody(d);
      if (i > 0) addBall(body[k * n + i - 1], b, Vec3(0, -0.5, 0), Vec3(0, 0.5, 0));
      if (k > 0) addBall(body[(k - 1) * n + i], b, Vec3(0.5, 0, 0), Vec3(-0.5, 0, 0));
    }
  }
}

JointRunRecord runJointScene(JointScene& scene, int steps, int every,
                             const std::function<void(int, const JointRunRecord&)>& progress) {
  JointRunRecord r;
  const double e0 = scene.energy();
  double stepping = 0.0;
  for (int s = 1; s <= steps; ++s) {
    const auto t0 = std::chrono::steady_clock::now();
    scene.world().step(1.0 / 60.0);
    stepping += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (s % every != 0 && s != steps) continue;
    const double gap = scene.worstGap();
    r.worst_gap = std::max(r.worst_gap, gap);
    r.final_gap = gap;
    r.worst_speed = std::max(r.worst_speed, scene.fastestSpeed());
    r.worst_energy_gain = std::max(r.worst_energy_gain, scene.energy() - e0);
    if (!std::isfinite(gap) || !scene.world().quarantined().empty()) r.finite = false;
    if (progress) progress(s, r);
  }
  r.seconds_per_step = stepping / std::max(1, steps);
  return r;
}

}  // namespace zonesim::physics
