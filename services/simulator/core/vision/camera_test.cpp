#include "services/simulator/core/vision/camera.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace ssl::sim {
namespace {

// Points on a grid over the rectangle with step <= `step`, including its edges and corners exactly.
std::vector<Vec2> grid_over(const geom::Rectangle& area, double step) {
  const int nx = static_cast<int>(std::ceil(area.width() / step));
  const int ny = static_cast<int>(std::ceil(area.height() / step));
  std::vector<Vec2> points;
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) {
      points.emplace_back(i == nx ? area.max().x() : area.min().x() + i * area.width() / nx,
                          j == ny ? area.max().y() : area.min().y() + j * area.height() / ny);
    }
  }
  return points;
}

TEST(SimVisionCameraTest, GridShapesForEverySupportedCount) {
  EXPECT_EQ(camera_grid(1).columns * camera_grid(1).rows, 1);
  EXPECT_EQ(camera_grid(2).columns, 2);
  EXPECT_EQ(camera_grid(4).columns, 2);
  EXPECT_EQ(camera_grid(4).rows, 2);
  EXPECT_EQ(camera_grid(6).columns, 3);
  EXPECT_EQ(camera_grid(8).columns, 4);
  EXPECT_EQ(camera_grid(8).rows, 2);
  EXPECT_THROW(camera_grid(5), std::invalid_argument);
}

TEST(SimVisionCameraTest, TilesCoverTheFieldAndBoundaryForEveryCameraCount) {
  for (const FieldGeometry& field : {FieldGeometry::division_a(), FieldGeometry::division_b()}) {
    const geom::Rectangle area = covered_area(field);
    EXPECT_DOUBLE_EQ(area.max().x(), 0.5 * field.field_length + field.boundary_width_goal_line);
    EXPECT_DOUBLE_EQ(area.max().y(), 0.5 * field.field_width + field.boundary_width);
    for (int count : {1, 2, 4, 6, 8}) {
      SCOPED_TRACE("cameras: " + std::to_string(count));
      VisionConfig config;
      config.camera_count = count;
      config.camera_overlap = 0.0;  // the tiles alone must cover everything
      const std::vector<CameraView> cameras = make_camera_layout(field, config);
      ASSERT_EQ(cameras.size(), static_cast<std::size_t>(count));
      double tile_area = 0;
      for (const CameraView& camera : cameras) tile_area += camera.tile.area();
      EXPECT_NEAR(tile_area, area.area(), 1e-9);
      for (const Vec2& p : grid_over(area, 0.05)) {
        int seen = 0;
        for (const CameraView& camera : cameras) seen += camera.view.contains(p) ? 1 : 0;
        ASSERT_GE(seen, 1) << p.transpose();
      }
    }
  }
}

TEST(SimVisionCameraTest, CamerasHangAboveTheirTilesAndCountAlongXFirst) {
  VisionConfig config;
  config.camera_count = 4;
  const std::vector<CameraView> cameras = make_camera_layout(FieldGeometry::division_a(), config);
  // Covered area 13.2 x 9.6 m: tile centres at (+-3.3, +-2.4).
  const std::vector<Vec2> centres{{-3.3, -2.4}, {3.3, -2.4}, {-3.3, 2.4}, {3.3, 2.4}};
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    EXPECT_EQ(cameras[i].camera_id, i);
    EXPECT_NEAR(cameras[i].position.x(), centres[i].x(), 1e-12);
    EXPECT_NEAR(cameras[i].position.y(), centres[i].y(), 1e-12);
    EXPECT_DOUBLE_EQ(cameras[i].position.z(), 4.0);
    EXPECT_NEAR(cameras[i].view.width(), cameras[i].tile.width() + 0.6, 1e-12);  // overlap on both sides
  }
}

TEST(SimVisionCameraTest, CalibrationProjectsTheViewIntoTheImageAndBack) {
  for (int count : {1, 2, 4, 6, 8}) {
    SCOPED_TRACE("cameras: " + std::to_string(count));
    VisionConfig config;
    config.camera_count = count;
    for (const CameraView& camera : make_camera_layout(FieldGeometry::division_a(), config)) {
      const CameraCalibration& c = camera.calibration;
      EXPECT_NEAR((c.derived_world - camera.position).norm(), 0.0, 1e-12);
      EXPECT_NEAR(std::hypot(c.q0, c.q1, c.q2) * std::hypot(c.q0, c.q1, c.q2) + c.q3 * c.q3, 1.0, 1e-12);
      EXPECT_EQ(c.pixel_image_width, 2448u);
      EXPECT_EQ(c.pixel_image_height, 2048u);
      // ssl-vision's derived camera position is -R^T t.
      const Vec3 derived = -(camera_rotation(c).transpose() * Vec3(c.tx, c.ty, c.tz));
      EXPECT_NEAR((derived - camera.position).norm(), 0.0, 1e-12);
      for (double z : {0.0, 0.0215, 0.15}) {
        for (const Vec2& corner : camera.view.corners()) {
          const auto pixel = project_to_pixel(c, Vec3(corner.x(), corner.y(), z));
          ASSERT_TRUE(pixel);
          EXPECT_GE(pixel->x(), 0.0);
          EXPECT_LE(pixel->x(), c.pixel_image_width);
          EXPECT_GE(pixel->y(), 0.0);
          EXPECT_LE(pixel->y(), c.pixel_image_height);
          const Vec3 back = pixel_to_world(c, *pixel, z);
          EXPECT_NEAR((back - Vec3(corner.x(), corner.y(), z)).norm(), 0.0, 1e-9);
        }
      }
      // The camera's own ground point is the principal point.
      const auto centre = project_to_pixel(c, Vec3(camera.position.x(), camera.position.y(), 0.0));
      ASSERT_TRUE(centre);
      EXPECT_NEAR(centre->x(), c.principal_point_x, 1e-9);
      EXPECT_NEAR(centre->y(), c.principal_point_y, 1e-9);
    }
  }
}

TEST(SimVisionCameraTest, ThePointAboveTheCameraIsNotInFront) {
  const CameraView camera = make_camera_layout(FieldGeometry::division_b(), VisionConfig{})[0];
  EXPECT_FALSE(project_to_pixel(camera.calibration, camera.position + Vec3(0.0, 0.0, 1.0)));
}

}  // namespace
}  // namespace ssl::sim
