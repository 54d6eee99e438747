#include "services/simulator/core/physics/physics_world.h"

#include <BulletCollision/CollisionDispatch/btSimulationIslandManager.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "services/simulator/core/physics/ball_model.h"
#include "services/simulator/core/physics/robot_kinematics.h"

namespace ssl::sim {
namespace {

// Collision groups: robots do not touch the carpet (they are locked to it), walls do not touch walls.
constexpr int kGroupGround = 1 << 0;
constexpr int kGroupWall = 1 << 1;
constexpr int kGroupRobot = 1 << 2;
constexpr int kGroupBall = 1 << 3;
constexpr int kMaskGround = kGroupBall;
constexpr int kMaskWall = kGroupRobot | kGroupBall;
constexpr int kMaskRobot = kGroupWall | kGroupRobot | kGroupBall;
constexpr int kMaskBall = kGroupGround | kGroupWall | kGroupRobot;

// Collision margin of the robot hull and the walls (m). The hull's core is pulled in by it, so the
// outer surface is the RobotSpec's; Bullet's default of 4 cm would round every edge.
constexpr double kHullMargin = 0.002;
constexpr double kWallMargin = 0.002;
// A ball centre this close to its resting height counts as on the carpet (m).
constexpr double kGroundSlop = 0.005;

bool finite(double v) { return std::isfinite(v); }
bool finite(const Vec2& v) { return v.allFinite(); }
bool finite(const Vec3& v) { return v.allFinite(); }

btVector3 bt(double x, double y, double z) { return btVector3(x, y, z); }

// Robots only turn about z, so the first basis column is the unit heading (cos yaw, sin yaw, 0).
Vec2 heading_of(const btTransform& transform) {
  const btMatrix3x3& basis = transform.getBasis();
  return Vec2(basis[0][0], basis[1][0]);
}

double yaw_of(const btTransform& transform) {
  const btMatrix3x3& basis = transform.getBasis();
  return std::atan2(basis[1][0], basis[0][0]);
}

btTransform pose(Vec2 position, double z, double yaw) {
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(bt(position.x(), position.y(), z));
  btQuaternion rotation;
  rotation.setRotation(btVector3(0, 0, 1), yaw);
  transform.setRotation(rotation);
  return transform;
}

std::optional<std::string> validate_field(const FieldGeometry& f) {
  const double values[] = {f.field_length, f.field_width, f.goal_width, f.goal_depth, f.goal_height,
                           f.goal_wall_thickness, f.boundary_width, f.boundary_width_goal_line};
  for (double v : values) {
    if (!finite(v) || v <= 0) return "field sizes, goal sizes and boundary widths must be finite and > 0";
  }
  if (f.goal_width + 2 * f.goal_wall_thickness >= f.field_width + 2 * f.boundary_width) {
    return "goal wider than the walled area";
  }
  if (f.goal_depth + f.goal_wall_thickness >= f.boundary_width_goal_line) {
    return "goal_depth + goal_wall_thickness must be < boundary_width_goal_line (the goal must fit)";
  }
  return std::nullopt;
}

std::optional<std::string> validate_spec(const RobotSpec& s) {
  const double positive[] = {s.radius, s.height, s.mass, s.center_to_dribbler, s.dribbler_width,
                             s.limits.acc_speedup_absolute_max, s.limits.acc_speedup_angular_max,
                             s.limits.acc_brake_absolute_max, s.limits.acc_brake_angular_max,
                             s.limits.vel_absolute_max, s.limits.vel_angular_max};
  for (double v : positive) {
    if (!finite(v) || v <= 0) return "sizes, mass and limits must be finite and > 0";
  }
  if (s.center_to_dribbler >= s.radius || s.center_to_dribbler <= kHullMargin) {
    return "center_to_dribbler must be in (0, radius)";
  }
  if (!finite(s.max_linear_kick_speed) || s.max_linear_kick_speed < 0 || !finite(s.max_chip_kick_speed) ||
      s.max_chip_kick_speed < 0) {
    return "kick speeds must be finite and >= 0";
  }
  for (double angle : s.wheel_angles) {
    if (!finite(angle)) return "wheel angles must be finite";
  }
  return std::nullopt;
}

}  // namespace

bool command_valid(const RobotCommand& c) {
  if (!finite(c.velocity) || !finite(c.kick_speed) || !finite(c.kick_angle) || !finite(c.dribbler_rpm)) {
    return false;
  }
  for (double w : c.wheel_velocity) {
    if (!finite(w)) return false;
  }
  if (c.kick_speed < 0) return false;
  return c.kick_angle >= 0 && c.kick_angle < std::numbers::pi / 2;
}

namespace {

// The robot hull: the spec's cylinder cut by the plane x = center_to_dribbler (robot frame: x forward, y
// left, z up), centred on the cylinder axis. An analytic support function instead of a btConvexHullShape:
// exact (no polygon) and about 10x cheaper per GJK support call, which dominates the collision cost. The
// core is pulled in by the collision margin, so the outer surface is the RobotSpec's.
ATTRIBUTE_ALIGNED16(class) RobotHullShape : public btConvexInternalShape {
 public:
  BT_DECLARE_ALIGNED_ALLOCATOR();

  explicit RobotHullShape(const RobotSpec& spec)
      : radius_(spec.radius - kHullMargin),
        front_(spec.center_to_dribbler - kHullMargin),
        half_width_(std::sqrt(radius_ * radius_ - front_ * front_)),
        half_height_(spec.height / 2 - kHullMargin),
        outer_radius_(spec.radius) {
    m_shapeType = CUSTOM_CONVEX_SHAPE_TYPE;
    m_collisionMargin = kHullMargin;
    m_implicitShapeDimensions = bt(radius_, radius_, half_height_);
  }

  btVector3 localGetSupportingVertexWithoutMargin(const btVector3& direction) const override {
    const double dx = direction.x();
    const double dy = direction.y();
    const double planar = std::sqrt(dx * dx + dy * dy);
    double x = 0;
    double y = 0;
    if (planar > 1e-12) {
      x = radius_ * dx / planar;
      y = radius_ * dy / planar;
      if (x > front_) {  // the arc's extreme point is cut away: one end of the flat front wins
        x = front_;
        y = dy >= 0 ? half_width_ : -half_width_;
      }
    }
    return bt(x, y, direction.z() >= 0 ? half_height_ : -half_height_);
  }

  void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* directions, btVector3* out,
                                                         int count) const override {
    for (int i = 0; i < count; ++i) out[i] = localGetSupportingVertexWithoutMargin(directions[i]);
  }

