#include "services/simulator/core/vision/camera.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

namespace ssl::sim {
namespace {

// The highest plane the calibration must keep in the image: the top of a robot (rules: <= 0.15 m) plus
// margin.
constexpr double kHighestObservedPlane = 0.2;  // m

}  // namespace

CameraGrid camera_grid(int camera_count) {
  switch (camera_count) {
    case 1: return {1, 1};
    case 2: return {2, 1};
    case 4: return {2, 2};
    case 6: return {3, 2};
    case 8: return {4, 2};
    default: throw std::invalid_argument("vision config: camera_count must be 1, 2, 4, 6 or 8");
  }
}

geom::Rectangle covered_area(const FieldGeometry& field) {
  const double half_x = field.wall_half_length();
  const double half_y = field.wall_half_width();
  return {Vec2(-half_x, -half_y), Vec2(half_x, half_y)};
}

CameraCalibration make_calibration(std::uint32_t camera_id, const Vec3& position, const geom::Rectangle& view,
                                   const VisionConfig& config) {
  CameraCalibration c;
  c.camera_id = camera_id;
  c.pixel_image_width = config.image_width;
  c.pixel_image_height = config.image_height;
  c.principal_point_x = 0.5 * config.image_width;
  c.principal_point_y = 0.5 * config.image_height;
  c.distortion = 0.0;
  // Looking straight down. Landscape view: camera x = world x, camera y = -world y, camera z = -world z
  // (half turn about x). Portrait view: camera x = world y, camera y = world x, camera z = -world z (half
  // turn about the diagonal (1, 1, 0)), so the image's long side always lies along the view's long side.
  const bool landscape = view.width() >= view.height();
  if (landscape) {
    c.q0 = 1.0, c.q1 = 0.0, c.q2 = 0.0, c.q3 = 0.0;
  } else {
    c.q0 = std::sqrt(0.5), c.q1 = std::sqrt(0.5), c.q2 = 0.0, c.q3 = 0.0;
  }
  // The view, seen from the camera, must fit the image on every plane up to the top of a robot; the
  // nearest such plane (largest image) is the highest one.
  const Vec2 far_offset = (view.max() - view.min()).cwiseAbs() * 0.5 +
                          (view.center() - Vec2(position.x(), position.y())).cwiseAbs();
  const double half_u = landscape ? far_offset.x() : far_offset.y();  // along the image's x axis
  const double half_v = landscape ? far_offset.y() : far_offset.x();
  const double depth = position.z() - kHighestObservedPlane;
  c.focal_length =
      std::min(0.5 * config.image_width * depth / half_u, 0.5 * config.image_height * depth / half_v);
  const Eigen::Matrix3d rotation = camera_rotation(c);
  const Vec3 translation = -(rotation * position);
  c.tx = translation.x();
  c.ty = translation.y();
  c.tz = translation.z();
  c.derived_world = position;
  return c;
}

std::vector<CameraView> make_camera_layout(const FieldGeometry& field, const VisionConfig& config) {
  config.validate();
  const CameraGrid grid = camera_grid(config.camera_count);
  const geom::Rectangle area = covered_area(field);
  const double tile_width = area.width() / grid.columns;
  const double tile_height = area.height() / grid.rows;
  std::vector<CameraView> cameras;
  cameras.reserve(static_cast<std::size_t>(grid.columns * grid.rows));
  for (int row = 0; row < grid.rows; ++row) {
    for (int column = 0; column < grid.columns; ++column) {
      CameraView camera;
      camera.camera_id = static_cast<std::uint32_t>(row * grid.columns + column);
      const Vec2 min = area.min() + Vec2(column * tile_width, row * tile_height);
      // The last tile ends exactly on the area's edge (no rounding gap at the boundary).
      const Vec2 max(column + 1 == grid.columns ? area.max().x() : min.x() + tile_width,
                     row + 1 == grid.rows ? area.max().y() : min.y() + tile_height);
      camera.tile = geom::Rectangle(min, max);
      camera.view = camera.tile.expanded(config.camera_overlap);
      const Vec2 center = camera.tile.center();
      camera.position = Vec3(center.x(), center.y(), config.camera_height);
      camera.calibration = make_calibration(camera.camera_id, camera.position, camera.view, config);
      cameras.push_back(camera);
    }
  }
  return cameras;
}

Eigen::Matrix3d camera_rotation(const CameraCalibration& calibration) {
  // Eigen's constructor takes (w, x, y, z); ssl-vision's q3 is w.
  Eigen::Quaterniond q(calibration.q3, calibration.q0, calibration.q1, calibration.q2);
  q.normalize();
  return q.toRotationMatrix();
}

std::optional<Eigen::Vector2d> project_to_pixel(const CameraCalibration& calibration, const Vec3& world) {
  const Vec3 translation(calibration.tx, calibration.ty, calibration.tz);
  const Vec3 p = camera_rotation(calibration) * world + translation;
  if (!(p.z() > 0.0)) return std::nullopt;
  return Eigen::Vector2d(calibration.focal_length * p.x() / p.z() + calibration.principal_point_x,
                         calibration.focal_length * p.y() / p.z() + calibration.principal_point_y);
}

Vec3 pixel_to_world(const CameraCalibration& calibration, const Eigen::Vector2d& pixel, double z) {
  const Eigen::Matrix3d rotation = camera_rotation(calibration);
  const Vec3 ray_camera((pixel.x() - calibration.principal_point_x) / calibration.focal_length,
                        (pixel.y() - calibration.principal_point_y) / calibration.focal_length, 1.0);
  const Vec3 ray_world = rotation.transpose() * ray_camera;
  const Vec3 origin = -(rotation.transpose() * Vec3(calibration.tx, calibration.ty, calibration.tz));
  const double t = (z - origin.z()) / ray_world.z();  // inf or NaN when parallel
  if (!std::isfinite(t)) return Vec3::Constant(std::nan(""));
  return origin + t * ray_world;
}

}  // namespace ssl::sim
