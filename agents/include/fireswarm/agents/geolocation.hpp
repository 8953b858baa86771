// Where a pixel of the thermal camera lies on the ground: the seed's flat-terrain
// formula (seed section 7.3, eq. 5-15) kept as it is printed, and the general
// pinhole ray-ground intersection with the full attitude and the camera mount,
// each fix carrying an (east, north) covariance.
//
// Conventions of the general intersection, the same as the simulator's camera
// (sim2d/thermal_camera.hpp) so that one is the exact inverse of the other:
//  * Attitude: body FRD relative to NED, heading (clockwise from true north),
//    then pitch (nose up positive), then roll (right wing down positive).
//  * Mount: `camera_pitch_deg` relative to the level body, negative down, in
//    [-90, 0]; -90 looks straight down, 0 forward. The optical axis lies in the
//    body's forward-down plane.
//  * Image: continuous pixel coordinates (u_px, v_px) from the top-left corner
//    of the top-left pixel; pixel (col, row) covers [col, col+1) x [row, row+1),
//    so its centre is (col + 0.5, row + 0.5), and the optical axis passes
//    through (width/2, height/2). Columns grow toward the vehicle's right; row 0
//    is the top, which is the vehicle's forward direction for a nadir camera.
//  * Pinhole: fx = (width/2) / tan(hfov/2), fy = (height/2) / tan(vfov/2).
//  * Ground: flat, `altitude_m` below the camera.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::agents {

/// A continuous image position (see the conventions above).
struct ImagePoint {
  double u_px = 0.0;  ///< along the columns, toward the vehicle's right
  double v_px = 0.0;  ///< along the rows, down the image
};

/// The camera's image geometry and mount.
struct CameraGeometry {
  int width_px = 96;
  int height_px = 64;
  double hfov_deg = 75.0;           ///< full horizontal field of view
  double vfov_deg = 60.0;           ///< full vertical field of view
  double camera_pitch_deg = -90.0;  ///< mount pitch relative to the level body, negative down
};

/// The geometry of a known camera model on a mount pitched `camera_pitch_deg`.
/// Throws std::invalid_argument naming "camera_pitch_deg" when it is not in
/// [-90, 0], or the model's field when its sizes or fields of view are not positive.
CameraGeometry GeometryOf(const common::CameraModel& model, double camera_pitch_deg = -90.0);

/// Where the vehicle believed it was, and how it was turned, when a frame was taken.
struct ObserverPose {
  common::LatLon position;  ///< GPS estimate, WGS84
  double altitude_m = 0.0;  ///< camera height above the (flat) ground
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double heading_rad = 0.0;  ///< clockwise from true north
  CameraGeometry camera;
};

/// 1-sigma errors of the inputs of a fix, for its covariance.
struct GeolocationSigmas {
  /// GPS horizontal position per axis: a 2.5 m CEP (50 % circle) is
  /// 2.5 / sqrt(2 ln 2) = 2.12 m per axis for a circular Gaussian.
  double horizontal_m = 2.12;
  double altitude_m = 1.0;         ///< height above ground (baro/GPS and terrain)
  double roll_rad = 0.0087266;     ///< 0.5 deg
  double pitch_rad = 0.0087266;    ///< 0.5 deg
  double heading_rad = 0.0174533;  ///< 1 deg (magnetometer/GPS course)
  double pixel_px = 0.5;           ///< centroid error per image axis
};

/// One pixel located on the ground.
struct GroundFix {
  common::EastNorth offset_m;  ///< from the vehicle's (GPS) position, metres
  common::LatLon position;     ///< offset_m applied at the vehicle through common::LocalFrame
  /// Covariance of (east, north), m^2, from every GeolocationSigmas term.
  Eigen::Matrix2d covariance_en_m2 = Eigen::Matrix2d::Zero();
  /// The part of covariance_en_m2 due to the pixel (centroid) error alone: the
  /// only term independent from frame to frame. GPS position, altitude and
  /// attitude errors drift slowly and repeat over the frames of one pass.
  Eigen::Matrix2d pixel_covariance_en_m2 = Eigen::Matrix2d::Zero();
};

/// Offset (east, north) in metres from the vehicle to where the ray through
/// `pixel` meets the flat ground; nullopt when the ray does not point below the
/// horizon or the altitude is not positive. Exact inverse of sim2d's
/// ThermalCamera::GroundToPixel.
std::optional<common::EastNorth> IntersectGround(const ObserverPose& pose, ImagePoint pixel);