  void getAabb(const btTransform& transform, btVector3& aabb_min, btVector3& aabb_max) const override {
    btTransformAabb(bt(-radius_, -radius_, -half_height_), bt(front_, radius_, half_height_), getMargin(),
                    transform, aabb_min, aabb_max);
  }

  // A full cylinder's inertia (the flat front removes ~3 % of the area; irrelevant for a velocity-driven
  // body that only turns about z).
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override {
    const double r2 = outer_radius_ * outer_radius_;
    const double h2 = 4 * (half_height_ + kHullMargin) * (half_height_ + kHullMargin);
    inertia = bt(mass * (3 * r2 + h2) / 12, mass * (3 * r2 + h2) / 12, mass * r2 / 2);
  }

  const char* getName() const override { return "SslRobotHull"; }
  void getPreferredPenetrationDirection(int, btVector3& direction) const override { direction.setZero(); }

 private:
  double radius_;
  double front_;
  double half_width_;
  double half_height_;
  double outer_radius_;
};

}  // namespace

std::optional<std::string> validate(const PhysicsParams& p) {
  const double positive[] = {p.step, p.gravity, p.ball_radius, p.ball_mass, p.ball_sliding_deceleration,
                             p.ball_rolling_deceleration, p.ball_inertia_factor, p.wheel_distance_fraction,
                             p.dribbler_contact_tolerance, p.dribbler_max_ball_height, p.dribbler_hold_gain,
                             p.dribbler_max_correction_speed, p.boundary_wall_height,
                             p.boundary_wall_thickness};
  for (double v : positive) {
    if (!finite(v) || v <= 0) return "step, gravity, ball, dribbler and wall parameters must be > 0";
  }
  if (p.step > 0.05) return "step must be <= 0.05 s";
  const double unit[] = {p.ball_restitution_ground, p.ball_restitution_wall, p.ball_restitution_goal,
                         p.ball_restitution_robot, p.ball_collision_spin_retention};
  for (double v : unit) {
    if (!finite(v) || v < 0 || v > 1) return "restitutions and spin retention must be in [0, 1]";
  }
  if (!finite(p.robot_friction) || p.robot_friction < 0 || !finite(p.wall_friction) || p.wall_friction < 0) {
    return "frictions must be finite and >= 0";
  }
  if (p.solver_iterations < 1) return "solver_iterations must be >= 1";
  if (p.dribbler_hold_gain * p.step >= 1) return "dribbler_hold_gain * step must be < 1";
  return std::nullopt;
}

