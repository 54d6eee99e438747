#include "services/world_model/core/chip_estimator.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ssl::wm {
namespace {

using Theta = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Row6 = Eigen::Matrix<double, 1, 6>;

// theta = (q.x, q.y, w.x, w.y, a0, a1): b.xy = q + w s, b.z = a0 + a1 s - g s^2 / 2.
enum : int { kQx = 0, kQy = 1, kWx = 2, kWy = 3, kA0 = 4, kA1 = 5 };

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }
bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// Solves N x = rhs for a symmetric positive semi-definite N after scaling it to unit diagonal (Cholesky,
// LDL^T); false when the scaled matrix's estimated reciprocal condition number is below min_rcond, or
// something is not finite. `inverse`, when given, receives N^-1.
bool solve_normal(const Matrix6& n, const Theta& rhs, double min_rcond, Theta& x, Matrix6* inverse) {
  const Theta diag = n.diagonal();
  if (!n.allFinite() || !rhs.allFinite() || (diag.array() <= 0).any()) return false;
  const Theta scale = diag.cwiseSqrt().cwiseInverse();
  const Matrix6 scaled = scale.asDiagonal() * n * scale.asDiagonal();
  const Eigen::LDLT<Matrix6> ldlt(scaled);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.rcond() > min_rcond)) return false;
  x = scale.asDiagonal() * ldlt.solve(scale.asDiagonal() * rhs);
  if (inverse != nullptr) {
    *inverse = scale.asDiagonal() * ldlt.solve(Matrix6::Identity()) * scale.asDiagonal();
  }
  return x.allFinite();
}

// Adds a detection row a (non-zero only at q.axis, w.axis, a0, a1: `values`) with right-hand side y to the
// normal equations: n += a^T a, v += a^T y.
inline void add_row(Matrix6& n, Theta& v, int axis, const Eigen::Vector4d& values, double y) {
  const int index[4] = {kQx + axis, kWx + axis, kA0, kA1};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) n(index[i], index[j]) += values(i) * values(j);
    v(index[i]) += values(i) * y;
  }
}

}  // namespace

// ---- ChipFit -------------------------------------------------------------------------------------------

ChipState ChipFit::state_at(time::Timestamp t) const {
  ChipState state;
  const double g = bounce.gravity;
  const double tau = time::to_seconds(t - t0);
  if (tau < 0) {
    state.position = origin;
    state.phase = ChipState::Phase::kBeforeKick;
    return state;
  }
  Vec2 p = origin.head<2>();
  Vec2 vxy = velocity.head<2>();
  double vz = std::max(0.0, velocity.z());
  double start = 0;  // s after t0 at which the current hop left the carpet
  int hop = 0;
  while (vz > 0 && g > 0) {
    const double duration = 2 * vz / g;
    if (tau < start + duration) {
      const double dt = tau - start;
      state.position << p + vxy * dt, bounce.ball_radius + vz * dt - g * dt * dt / 2;
      state.velocity << vxy, vz - g * dt;
      state.phase = ChipState::Phase::kAirborne;
      state.hop = hop;
      return state;
    }
    p += vxy * duration;
    start += duration;
    vxy *= hop == 0 ? bounce.damping_xy_first_hop : bounce.damping_xy_other_hops;
    vz *= bounce.damping_z;
    ++hop;
    if (vz < bounce.min_hop_speed || hop > bounce.max_hops) vz = 0;
  }
  // Rolling from (p, vxy) at `start` with constant deceleration until it stops.
  state.hop = hop;
  const double speed = vxy.norm();
  const double dt = tau - start;
  const double decel = bounce.roll_deceleration;
  if (speed <= 0) {
    state.position << p, bounce.ball_radius;
    state.phase = ChipState::Phase::kStopped;
    return state;
  }
  const Vec2 dir = vxy / speed;
  const double t_stop = decel > 0 ? speed / decel : std::numeric_limits<double>::infinity();
  const double moving = std::min(dt, t_stop);
  state.position << p + dir * (speed * moving - decel * moving * moving / 2), bounce.ball_radius;
  if (dt < t_stop) {
    state.velocity << dir * (speed - decel * dt), 0;
    state.phase = ChipState::Phase::kRolling;
  } else {
    state.phase = ChipState::Phase::kStopped;
  }
  return state;
}

