#include "tests/support/validation.h"

#include <gtest/gtest.h>

#include <cstdio>


namespace ssl::testing {

void Always::require(bool holds, double t, const std::function<std::string()>& detail) {
  ++evaluated_;
  if (holds) return;
  if (failures_++ == 0) first_ = "t=" + fmt(t) + " s: " + detail();
}

void Always::report() const {
  EXPECT_GT(evaluated_, 0) << name_ << ": never evaluated (scenario too short?)";
  EXPECT_EQ(failures_, 0) << name_ << " failed at " << failures_ << " of " << evaluated_ << " evaluations; first "
                          << first_;
}

std::string Always::fmt(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", value);
  return text;
}

bool Eventually::update(bool now_true, double t) {
  if (done_) return true;
  if (!now_true) {
    since_.reset();
    return false;
  }
  if (!since_) since_ = t;
  if (t - *since_ >= hold_ - 1e-9 && *since_ <= deadline_) {
    done_ = true;
    at_ = *since_;
  }
  return done_;
}

void Eventually::report(const std::string& detail) const {
  EXPECT_TRUE(done_) << name_ << " did not happen within " << deadline_ << " s " << detail;
}

}  // namespace ssl::testing
