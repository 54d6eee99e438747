// The simulated camera installation: which part of the field each camera covers, where it hangs, and the
// pinhole calibration it publishes (SSL_GeometryCameraCalibration, in SI units: translations in metres,
// focal length and principal point in pixels).
//
// Frames. World = the SSL-Vision global frame (metres, z up from the carpet). Camera = ssl-vision's
// convention: p_camera = R(q) * p_world + t, with the quaternion q = (q0, q1, q2, q3) = (x, y, z, w) and the
// camera's z axis looking down at the field. Pixels: pixel = focal_length * (x_c / z_c, y_c / z_c) +
// principal point. Our cameras look straight down with no lens distortion (distortion = 0), the image's long
// side along the longer side of the camera's view, so these functions ignore `distortion`.
//
//   std::vector<CameraView> cameras = make_camera_layout(FieldGeometry::division_a(), VisionConfig{});
//   auto pixel = project_to_pixel(cameras[0].calibration, Vec3(-3.0, -2.0, 0.0215));
//   Vec3 back = pixel_to_world(cameras[0].calibration, *pixel, 0.0215);  // == (-3, -2, 0.0215)
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "libs/geometry/rectangle.h"
#include "services/simulator/core/types.h"
#include "services/simulator/core/vision/vision_config.h"

namespace ssl::sim {

/// One camera's calibration as ssl-vision publishes it, SI units (the adapter converts metres to mm).
struct CameraCalibration {
  std::uint32_t camera_id = 0;
  double focal_length = 0;                // px
  double principal_point_x = 0;           // px
  double principal_point_y = 0;           // px
  double distortion = 0;                  // ssl-vision's radial distortion coefficient (always 0 here)
  double q0 = 0, q1 = 0, q2 = 0, q3 = 1;  // world -> camera rotation quaternion (x, y, z, w)
  double tx = 0, ty = 0, tz = 0;          // m, world -> camera translation
  Vec3 derived_world = Vec3::Zero();      // m, camera position in the world (= -R^T t)
  std::uint32_t pixel_image_width = 0;    // px
  std::uint32_t pixel_image_height = 0;   // px

  friend bool operator==(const CameraCalibration&, const CameraCalibration&) = default;
};

/// One camera of the layout. `view` is what the camera reports: its tile grown by the overlap.
struct CameraView {
  std::uint32_t camera_id = 0;
  geom::Rectangle tile{Vec2::Zero(), Vec2::Zero()};  // its share of the field incl. boundary, m
  geom::Rectangle view{Vec2::Zero(), Vec2::Zero()};  // tile grown by camera_overlap, m
  Vec3 position = Vec3::Zero();                      // where the camera really hangs, m
  CameraCalibration calibration;                     // nominal calibration of a camera at `position`
};

/// Columns (along x) and rows (along y) of the camera grid for 1, 2, 4, 6 or 8 cameras.
struct CameraGrid {
  int columns = 1;
  int rows = 1;
};
/// Throws std::invalid_argument for other camera counts.
CameraGrid camera_grid(int camera_count);

/// The area the cameras cover together: the field plus its boundary (x: goal line + boundary_width_goal_line,
/// y: touch line + boundary_width), centred on the origin.
geom::Rectangle covered_area(const FieldGeometry& field);

/// The cameras of `config` over `field`, ordered by camera id. Throws std::invalid_argument for an invalid
/// config (see VisionConfig::validate).
std::vector<CameraView> make_camera_layout(const FieldGeometry& field, const VisionConfig& config);

/// The calibration of a camera at `position` looking straight down and covering `view` (on the carpet, up
/// to 0.2 m above it, the top of a robot) with an image of config.image_width x config.image_height pixels.
CameraCalibration make_calibration(std::uint32_t camera_id, const Vec3& position, const geom::Rectangle& view,
                                   const VisionConfig& config);

/// The world -> camera rotation matrix of the calibration's (normalised) quaternion.
Eigen::Matrix3d camera_rotation(const CameraCalibration& calibration);

/// Pixel where a world point (m) appears; nullopt when it is not in front of the camera.
std::optional<Eigen::Vector2d> project_to_pixel(const CameraCalibration& calibration, const Vec3& world);

/// The world point at height z (m) seen at `pixel`: ssl-vision's image2field. NaN components when the
/// camera ray through the pixel is parallel to the plane.
Vec3 pixel_to_world(const CameraCalibration& calibration, const Eigen::Vector2d& pixel, double z);

}  // namespace ssl::sim