// ---- ChipEstimator -------------------------------------------------------------------------------------

void ChipEstimator::reset() {
  cache_.valid = false;
  cache_.has_theta = false;
  count_ = 0;
  refused_ = 0;
  has_prior_ = false;
  has_direction_ = false;
  has_elevation_ = false;
  t_first_ = time::Timestamp::max();
}

void ChipEstimator::reset(const ChipKick& kick) {
  reset();
  const bool valid = finite(kick.position) && std::isfinite(kick.position_stddev) &&
                     kick.position_stddev > 0 && std::isfinite(kick.time_stddev) && kick.time_stddev >= 0;
  if (!valid) return;
  has_prior_ = true;
  kick_ = kick;
  if (kick.direction && finite(*kick.direction) && kick.direction->norm() > 1e-9 &&
      std::isfinite(kick.direction_stddev) && kick.direction_stddev > 0) {
    has_direction_ = true;
    kick_direction_ = kick.direction->normalized();
    kick_normal_ = geom::perpendicular(kick_direction_);
  }
  if (kick.elevation && std::isfinite(*kick.elevation) && *kick.elevation > 0 &&
      *kick.elevation < std::numbers::pi / 2 - 0.05 && std::isfinite(kick.elevation_stddev) &&
      kick.elevation_stddev > 0) {
    has_elevation_ = true;
    tan2_elevation_ = std::tan(*kick.elevation) * std::tan(*kick.elevation);
  }
}

void ChipEstimator::reset(const Vec2& kick_position, time::Timestamp t_kick) {
  reset(ChipKick{.position = kick_position, .time = t_kick});
}

bool ChipEstimator::add(const ChipObservation& observation) {
  const double r = params_.bounce.ball_radius;
  const bool valid = finite(observation.detection) && finite(observation.camera) &&
                     std::isfinite(observation.stddev) &&
                     observation.camera.z() - r >= params_.min_camera_height;
  if (!valid || count_ >= kMaxObservations) {
    ++refused_;
    return false;
  }
  // Keep capture-time order (cameras' frames arrive slightly out of order): insert from the back.
  int i = count_++;
  for (; i > 0 && observations_[static_cast<std::size_t>(i - 1)].t_capture > observation.t_capture; --i) {
    observations_[static_cast<std::size_t>(i)] = observations_[static_cast<std::size_t>(i - 1)];
  }
  observations_[static_cast<std::size_t>(i)] = observation;
  t_first_ = std::min(t_first_, observation.t_capture);
  if (i < cache_.count) cache_.valid = false;  // inserted among the detections the cache was made from
  if (i == 0 && !has_prior_) cache_.has_theta = false;  // t_ref moved: another parametrisation
  return true;
}

ChipEstimator::PriorStddevs ChipEstimator::prior_stddevs(const Vec2& w, double a1, double vz2) const {
  PriorStddevs s;
  const double st = kick_.time_stddev;
  const double sp = kick_.position_stddev;
  s.xy = std::sqrt(sp * sp + w.squaredNorm() * st * st);
  s.z = std::sqrt(a1 * a1 * st * st + 1e-6);  // >= 1 mm: the ball rests on a carpet, not on a plane
  s.direction = kick_.direction_stddev * std::max(w.norm(), 0.5);
  if (has_elevation_) {
    // v_z - tan(e) |w| has the stddev |w| de / cos^2(e); the squared form scales it by 2 v_z.
    const double vz_stddev = std::max(0.05, w.norm() * kick_.elevation_stddev * (1 + tan2_elevation_));
    s.elevation = 2 * std::sqrt(std::max(vz2, 0.25)) * vz_stddev;
  }
  return s;
}