struct PhysicsWorld::Impl {
  struct Robot {
    RobotKey key;
    std::unique_ptr<btRigidBody> body;
    RobotCommand command;
    bool kick_latched = false;  // kicked; no kick or hold until the ball has left the front
    double speed_scale = 1;         // of the team's speed limits
    double acceleration_scale = 1;  // of the team's acceleration limits
  };

  FieldGeometry field;
  PhysicsParams params;
  std::array<RobotSpec, 2> specs{};
  std::int64_t step_ns = 0;
  std::int64_t pending_ns = 0;
  time::Timestamp now;

  // Bullet, in construction order (destroyed in reverse; bodies are removed in ~Impl first).
  btDefaultCollisionConfiguration collision_config;
  btCollisionDispatcher dispatcher{&collision_config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &collision_config};

  std::vector<std::unique_ptr<btCollisionShape>> static_shapes;
  std::vector<std::unique_ptr<btRigidBody>> static_bodies;
  std::array<std::unique_ptr<RobotHullShape>, 2> hulls;
  std::unique_ptr<btSphereShape> ball_shape;
  std::unique_ptr<btRigidBody> ball;
  Vec2 ball_spin = Vec2::Zero();  // rolling velocity of the ball's spin (ball_model.h)
  std::map<RobotKey, Robot> robots;

  Impl(const FieldGeometry& field_in, const PhysicsParams& params_in) : field(field_in), params(params_in) {
    step_ns = std::llround(params.step * 1e9);
    world.setGravity(bt(0, 0, -params.gravity));
    // Measured with physics_world_benchmark.cpp: walls and carpet never move, so only moving bodies'
    // AABBs are updated; one solver call for all contacts beats splitting them into islands (+7 %).
    world.setForceUpdateAllAabbs(false);
    world.getSimulationIslandManager()->setSplitIslands(false);
    btContactSolverInfo& info = world.getSolverInfo();
    info.m_numIterations = params.solver_iterations;
    // Always resolve penetration by split impulse (position only), never by adding velocity: the ball's
    // carpet friction is derived from the velocity the carpet gives it (ball_model.h).
    info.m_splitImpulse = 1;
    info.m_splitImpulsePenetrationThreshold = 0;
    build_field();
    build_ball();
    for (std::size_t team = 0; team < 2; ++team) hulls[team] = std::make_unique<RobotHullShape>(specs[team]);
  }

  ~Impl() {
    for (auto& [key, robot] : robots) world.removeRigidBody(robot.body.get());
    world.removeRigidBody(ball.get());
    for (auto& body : static_bodies) world.removeRigidBody(body.get());
  }

  static std::size_t team_index(TeamColor team) { return team == TeamColor::kBlue ? 0 : 1; }