/// IntersectGround plus the geodetic position and the covariance propagated from
/// `sigmas` (first order: numerical Jacobian of the intersection). nullopt as
/// IntersectGround, and also when a perturbed ray no longer meets the ground.
std::optional<GroundFix> GeolocatePixel(const ObserverPose& pose, ImagePoint pixel,
                                        const GeolocationSigmas& sigmas = {});

// ---- The seed's formula, seed section 7.3 ------------------------------------

/// Seed eq. 5-6: the unweighted mean of the pixel positions of one hot region.
/// Each pixel (col, row) counts at its centre (col + 0.5, row + 0.5), the
/// continuous coordinates above. Requires cols.size() == rows.size() > 0.
ImagePoint SeedCentroid(std::span<const int> cols, std::span<const int> rows);

/// The inputs of seed eq. 7-15, in the seed's own terms.
struct SeedGeolocationInput {
  /// Xc, Yc of eq. 5-6 in the seed's image: rows from the top, but columns as
  /// the seed's eq. 7 and 10 count them (see SeedFlatTerrainGeolocation):
  /// from the right. Use SeedInputFromImage to fill them from our image.
  double centroid_x_px = 48.0;
  double centroid_y_px = 32.0;
  int width_px = 96;               ///< the seed's 96 pixels across
  int height_px = 64;              ///< and 64 down
  double hfov_deg = 75.0;          ///< the seed's 75 deg horizontal field of view
  double vfov_deg = 60.0;          ///< and 60 deg vertical
  double gps_heading_deg = 0.0;    ///< omega_GPS: the vehicle's heading, clockwise from north
  double frame_pitch_deg = 0.0;    ///< phi_f: the frame's pitch, positive nose DOWN
  double camera_mount_deg = 90.0;  ///< phi_c: the mount's depression below the body, 90 = nadir
  double height_m = 100.0;         ///< H_GPS: height above the flat ground
  common::LatLon position;         ///< Lat_GPS, Lon_GPS
  double earth_radius_m = 6371e3;  ///< R of eq. 14-15
};

/// The outputs of seed eq. 7-15.
struct SeedGeolocationResult {
  double bearing_deg = 0.0;              ///< omega_t (eq. 10), clockwise from north
  double ground_distance_m = 0.0;        ///< D_t (eq. 13); negative behind the vehicle
  double angle_from_vertical_deg = 0.0;  ///< theta_t (eq. 12), the ray from straight down
  common::LatLon position;               ///< Lat_t, Lon_t (eq. 14-15), on a sphere of radius R
};

/// Seed eq. 7-15 exactly as printed:
///   dx = W/2 - Xc (7), dy = H/2 - Yc (8), X_t = dx * hfov / W (9),
///   omega_t = omega_GPS + X_t (10), phi_t = dy * vfov / H (11),
///   theta_t = 90 - (phi_f + phi_c) + phi_t (12), D_t = H_GPS tan(theta_t) (13),
///   and the spherical destination point (14-15).
/// What the signs imply:
///  * eq. 10 adds dx = W/2 - Xc to the bearing, so a centroid with a larger Xc
///    lies to the LEFT: the seed's Xc counts columns from the right (a mirrored
///    read-out of the image). Our images count from the left, so pass W - u.
///  * eq. 12 adds dy = H/2 - Yc to the angle from the vertical, so rows above the
///    centre lie farther away: Yc counts rows from the top, as ours do.
///  * eq. 12 makes phi_f + phi_c the optical axis' depression below the horizon,
///    so phi_c is the mount's depression (90 = nadir) and phi_f the frame's pitch
///    positive nose down: phi_f = -pitch_FRD, phi_c = -camera_pitch_deg.
///  * Roll is ignored, and eq. 9 and 11 take a constant angle per pixel where a
///    pinhole camera has tan(angle) proportional to the pixel offset: at the
///    image centre and edges the two agree; in between the linear angle is off
///    by up to 1.1 deg vertically and 2.2 deg horizontally for 60 x 75 deg.
///  * With the seed's integer pixel indices in eq. 5-6 the image centre would be
///    (47.5, 31.5), half a pixel from eq. 7-8's (48, 32); continuous coordinates
///    (SeedCentroid) put it at (48, 32) exactly.
/// No checks: theta_t at or past 90 deg gives an infinite or negative distance,
/// as the seed's formula does.
SeedGeolocationResult SeedFlatTerrainGeolocation(const SeedGeolocationInput& input);

/// The seed's inputs for a centroid in our image convention (columns to the
/// right, row 0 at the top) seen from `pose`: mirrors the column for eq. 7,
/// turns FRD pitch and the mount pitch into phi_f and phi_c, and drops the roll
/// (which the seed ignores).
SeedGeolocationInput SeedInputFromImage(ImagePoint centroid, const ObserverPose& pose);

}  // namespace fireswarm::agents