bool ChipEstimator::linear_init(int n, Theta& theta) const {
  if (n < std::max(1, params_.min_observations) || n > count_) return false;
  const double g = params_.bounce.gravity;
  const double r = params_.bounce.ball_radius;
  const time::Timestamp ref = t_ref();
  Matrix6 normal = Matrix6::Zero();
  Theta rhs = Theta::Zero();
  for (int i = 0; i < n; ++i) {
    const ChipObservation& o = observations_[static_cast<std::size_t>(i)];
    const double s = time::to_seconds(o.t_capture - ref);
    const Vec3& c = o.camera;
    const double h = c.z() - r;
    const Vec2 u = o.detection - c.head<2>();
    const double weight = 1 / (stddev_of(o) * stddev_of(o));
    // b.xy + (u / H) b.z = c.xy + (u / H) c.z, with b.z = a0 + a1 s - g s^2 / 2.
    const double sw = std::sqrt(weight);
    for (int axis = 0; axis < 2; ++axis) {
      const double y = c(axis) + u(axis) * (c.z() + g * s * s / 2) / h;
      add_row(normal, rhs, axis, sw * Eigen::Vector4d(1, s, u(axis) / h, u(axis) * s / h), sw * y);
    }
  }
  if (has_prior_) {
    const double v = params_.prior_nominal_speed;
    const PriorStddevs prior = prior_stddevs(Vec2(v, v), v, v * v);
    const double wxy = 1 / (prior.xy * prior.xy), wz = 1 / (prior.z * prior.z);
    normal(kQx, kQx) += wxy;
    normal(kQy, kQy) += wxy;
    rhs(kQx) += kick_.position.x() * wxy;
    rhs(kQy) += kick_.position.y() * wxy;
    normal(kA0, kA0) += wz;
    rhs(kA0) += r * wz;
    if (has_direction_) {
      Row6 a = Row6::Zero();
      a(kWx) = kick_normal_.x();
      a(kWy) = kick_normal_.y();
      normal.noalias() += a.transpose() * a / (prior.direction * prior.direction);
    }
  }
  if (!solve_normal(normal, rhs, params_.min_reciprocal_condition, theta, nullptr)) return false;
  if (has_elevation_) {
    // Linearised elevation row for the start: a1 (~ v_z at the kick) = tan(e) (direction . w).
    const Vec2 w(theta(kWx), theta(kWy));
    Vec2 dir = has_direction_ ? kick_direction_ : Vec2::Zero();
    if (!has_direction_ && w.norm() > 0.1) dir = w.normalized();
    if (dir.squaredNorm() > 0) {
      const double tan_e = std::sqrt(tan2_elevation_);
      const double stddev =
          std::max(0.05, std::max(w.norm(), 0.5) * kick_.elevation_stddev * (1 + tan2_elevation_));
      Row6 a = Row6::Zero();
      a(kA1) = 1;
      a(kWx) = -tan_e * dir.x();
      a(kWy) = -tan_e * dir.y();
      normal.noalias() += a.transpose() * a / (stddev * stddev);
      if (!solve_normal(normal, rhs, params_.min_reciprocal_condition, theta, nullptr)) return false;
    }
  }
  if (has_prior_ && theta(kA1) < 0) {
    // The ball rises at the kick: the one-sided row a1 >= 0 is active (see refine()).
    normal(kA1, kA1) += 1 / (vertical_speed_stddev() * vertical_speed_stddev());
    if (!solve_normal(normal, rhs, params_.min_reciprocal_condition, theta, nullptr)) return false;
  }
  return true;
}