  void add_static(std::unique_ptr<btCollisionShape> shape, const btVector3& origin, double restitution,
                  int group, int mask) {
    btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, shape.get());
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(origin);
    info.m_restitution = restitution;
    info.m_friction = params.wall_friction;
    auto body = std::make_unique<btRigidBody>(info);
    world.addRigidBody(body.get(), group, mask);
    static_shapes.push_back(std::move(shape));
    static_bodies.push_back(std::move(body));
  }

  void add_box(double cx, double cy, double hx, double hy, double height, double restitution) {
    auto box = std::make_unique<btBoxShape>(bt(hx, hy, height / 2));
    box->setMargin(kWallMargin);
    add_static(std::move(box), bt(cx, cy, height / 2), restitution, kGroupWall, kMaskWall);
  }

  void build_field() {
    add_static(std::make_unique<btStaticPlaneShape>(bt(0, 0, 1), 0.0), bt(0, 0, 0),
               params.ball_restitution_ground, kGroupGround, kMaskGround);
    const double t = params.boundary_wall_thickness;
    const double h = params.boundary_wall_height;
    const double inner_x = field.wall_half_length();
    const double inner_y = field.wall_half_width();
    const double e = params.ball_restitution_wall;
    for (double sign : {-1.0, 1.0}) {
      add_box(0, sign * (inner_y + t / 2), inner_x + t, t / 2, h, e);  // along a touch line
      add_box(sign * (inner_x + t / 2), 0, t / 2, inner_y + t, h, e);  // behind a goal line
    }
    // Goals: back wall across the full outer width, side walls from the goal line to the back wall.
    const double gx = field.field_length / 2;
    const double gw = field.goal_width / 2;
    const double depth = field.goal_depth;
    const double wall = field.goal_wall_thickness;
    const double g = params.ball_restitution_goal;
    for (double sign : {-1.0, 1.0}) {
      add_box(sign * (gx + depth + wall / 2), 0, wall / 2, gw + wall, field.goal_height, g);
      for (double side : {-1.0, 1.0}) {
        add_box(sign * (gx + depth / 2), side * (gw + wall / 2), depth / 2, wall / 2, field.goal_height, g);
      }
    }
  }

  void build_ball() {
    ball_shape = std::make_unique<btSphereShape>(params.ball_radius);
    btVector3 inertia(0, 0, 0);
    ball_shape->calculateLocalInertia(params.ball_mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(params.ball_mass, nullptr, ball_shape.get(), inertia);
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(bt(0, 0, params.ball_radius));
    // Frictionless everywhere (carpet friction is ball_model.h; Bullet friction is poor at rolling), and
    // restitution 1, so Bullet's product rule gives each contact the restitution of the other body.
    info.m_friction = 0;
    info.m_rollingFriction = 0;
    info.m_restitution = 1;
    info.m_linearDamping = 0;
    info.m_angularDamping = 0;
    ball = std::make_unique<btRigidBody>(info);
    ball->setAngularFactor(0);  // the spin lives in ball_spin
    ball->setFlags(0);          // no gyroscopic term (the body does not rotate)
    ball->setActivationState(DISABLE_DEACTIVATION);
    // Solve only touching contacts of the ball. Bullet also solves "speculative" contacts found up to a
    // fraction of a millimetre before impact, and then lets the ball approach by that gap in the step,
    // which takes up to gap / step off a bounce (10 % at 2 m/s): restitution would depend on the phase.
    ball->setContactProcessingThreshold(0);
    // Continuous collision detection only matters above ~radius per sub-step (> 10 m/s at 2 ms).
    ball->setCcdMotionThreshold(params.ball_radius);
    ball->setCcdSweptSphereRadius(params.ball_radius * 0.8);
    world.addRigidBody(ball.get(), kGroupBall, kMaskBall);
  }

  std::unique_ptr<btRigidBody> make_robot_body(const RobotSpec& spec, RobotHullShape* hull,
                                               const btTransform& transform) {
    btVector3 inertia(0, 0, 0);
    hull->calculateLocalInertia(spec.mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(spec.mass, nullptr, hull, inertia);
    info.m_startWorldTransform = transform;
    info.m_friction = params.robot_friction;
    info.m_restitution = params.ball_restitution_robot;
    info.m_linearDamping = 0;
    info.m_angularDamping = 0;
    auto body = std::make_unique<btRigidBody>(info);
    body->setLinearFactor(bt(1, 1, 0));
    body->setAngularFactor(bt(0, 0, 1));
    body->setActivationState(DISABLE_DEACTIVATION);
    body->setFlags(0);  // no gyroscopic term: the body only turns about z, where it is zero anyway
    return body;
  }

  bool set_team_spec(TeamColor team, const RobotSpec& spec) {
    if (validate_spec(spec)) return false;
    const std::size_t index = team_index(team);
    auto hull = std::make_unique<RobotHullShape>(spec);
    for (auto& [key, robot] : robots) {
      if (key.team != team) continue;
      btRigidBody* body = robot.body.get();
      const btTransform transform = body->getWorldTransform();
      const btVector3 velocity = body->getLinearVelocity();
      const btVector3 angular = body->getAngularVelocity();
      world.removeRigidBody(body);
      btTransform lifted = transform;
      lifted.getOrigin().setZ(spec.height / 2);
      robot.body = make_robot_body(spec, hull.get(), lifted);
      robot.body->setLinearVelocity(velocity);
      robot.body->setAngularVelocity(angular);
      world.addRigidBody(robot.body.get(), kGroupRobot, kMaskRobot);
    }
    specs[index] = spec;
    hulls[index] = std::move(hull);
    return true;
  }

  // --- ball and dribbler geometry ---

  // Ball centre in the robot frame (x forward, y left), and the distance along x at which it touches
  // the flat front.
  struct FrontRelation {
    Vec2 local;
    double touch_x;
  };
  FrontRelation front_relation(const Robot& robot) const {
    const RobotSpec& spec = specs[team_index(robot.key.team)];
    const btTransform& transform = robot.body->getWorldTransform();
    const btVector3& ball_position = ball->getWorldTransform().getOrigin();
    const Vec2 forward = heading_of(transform);
    const Vec2 offset(ball_position.x() - transform.getOrigin().x(),
                      ball_position.y() - transform.getOrigin().y());
    return {Vec2(forward.dot(offset), geom::cross(forward, offset)),
            spec.center_to_dribbler + params.ball_radius};
  }

  bool ball_touches_front(const Robot& robot) const {
    const RobotSpec& spec = specs[team_index(robot.key.team)];
    const btVector3& ball_position = ball->getWorldTransform().getOrigin();
    if (ball_position.z() > params.ball_radius + params.dribbler_max_ball_height) return false;
    // Cheap rejection first: most robots are far from the ball.
    const btVector3& centre = robot.body->getWorldTransform().getOrigin();
    const double reach = spec.center_to_dribbler + params.ball_radius + params.dribbler_contact_tolerance;
    const double dx = ball_position.x() - centre.x();
    const double dy = ball_position.y() - centre.y();
    if (dx * dx + dy * dy > reach * reach + spec.dribbler_width * spec.dribbler_width / 4) return false;
    const FrontRelation r = front_relation(robot);
    return std::abs(r.local.x() - r.touch_x) <= params.dribbler_contact_tolerance &&
           std::abs(r.local.y()) <= spec.dribbler_width / 2;
  }

  // --- one sub-step ---

  void drive_robot(Robot& robot, double h) {
    const RobotSpec& spec = specs[team_index(robot.key.team)];
    RobotLimits limits = spec.limits;
    limits.vel_absolute_max *= robot.speed_scale;
    limits.vel_angular_max *= robot.speed_scale;
    limits.acc_speedup_absolute_max *= robot.acceleration_scale;
    limits.acc_brake_absolute_max *= robot.acceleration_scale;
    limits.acc_speedup_angular_max *= robot.acceleration_scale;
    limits.acc_brake_angular_max *= robot.acceleration_scale;
    btRigidBody* body = robot.body.get();
    const RobotCommand& command = robot.command;
    Vec3 target = Vec3::Zero();  // local or global, see `local` below
    bool local = false;
    switch (command.move) {
      case RobotCommand::Move::kNone:
        break;
      case RobotCommand::Move::kLocalVelocity:
        target = command.velocity;
        local = true;
        break;
      case RobotCommand::Move::kGlobalVelocity:
        target = command.velocity;
        break;
      case RobotCommand::Move::kWheelVelocity:
        target = local_velocity_from_wheels(spec, spec.radius * params.wheel_distance_fraction,
                                            command.wheel_velocity);
        local = true;
        break;
    }
    const double target_angular = std::clamp(target.z(), -limits.vel_angular_max, limits.vel_angular_max);
    const double angular =
        ramp_angular_velocity(body->getAngularVelocity().z(), target_angular, limits.acc_speedup_angular_max,
                              limits.acc_brake_angular_max, h);
    Vec2 target_linear = target.head<2>();
    if (local) {
      // A local command follows the robot's heading; take the heading at mid-step (second order).
      const Vec2 forward = heading_of(body->getWorldTransform());
      const Vec2 mid_forward =
          angular == 0 ? forward : geom::rotate(forward, geom::Angle::from_radians(angular * h / 2));
      target_linear = target_linear.x() * mid_forward + target_linear.y() * geom::perpendicular(mid_forward);
    }
    target_linear = clamp_norm(target_linear, limits.vel_absolute_max);
    const btVector3& v = body->getLinearVelocity();
    const Vec2 linear = ramp_velocity(Vec2(v.x(), v.y()), target_linear, limits.acc_speedup_absolute_max,
                                      limits.acc_brake_absolute_max, h);
    body->setLinearVelocity(bt(linear.x(), linear.y(), 0));
    body->setAngularVelocity(bt(0, 0, angular));
  }

  void kick(const Robot& robot) {
    const RobotSpec& spec = specs[team_index(robot.key.team)];
    const double angle = robot.command.kick_angle;
    const double limit = angle > 0 ? spec.max_chip_kick_speed : spec.max_linear_kick_speed;
    const double speed = std::min(robot.command.kick_speed, limit);
    const Vec2 forward = heading_of(robot.body->getWorldTransform()).normalized();
    const Vec2 horizontal = speed * std::cos(angle) * forward;
    ball->setLinearVelocity(bt(horizontal.x(), horizontal.y(), speed * std::sin(angle)));
    ball_spin = Vec2::Zero();
  }

  void hold(const Robot& robot) {
    const btRigidBody* body = robot.body.get();
    const btTransform& transform = body->getWorldTransform();
    const FrontRelation relation = front_relation(robot);
    const Vec2 centre(transform.getOrigin().x(), transform.getOrigin().y());
    const Vec2 arm = relation.touch_x * heading_of(transform);
    const Vec2 target = centre + arm;
    const btVector3& v = body->getLinearVelocity();
    const double omega = body->getAngularVelocity().z();
    const Vec2 target_velocity = Vec2(v.x(), v.y()) + omega * Vec2(-arm.y(), arm.x());
    const btVector3& p = ball->getWorldTransform().getOrigin();
    const Vec2 correction = clamp_norm(params.dribbler_hold_gain * (target - Vec2(p.x(), p.y())),
                                       params.dribbler_max_correction_speed);
    const Vec2 velocity = target_velocity + correction;
    const double vz = std::min(0.0, params.dribbler_hold_gain * (params.ball_radius - p.z()));
    ball->setLinearVelocity(bt(velocity.x(), velocity.y(), vz));
    ball_spin = velocity;
  }

  void substep() {
    const double h = params.step;
    for (auto& [key, robot] : robots) drive_robot(robot, h);

    // Kicks and the dribbler, after the robots' velocities are set so a held ball moves with them.
    bool ball_controlled = false;
    bool ball_held = false;
    for (auto& [key, robot] : robots) {
      if (!ball_touches_front(robot)) {
        robot.kick_latched = false;
        continue;
      }
      if (ball_controlled || robot.kick_latched) continue;
      if (robot.command.kick_speed > 0) {
        kick(robot);
        robot.kick_latched = true;
        ball_controlled = true;
      } else if (robot.command.dribbler_rpm > 0) {
        hold(robot);
        ball_controlled = true;
        ball_held = true;
      }
    }

    const btVector3 ball_velocity_before = ball->getLinearVelocity();
    world.stepSimulation(h, 0, h);
    const btVector3& ball_velocity = ball->getLinearVelocity();

    if (ball_held) {
      ball_spin = Vec2(ball_velocity.x(), ball_velocity.y());
      return;
    }
    // A wall, goal or robot contact changed the horizontal velocity (the carpet cannot: it is frictionless
    // in Bullet and its normal is vertical).
    if (ball_velocity.x() != ball_velocity_before.x() || ball_velocity.y() != ball_velocity_before.y()) {
      ball_spin *= params.ball_collision_spin_retention;
    }
    const double ball_z = ball->getWorldTransform().getOrigin().z();
    if (ball_z > params.ball_radius + kGroundSlop) return;
    // Normal impulse per unit mass from the carpet: what the solver added on top of gravity.
    const double normal_delta_v = ball_velocity.z() - (ball_velocity_before.z() - params.gravity * h);
    if (normal_delta_v <= 0) return;
    BallGroundMotion motion{Vec2(ball_velocity.x(), ball_velocity.y()), ball_spin};
    apply_carpet_friction(motion, normal_delta_v, params);
    ball->setLinearVelocity(bt(motion.velocity.x(), motion.velocity.y(), ball_velocity.z()));
    ball_spin = motion.spin_velocity;
  }

  void step(time::Duration dt) {
    if (dt.count() <= 0) return;
    pending_ns += dt.count();
    while (pending_ns >= step_ns) {
      substep();
      pending_ns -= step_ns;
      now += time::Duration(step_ns);
    }
  }

  WorldSnapshot snapshot() const {
    WorldSnapshot snap;
    snap.time = now;
    const btVector3& p = ball->getWorldTransform().getOrigin();
    const btVector3& v = ball->getLinearVelocity();
    snap.ball.position = Vec3(p.x(), p.y(), p.z());
    snap.ball.velocity = Vec3(v.x(), v.y(), v.z());
    snap.robots.reserve(robots.size());
    for (const auto& [key, robot] : robots) {
      const btTransform& transform = robot.body->getWorldTransform();
      const btVector3& rv = robot.body->getLinearVelocity();
      RobotState state;
      state.key = key;
      state.position = Vec2(transform.getOrigin().x(), transform.getOrigin().y());
      state.orientation = yaw_of(transform);
      state.velocity = Vec2(rv.x(), rv.y());
      state.angular_velocity = robot.body->getAngularVelocity().z();
      state.ball_contact = ball_touches_front(robot);
      snap.robots.push_back(state);
    }
    return snap;
  }
};

PhysicsWorld::PhysicsWorld(const FieldGeometry& field, const PhysicsParams& params) {
  if (auto error = validate_field(field)) throw std::invalid_argument("FieldGeometry: " + *error);
  if (auto error = validate(params)) throw std::invalid_argument("PhysicsParams: " + *error);
  impl_ = std::make_unique<Impl>(field, params);
}

PhysicsWorld::~PhysicsWorld() = default;
PhysicsWorld::PhysicsWorld(PhysicsWorld&&) noexcept = default;
PhysicsWorld& PhysicsWorld::operator=(PhysicsWorld&&) noexcept = default;

bool PhysicsWorld::set_team_spec(TeamColor team, const RobotSpec& spec) {
  return impl_->set_team_spec(team, spec);
}

const RobotSpec& PhysicsWorld::team_spec(TeamColor team) const {
  return impl_->specs[Impl::team_index(team)];
}

bool PhysicsWorld::add_robot(RobotKey key, Vec2 position, double orientation) {
  if (key.id >= kMaxRobotsPerTeam || !finite(position) || !finite(orientation)) return false;
  if (impl_->robots.contains(key)) return false;
  const std::size_t team = Impl::team_index(key.team);
  const RobotSpec& spec = impl_->specs[team];
  Impl::Robot robot;
  robot.key = key;
  robot.body =
      impl_->make_robot_body(spec, impl_->hulls[team].get(), pose(position, spec.height / 2, orientation));
  impl_->world.addRigidBody(robot.body.get(), kGroupRobot, kMaskRobot);
  impl_->robots.emplace(key, std::move(robot));
  return true;
}

bool PhysicsWorld::set_robot_limit_scale(RobotKey key, double speed, double acceleration) {
  const auto it = impl_->robots.find(key);
  if (it == impl_->robots.end() || !(std::isfinite(speed) && speed > 0) ||
      !(std::isfinite(acceleration) && acceleration > 0)) {
    return false;
  }
  it->second.speed_scale = speed;
  it->second.acceleration_scale = acceleration;
  return true;
}

bool PhysicsWorld::remove_robot(RobotKey key) {
  const auto it = impl_->robots.find(key);
  if (it == impl_->robots.end()) return false;
  impl_->world.removeRigidBody(it->second.body.get());
  impl_->robots.erase(it);
  return true;
}

bool PhysicsWorld::has_robot(RobotKey key) const { return impl_->robots.contains(key); }

bool PhysicsWorld::teleport_robot(RobotKey key, Vec2 position, double orientation, Vec2 velocity,
                                  double angular_velocity) {
  const auto it = impl_->robots.find(key);
  if (it == impl_->robots.end()) return false;
  if (!finite(position) || !finite(orientation) || !finite(velocity) || !finite(angular_velocity)) {
    return false;
  }
  const RobotSpec& spec = impl_->specs[Impl::team_index(key.team)];
  btRigidBody* body = it->second.body.get();
  const btTransform transform = pose(position, spec.height / 2, orientation);
  body->setWorldTransform(transform);
  body->setInterpolationWorldTransform(transform);
  body->setLinearVelocity(bt(velocity.x(), velocity.y(), 0));
  body->setAngularVelocity(bt(0, 0, angular_velocity));
  body->clearForces();
  return true;
}

bool PhysicsWorld::teleport_ball(const Vec3& position, const Vec3& velocity, BallSpin spin) {
  if (!finite(position) || !finite(velocity)) return false;
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(bt(position.x(), position.y(), std::max(position.z(), impl_->params.ball_radius)));
  btRigidBody* ball = impl_->ball.get();
  ball->setWorldTransform(transform);
  ball->setInterpolationWorldTransform(transform);
  ball->setLinearVelocity(bt(velocity.x(), velocity.y(), velocity.z()));
  ball->setAngularVelocity(bt(0, 0, 0));
  ball->clearForces();
  impl_->ball_spin = spin == BallSpin::kRolling ? Vec2(velocity.x(), velocity.y()) : Vec2::Zero();
  for (auto& [key, robot] : impl_->robots) robot.kick_latched = false;
  return true;
}

bool PhysicsWorld::set_command(RobotKey key, const RobotCommand& command) {
  const auto it = impl_->robots.find(key);
  if (it == impl_->robots.end() || !command_valid(command)) return false;
  it->second.command = command;
  return true;
}

std::optional<RobotCommand> PhysicsWorld::command(RobotKey key) const {
  const auto it = impl_->robots.find(key);
  if (it == impl_->robots.end()) return std::nullopt;
  return it->second.command;
}

void PhysicsWorld::step(time::Duration dt) { impl_->step(dt); }
WorldSnapshot PhysicsWorld::snapshot() const { return impl_->snapshot(); }
time::Timestamp PhysicsWorld::time() const { return impl_->now; }
const FieldGeometry& PhysicsWorld::field() const { return impl_->field; }
const PhysicsParams& PhysicsWorld::params() const { return impl_->params; }

}  // namespace ssl::sim
