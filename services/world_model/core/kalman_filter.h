// KalmanFilter<N, M>: a fixed-size linear Kalman filter on Eigen matrices (no heap allocation), in the
// shape of ER-Force's tracking/kalmanfilter.h: the owner sets the textbook matrices (F, B*u as `u`, Q, H,
// R) before each step and calls predict() / update(). Units and frames are the owner's; this class only
// does the algebra.
//
//   KalmanFilter<4, 2> kf(x0, p0);
//   kf.F = ...; kf.Q = ...;
//   kf.predict(true);          // commit: x = F x + u, P = F P F^T + Q
//   kf.H = ...; kf.R = ...;
//   kf.update(z);              // or update_with_innovation(y) for wrapped angles
//   kf.predict(false);         // look ahead without changing the committed state (latency compensation)
//   State ahead = kf.predicted_state();
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace ssl::wm {

template <int N, int M>
class KalmanFilter {
 public:
  using State = Eigen::Matrix<double, N, 1>;
  using StateMatrix = Eigen::Matrix<double, N, N>;
  using Measurement = Eigen::Matrix<double, M, 1>;
  using MeasurementMatrix = Eigen::Matrix<double, M, N>;
  using MeasurementCovariance = Eigen::Matrix<double, M, M>;

  KalmanFilter() : KalmanFilter(State::Zero(), StateMatrix::Identity()) {}
  KalmanFilter(const State& x0, const StateMatrix& p0) { reset(x0, p0); }

  //! Sets the committed and predicted state and covariance.
  void reset(const State& x0, const StateMatrix& p0) {
    x_ = x0;
    p_ = p0;
    xm_ = x0;
    pm_ = p0;
    F.setIdentity();
    u.setZero();
    Q.setZero();
    H.setZero();
    R.setIdentity();
  }

  //! Prediction with F, u and Q. `permanent`: commit it as the new state (a measurement step follows or
  //! time simply advances); otherwise only predicted_state() changes.
  void predict(bool permanent) {
    xm_ = F * x_ + u;
    pm_ = F * p_ * F.transpose() + Q;
    if (permanent) {
      x_ = xm_;
      p_ = pm_;
    }
  }

  //! Innovation z - H x of the committed state.
  Measurement innovation(const Measurement& z) const { return z - H * x_; }

  //! Innovation covariance S = H P H^T + R.
  MeasurementCovariance innovation_covariance() const { return H * p_ * H.transpose() + R; }

  //! Squared Mahalanobis distance of an innovation: the gate statistic (chi-square with M dof).
  double mahalanobis2(const Measurement& y) const { return y.dot(innovation_covariance().inverse() * y); }

  //! Measurement update of the committed state with z (H, R set by the owner).
  void update(const Measurement& z) { update_with_innovation(innovation(z)); }

  //! Measurement update with a precomputed innovation (for angles, wrap it first).
  void update_with_innovation(const Measurement& y) {
    const MeasurementCovariance s = innovation_covariance();
    const Eigen::Matrix<double, N, M> k = p_ * H.transpose() * s.inverse();
    x_ += k * y;
    // Joseph form keeps P symmetric positive definite.
    const StateMatrix i_kh = StateMatrix::Identity() - k * H;
    p_ = i_kh * p_ * i_kh.transpose() + k * R * k.transpose();
    xm_ = x_;
    pm_ = p_;
  }

  const State& state() const { return x_; }
  State& mutable_state() { return x_; }
  const StateMatrix& covariance() const { return p_; }
  StateMatrix& mutable_covariance() { return p_; }
  const State& predicted_state() const { return xm_; }
  const StateMatrix& predicted_covariance() const { return pm_; }

  StateMatrix F;                    //!< state transition
  State u;                          //!< control input already multiplied by B (state increment)
  StateMatrix Q;                    //!< process noise covariance
  MeasurementMatrix H;              //!< measurement model
  MeasurementCovariance R;          //!< measurement noise covariance

 private:
  State x_;                         //!< committed state
  StateMatrix p_;                   //!< committed covariance
  State xm_;                        //!< predicted state (predict(false))
  StateMatrix pm_;                  //!< predicted covariance
};

}  // namespace ssl::wm