std::optional<ChipEstimator::Solution> ChipEstimator::refine(int n, Theta theta) const {
  if (n < std::max(1, params_.min_observations) || n > count_) return std::nullopt;
  const double g = params_.bounce.gravity;
  const double r = params_.bounce.ball_radius;
  const time::Timestamp ref = t_ref();

  // Normal equations of the exact detection-plane residuals at theta (Gauss-Newton).
  struct Evaluation {
    Matrix6 normal = Matrix6::Zero();
    Theta gradient = Theta::Zero();  // J^T r
    double chi2 = 0;
    double chi2_detections = 0;
    double ssr_m2 = 0;
    bool ok = false;
  };
  const auto evaluate = [&](const Theta& th) {
    Evaluation e;
    for (int i = 0; i < n; ++i) {
      const ChipObservation& o = observations_[static_cast<std::size_t>(i)];
      const double s = time::to_seconds(o.t_capture - ref);
      const Vec3& c = o.camera;
      const double h = c.z() - r;
      const Vec2 bxy(th(kQx) + th(kWx) * s, th(kQy) + th(kWy) * s);
      const double bz = th(kA0) + th(kA1) * s - g * s * s / 2;
      const double depth = c.z() - bz;
      if (!(depth > 0.05 * h)) return e;  // the ball would reach the camera: nonsense
      const double k = h / depth;
      const Vec2 rel = bxy - c.head<2>();
      const Vec2 residual = c.head<2>() + rel * k - o.detection;
      const double sigma = stddev_of(o);
      e.ssr_m2 += residual.squaredNorm();
      e.chi2_detections += residual.squaredNorm() / (sigma * sigma);
      for (int axis = 0; axis < 2; ++axis) {
        const double dz = rel(axis) * k / depth;  // d residual / d b.z
        const Eigen::Vector4d j = Eigen::Vector4d(k, k * s, dz, dz * s) / sigma;
        add_row(e.normal, e.gradient, axis, j, residual(axis) / sigma);
      }
    }
    e.chi2 = e.chi2_detections;
    if (has_prior_) {
      // Prior rows (linear in theta but for the elevation row; weights follow the current estimate).
      const Vec2 w(th(kWx), th(kWy));
      const double vz2 = th(kA1) * th(kA1) + 2 * g * (th(kA0) - r);
      const PriorStddevs prior = prior_stddevs(w, th(kA1), vz2);
      const double wxy = 1 / (prior.xy * prior.xy), wz = 1 / (prior.z * prior.z);
      const Vec2 dq(th(kQx) - kick_.position.x(), th(kQy) - kick_.position.y());
      const double dz = th(kA0) - r;
      e.chi2 += dq.squaredNorm() * wxy + dz * dz * wz;
      e.normal(kQx, kQx) += wxy;
      e.normal(kQy, kQy) += wxy;
      e.normal(kA0, kA0) += wz;
      e.gradient(kQx) += dq.x() * wxy;
      e.gradient(kQy) += dq.y() * wxy;
      e.gradient(kA0) += dz * wz;
      if (has_direction_) {
        Row6 a = Row6::Zero();
        a(kWx) = kick_normal_.x() / prior.direction;
        a(kWy) = kick_normal_.y() / prior.direction;
        const double across = kick_normal_.dot(w) / prior.direction;
        e.chi2 += across * across;
        e.normal.noalias() += a.transpose() * a;
        e.gradient.noalias() += across * a.transpose();
      }
      if (th(kA1) < 0) {
        // One-sided: at the kick the ball rises (a1 >= 0 within the time uncertainty). Without this row
        // z(t_kick) = r is also met by a parabola that LANDS at the kick.
        const double sa = vertical_speed_stddev();
        e.chi2 += th(kA1) * th(kA1) / (sa * sa);
        e.normal(kA1, kA1) += 1 / (sa * sa);
        e.gradient(kA1) += th(kA1) / (sa * sa);
      }
      if (has_elevation_) {
        // v_z^2 - tan^2(e) |w|^2: smooth in theta, also where v_z = 0.
        const double residual = (vz2 - tan2_elevation_ * w.squaredNorm()) / prior.elevation;
        Row6 a = Row6::Zero();
        a(kA0) = 2 * g;
        a(kA1) = 2 * th(kA1);
        a(kWx) = -2 * tan2_elevation_ * w.x();
        a(kWy) = -2 * tan2_elevation_ * w.y();
        a /= prior.elevation;
        e.chi2 += residual * residual;
        e.normal.noalias() += a.transpose() * a;
        e.gradient.noalias() += residual * a.transpose();
      }
    }
    e.ok = std::isfinite(e.chi2);
    return e;
  };

  Evaluation current = evaluate(theta);
  if (!current.ok) return std::nullopt;
  const double min_rcond = params_.min_reciprocal_condition;
  for (int iteration = 0; iteration < params_.gauss_newton_iterations; ++iteration) {
    Theta step;
    if (!solve_normal(current.normal, -current.gradient, min_rcond, step, nullptr)) return std::nullopt;
    // Converged: the step moves the ball by less than a micrometre over a second.
    if (step.cwiseAbs().maxCoeff() < 1e-7) break;
    bool accepted = false;
    for (int halving = 0; halving < 4 && !accepted; ++halving, step /= 2) {
      const Evaluation candidate = evaluate(theta + step);
      if (candidate.ok && candidate.chi2 <= current.chi2 * (1 + 1e-12) + 1e-15) {
        theta += step;
        current = candidate;
        accepted = true;
      }
    }
    if (!accepted) break;
  }

  Solution solution;
  Theta unused;
  if (!solve_normal(current.normal, Theta::Zero(), min_rcond, unused, &solution.covariance)) {
    return std::nullopt;
  }
  solution.theta = theta;
  solution.chi2 = current.chi2;
  solution.chi2_detections = current.chi2_detections;
  solution.sum_squared_residual_m2 = current.ssr_m2;
  solution.used = n;
  return solution;
}

