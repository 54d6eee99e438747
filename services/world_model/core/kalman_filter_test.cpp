#include "services/world_model/core/kalman_filter.h"

#include <gtest/gtest.h>

namespace ssl::wm {
namespace {

TEST(WorldModelKalmanFilter, ConstantPositionConvergesToTheMeanOfMeasurements) {
  KalmanFilter<1, 1> kf(KalmanFilter<1, 1>::State(0.0), KalmanFilter<1, 1>::StateMatrix(100.0));
  kf.H(0, 0) = 1;
  kf.R(0, 0) = 1;
  const double z[] = {1.0, 3.0, 2.0, 2.0};
  for (double m : z) {
    kf.predict(true);
    kf.update(KalmanFilter<1, 1>::Measurement(m));
  }
  EXPECT_NEAR(kf.state()(0), 2.0, 0.01);
  EXPECT_LT(kf.covariance()(0, 0), 0.26);
}

TEST(WorldModelKalmanFilter, PredictWithoutCommitLeavesTheStateUnchanged) {
  KalmanFilter<2, 1>::State x0(1.0, 2.0);
  KalmanFilter<2, 1> kf(x0, KalmanFilter<2, 1>::StateMatrix::Identity());
  kf.F << 1, 0.5, 0, 1;
  kf.predict(false);
  EXPECT_DOUBLE_EQ(kf.predicted_state()(0), 2.0);
  EXPECT_DOUBLE_EQ(kf.state()(0), 1.0);
  kf.predict(true);
  EXPECT_DOUBLE_EQ(kf.state()(0), 2.0);
}

}  // namespace
}  // namespace ssl::wm