ChipFit ChipEstimator::make_fit(const Solution& solution) const {
  const double g = params_.bounce.gravity;
  const double r = params_.bounce.ball_radius;
  const Theta& th = solution.theta;
  const Vec2 q(th(kQx), th(kQy));
  const Vec2 w(th(kWx), th(kWy));
  const double a0 = th(kA0), a1 = th(kA1);
  // Take-off and landing are where b.z = r; below-ground parabolas (noise on a flat ball) have no flight.
  const double discriminant = a1 * a1 + 2 * g * (a0 - r);
  const double vz = std::sqrt(std::max(0.0, discriminant));
  const double s0 = (a1 - vz) / g;
  const double s_land = (a1 + vz) / g;
  const time::Timestamp ref = t_ref();

  ChipFit fit;
  fit.origin << q + w * s0, r;
  fit.velocity << w, vz;
  fit.t0 = ref + time::duration_from_seconds(s0);
  fit.apex_time = ref + time::duration_from_seconds(a1 / g);
  fit.apex_height = r + vz * vz / (2 * g);
  fit.landing_time = ref + time::duration_from_seconds(s_land);
  fit.landing_point = q + w * s_land;
  fit.observations = solution.used;
  fit.chi2 = solution.chi2;
  fit.normalised_rms = std::sqrt(solution.chi2_detections / (2.0 * std::max(1, solution.used)));
  fit.rms_residual_m = std::sqrt(solution.sum_squared_residual_m2 / std::max(1, solution.used));
  fit.bounce = params_.bounce;

  // Linearised uncertainty (vz clamped away from 0, where the take-off is not differentiable).
  const double vz_safe = std::max(vz, 1e-6);
  const Matrix6& cov = solution.covariance;
  Eigen::Matrix<double, 3, 6> jv = Eigen::Matrix<double, 3, 6>::Zero();
  jv(0, kWx) = 1;
  jv(1, kWy) = 1;
  jv(2, kA0) = g / vz_safe;
  jv(2, kA1) = a1 / vz_safe;
  fit.velocity_covariance = jv * cov * jv.transpose();
  Eigen::Matrix<double, 2, 6> jl = Eigen::Matrix<double, 2, 6>::Zero();
  jl(0, kQx) = jl(1, kQy) = 1;
  jl(0, kWx) = jl(1, kWy) = s_land;
  jl.col(kA0) = w / vz_safe;                  // d s_land / d a0 = 1 / vz
  jl.col(kA1) = w * (1 + a1 / vz_safe) / g;   // d s_land / d a1
  fit.landing_covariance = jl * cov * jl.transpose();
  Row6 jt = Row6::Zero();
  jt(kA0) = -1 / vz_safe;
  jt(kA1) = (1 - a1 / vz_safe) / g;
  fit.t0_stddev = std::sqrt(std::max(0.0, (jt * cov * jt.transpose())(0, 0)));
  Row6 jland = Row6::Zero();
  jland(kA0) = 1 / vz_safe;
  jland(kA1) = (1 + a1 / vz_safe) / g;
  fit.landing_time_stddev = std::sqrt(std::max(0.0, (jland * cov * jland.transpose())(0, 0)));
  return fit;
}

time::Timestamp ChipEstimator::landed_after(const ChipFit& fit) const {
  // A detection is after the landing only when it is so beyond the fit's own uncertainty: an early noisy
  // fit must not cut the flight short.
  const double margin = params_.landing_guard + 3 * fit.landing_time_stddev;
  return fit.landing_time + time::duration_from_seconds(std::min(margin, 10.0));
}

bool ChipEstimator::consistent(const ChipFit& fit, int n) const {
  if (!(fit.normalised_rms <= params_.max_normalised_rms)) return false;
  if (fit.velocity.z() < params_.min_chip_vz) return true;  // no flight to end
  return observations_[static_cast<std::size_t>(n - 1)].t_capture <= landed_after(fit);
}

std::optional<ChipEstimator::Fitted> ChipEstimator::fit_first(int n, bool warm_start) const {
  std::optional<Solution> solution;
  Theta theta;
  if (linear_init(n, theta)) solution = refine(n, theta);
  // A poor local minimum (one camera, few detections, a nonlinear prior): try from the last fit too.
  if (warm_start && cache_.has_theta && (!solution || !consistent(make_fit(*solution), n))) {
    const std::optional<Solution> warm = refine(n, cache_.theta);
    if (warm && (!solution || warm->chi2 < solution->chi2)) solution = warm;
  }
  if (!solution) return std::nullopt;
  return Fitted{make_fit(*solution), solution->theta};
}

std::optional<ChipFit> ChipEstimator::fit_impl(int& used) const {
  if (cache_.valid && cache_.count == count_) {
    used = cache_.used;
    return cache_.fit;
  }
  std::optional<Fitted> result;
  bool done = false;
  if (cache_.valid && cache_.fit && cache_.used < cache_.count) {
    // Later hops were seen: the prefix found then stands (fits of it do not change) unless the
    // detections are now all explained. One fit instead of a bisection.
    result = fit_first(count_, false);
    if (!result || !consistent(result->fit, count_)) {
      cache_.count = count_;
      used = cache_.used;
      return cache_.fit;
    }
    used = count_;
    done = true;
  }
  if (!done) result = fit_uncached(used);
  cache_.valid = true;
  cache_.count = count_;
  cache_.used = used;
  cache_.has_flat = false;
  cache_.flat.reset();
  cache_.fit.reset();
  if (result) {
    cache_.fit = result->fit;
    cache_.theta = result->theta;
    cache_.has_theta = true;
  }
  return cache_.fit;
}

std::optional<ChipEstimator::Fitted> ChipEstimator::fit_uncached(int& used) const {
  used = count_;
  std::optional<Fitted> all = fit_first(count_);
  if (all && consistent(all->fit, count_)) return all;

  // Later hops (or garbage) among the detections: the longest consistent prefix, by bisection.
  int lo = std::max(1, params_.min_observations);
  int hi = count_;
  std::optional<Fitted> best = fit_first(lo);
  if (!best || lo >= hi) return all;
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    std::optional<Fitted> f = fit_first(mid);
    if (f && consistent(f->fit, mid)) {
      lo = mid;
      best = f;
    } else {
      hi = mid;
    }
  }
  used = lo;
  // ... then exactly the detections before the landing (+ landing_guard): there are later hops here. The
  // prefix may hold a detection or two of the next hop, so the landing moves a little: repeat until stable.
  for (int pass = 0; pass < 3 && best->fit.velocity.z() >= params_.min_chip_vz; ++pass) {
    const time::Timestamp limit = best->fit.landing_time + time::duration_from_seconds(params_.landing_guard);
    int m = 0;
    while (m < count_ && observations_[static_cast<std::size_t>(m)].t_capture <= limit) ++m;
    if (m == used || m < params_.min_observations) break;
    std::optional<Fitted> trimmed = fit_first(m);
    if (!trimmed || !(trimmed->fit.normalised_rms <= params_.max_normalised_rms)) break;
    best = trimmed;
    used = m;
  }
  return best;
}

std::optional<ChipFit> ChipEstimator::fit() const {
  int used = 0;
  return fit_impl(used);
}

std::optional<FlatFit> ChipEstimator::fit_flat(int n, const PriorStddevs& prior) const {
  // Moments of the detections (weights 1 / sigma^2, isotropic), positions relative to `centre`. With them
  // the flat model's least squares for any direction is closed-form, without another pass over the data.
  if (n < 3 || n > count_) return std::nullopt;
  const time::Timestamp ref = t_ref();
  const Vec2 centre = has_prior_ ? kick_.position : observations_[0].detection;
  double m[5] = {0, 0, 0, 0, 0};                            // sum W s^k
  Vec2 dm[3] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};  // sum W s^k d
  double energy = 0;                                        // sum W |d|^2
  const auto accumulate = [&](double weight, double s, const Vec2& d) {
    double sk = 1;
    for (int k = 0; k < 5; ++k, sk *= s) {
      m[k] += weight * sk;
      if (k < 3) dm[k] += weight * sk * d;
    }
    energy += weight * d.squaredNorm();
  };
  for (int i = 0; i < n; ++i) {
    const ChipObservation& o = observations_[static_cast<std::size_t>(i)];
    const double sigma = stddev_of(o);
    accumulate(1 / (sigma * sigma), time::to_seconds(o.t_capture - ref), o.detection - centre);
  }
  // The kick position prior is one more "detection" at s = 0 (the ball on the carpet: no z row needed).
  if (has_prior_) accumulate(1 / (prior.xy * prior.xy), 0, Vec2::Zero());

  if (!(m[0] > 0)) return std::nullopt;
  const double lo = params_.flat_min_deceleration, hi = params_.flat_max_deceleration;
  // For a direction, q is eliminated (the weighted mean), leaving chi2 over x = (speed, deceleration) with
  // the basis (s, -s^2 / 2): chi2 = e - 2 g.x + x^T C x, C and e from the centred moments.
  const double c11 = m[2] - m[1] * m[1] / m[0];
  const double c12 = -(m[3] - m[1] * m[2] / m[0]) / 2;
  const double c22 = (m[4] - m[2] * m[2] / m[0]) / 4;
  const Vec2 d1 = dm[1] - dm[0] * (m[1] / m[0]);
  const Vec2 d2 = dm[2] - dm[0] * (m[2] / m[0]);
  const double e0 = energy - dm[0].squaredNorm() / m[0];
  const double det = c11 * c22 - c12 * c12;
  if (!(c11 > 0)) return std::nullopt;
  const auto evaluate = [&](double angle, Eigen::Vector2d& x) {
    const Vec2 dir(std::cos(angle), std::sin(angle));
    const double g1 = dir.dot(d1), g2 = -dir.dot(d2) / 2;
    bool inside = false;
    if (det > 1e-12 * c11 * c22) {
      x << (c22 * g1 - c12 * g2) / det, (c11 * g2 - c12 * g1) / det;
      inside = x(1) >= lo && x(1) <= hi;
    }
    if (!inside) {
      // Deceleration at its bound (or undetermined): the best speed for it.
      const double decel = det > 1e-12 * c11 * c22 ? std::clamp(x(1), lo, hi) : lo;
      x << (g1 - c12 * decel) / c11, decel;
    }
    double chi2 = std::max(0.0, e0 - 2 * (g1 * x(0) + g2 * x(1)) +
                                    (c11 * x(0) * x(0) + 2 * c12 * x(0) * x(1) + c22 * x(1) * x(1)));
    if (has_direction_) {
      const double stddev = kick_.direction_stddev * std::max(std::abs(x(0)), 0.5);
      const double across = kick_normal_.dot(dir) * x(0) / stddev;
      chi2 += across * across;
    }
    return std::isfinite(chi2) ? chi2 : std::numeric_limits<double>::infinity();
  };

  // The direction: a coarse scan of the circle (chi2 is not unimodal in it: the speed may be negative, the
  // deceleration is bounded), then a golden-section search around the best.
  constexpr int kScan = 24;
  constexpr double kTwoPi = 2 * std::numbers::pi;
  Eigen::Vector2d x;
  double best_angle = 0;
  double best_chi2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kScan; ++i) {
    const double angle = kTwoPi * i / kScan;
    const double chi2 = evaluate(angle, x);
    if (chi2 < best_chi2) {
      best_chi2 = chi2;
      best_angle = angle;
    }
  }
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double a = best_angle - kTwoPi / kScan, b = best_angle + kTwoPi / kScan;
  double c1 = b - ratio * (b - a), c2 = a + ratio * (b - a);
  double f1 = evaluate(c1, x), f2 = evaluate(c2, x);
  for (int i = 0; i < 24; ++i) {
    if (f1 < f2) {
      b = c2;
      c2 = c1;
      f2 = f1;
      c1 = b - ratio * (b - a);
      f1 = evaluate(c1, x);
    } else {
      a = c1;
      c1 = c2;
      f1 = f2;
      c2 = a + ratio * (b - a);
      f2 = evaluate(c2, x);
    }
  }
  if (std::min(f1, f2) < best_chi2) {
    best_angle = f1 < f2 ? c1 : c2;
    best_chi2 = std::min(f1, f2);
  }
  if (!std::isfinite(best_chi2)) return std::nullopt;
  evaluate(best_angle, x);

  FlatFit flat;
  flat.direction = Vec2(std::cos(best_angle), std::sin(best_angle));
  flat.speed = x(0);
  flat.deceleration = x(1);
  flat.origin = centre + (dm[0] - flat.direction * (x(0) * m[1] - x(1) * m[2] / 2)) / m[0];
  flat.chi2 = best_chi2;
  double ssr = 0;
  for (int i = 0; i < n; ++i) {
    const ChipObservation& o = observations_[static_cast<std::size_t>(i)];
    const double s = time::to_seconds(o.t_capture - ref);
    const Vec2 model = flat.origin + flat.direction * (flat.speed * s - flat.deceleration * s * s / 2);
    ssr += (o.detection - model).squaredNorm();
  }
  flat.rms_residual_m = std::sqrt(ssr / n);
  return flat;
}

ChipClassification ChipEstimator::classify() const {
  ChipClassification result;
  int used = 0;
  result.chip = fit_impl(used);
  if (!result.chip) return result;
  // The prior's weights of the chip fit, so that both hypotheses pay for the kick alike.
  if (!cache_.has_flat) {
    const Vec2 w = result.chip->velocity.head<2>();
    const double vz = result.chip->velocity.z();
    cache_.flat = fit_flat(result.chip->observations, prior_stddevs(w, vz, vz * vz));
    cache_.has_flat = true;
  }
  result.flat = cache_.flat;
  if (!result.flat) return result;
  result.chi2_margin = result.flat->chi2 - result.chip->chi2;
  // Detections noisier than assumed inflate both chi2s alike: scale the margin by the chip fit's noise
  // estimate when that is above 1 (an F-test in spirit), so more noise needs more evidence.
  const double noise_scale = std::max(1.0, result.chip->normalised_rms * result.chip->normalised_rms);
  result.is_chip = result.chip->observations >= params_.min_classify_observations &&
                   result.chip->velocity.z() >= params_.min_chip_vz &&
                   result.chip->velocity.norm() <= params_.max_chip_speed &&
                   result.chi2_margin / noise_scale >= params_.chip_chi2_margin &&
                   result.chip->normalised_rms <= params_.max_normalised_rms;
  return result;
}

}  // namespace ssl::wm
