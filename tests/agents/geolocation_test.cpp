// Geolocation: the general intersection against sim2d's camera, its covariance
// against a Monte Carlo, and the seed's formula (seed section 7.3, eq. 5-15):
// its centre, its spherical destination point, its column sign, and how far its
// constant angle per pixel strays from the pinhole intersection.
#include "fireswarm/agents/geolocation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "agents/thermal_scene.hpp"
#include "fireswarm/common/north_east.hpp"

namespace fireswarm::agents {
namespace {

using testing::kDeg;

ObserverPose PoseAt(common::LatLon position, double altitude_m, double heading_deg,
                    double pitch_deg, double roll_deg, CameraGeometry camera = {}) {
  ObserverPose pose;
  pose.position = position;
  pose.altitude_m = altitude_m;
  pose.heading_rad = heading_deg * kDeg;
  pose.pitch_rad = pitch_deg * kDeg;
  pose.roll_rad = roll_deg * kDeg;
  pose.camera = camera;
  return pose;
}

TEST(IntersectGround, InvertsSim2dCameraForEveryModelAttitudeAndMount) {
  const common::LocalFrame geo(common::LatLon{45.0, 7.0});
  struct Attitude {
    double heading_deg, pitch_deg, roll_deg;
  };
  const std::array<Attitude, 5> attitudes = {{{0.0, 0.0, 0.0},
                                              {37.0, -8.0, 4.0},
                                              {210.0, 12.0, -15.0},
                                              {300.0, -20.0, 10.0},
                                              {90.0, 5.0, 25.0}}};
  std::mt19937_64 rng(11);
  int checked = 0;
  double worst_m = 0.0;
  for (const common::CameraModel& model : common::CameraModels()) {
    for (const double mount_deg : {-90.0, -70.0, -45.0, -20.0, 0.0}) {
      const sim2d::ThermalCamera camera(model, sim2d::CameraMount{mount_deg});
      for (const Attitude& a : attitudes) {
        SCOPED_TRACE(std::string(model.name) + " mount " + std::to_string(mount_deg) + " heading " +
                     std::to_string(a.heading_deg));
        const sim2d::VehicleTruth v =
            testing::Flying({120.0, -40.0}, 85.0, a.heading_deg, a.pitch_deg, a.roll_deg);
        const ObserverPose pose = testing::PoseOf(v, camera, geo);
        std::uniform_real_distribution<double> u(0.0, model.width_px);
        std::uniform_real_distribution<double> w(0.0, model.height_px);
        for (int i = 0; i < 40; ++i) {
          // A ground point the camera sees (sim2d's inverse), projected forward
          // by sim2d, and inverted by the vehicle's geolocation.
          const std::optional<sim2d::Vec2> ground = camera.PixelToGround(v, u(rng), w(rng));
          if (!ground || (*ground - v.position_m).norm() > 2000.0) continue;
          const std::optional<sim2d::PixelCoord> pixel = camera.GroundToPixel(v, *ground);
          if (!pixel) continue;
          const std::optional<common::EastNorth> offset =
              IntersectGround(pose, ImagePoint{pixel->u_px, pixel->v_px});
          ASSERT_TRUE(offset.has_value());
          const sim2d::Vec2 found = v.position_m + sim2d::Vec2(offset->east_m, offset->north_m);
          const double error_m = (found - *ground).norm();
          worst_m = std::max(worst_m, error_m);
          EXPECT_LT(error_m, 0.01);
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 1500);
  EXPECT_LT(worst_m, 0.01);
}

TEST(IntersectGround, RayAboveTheHorizonHasNoFix) {
  CameraGeometry forward;
  forward.camera_pitch_deg = 0.0;
  const ObserverPose pose = PoseAt({45.0, 7.0}, 100.0, 0.0, 0.0, 0.0, forward);
  EXPECT_FALSE(IntersectGround(pose, ImagePoint{48.0, 10.0}).has_value());  // upper half: sky
  EXPECT_TRUE(IntersectGround(pose, ImagePoint{48.0, 50.0}).has_value());
  ObserverPose grounded = PoseAt({45.0, 7.0}, 0.0, 0.0, 0.0, 0.0);
  EXPECT_FALSE(IntersectGround(grounded, ImagePoint{48.0, 32.0}).has_value());
}

TEST(GeolocatePixel, PositionIsTheOffsetThroughLocalFrame) {
  const ObserverPose pose = PoseAt({45.0, 7.0}, 100.0, 30.0, -5.0, 2.0);
  const std::optional<GroundFix> fix = GeolocatePixel(pose, ImagePoint{70.0, 20.0});
  ASSERT_TRUE(fix.has_value());
  const common::EastNorth back = common::LocalFrame(pose.position).ToLocal(fix->position);
  EXPECT_NEAR(back.east_m, fix->offset_m.east_m, 1e-6);
  EXPECT_NEAR(back.north_m, fix->offset_m.north_m, 1e-6);
  const std::optional<common::EastNorth> offset = IntersectGround(pose, ImagePoint{70.0, 20.0});
  EXPECT_NEAR(offset->east_m, fix->offset_m.east_m, 1e-12);
}

// Empirical covariance of the fix under the same perturbations, by sampling.
Eigen::Matrix2d MonteCarloCovariance(const ObserverPose& pose, ImagePoint pixel,
                                     const GeolocationSigmas& s, int samples) {
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d sum_sq = Eigen::Matrix2d::Zero();
  for (int i = 0; i < samples; ++i) {
    ObserverPose p = pose;
    p.altitude_m += s.altitude_m * normal(rng);
    p.roll_rad += s.roll_rad * normal(rng);
    p.pitch_rad += s.pitch_rad * normal(rng);
    p.heading_rad += s.heading_rad * normal(rng);
    ImagePoint q = pixel;
    q.u_px += s.pixel_px * normal(rng);
    q.v_px += s.pixel_px * normal(rng);
    const double gps_north_m = s.horizontal_m * normal(rng);
    const double gps_east_m = s.horizontal_m * normal(rng);
    const std::optional<common::EastNorth> offset = IntersectGround(p, q);
    EXPECT_TRUE(offset.has_value());
    const Eigen::Vector2d ne(offset->north_m + gps_north_m, offset->east_m + gps_east_m);
    sum += ne;
    sum_sq += ne * ne.transpose();
  }
  const Eigen::Vector2d mean = sum / samples;
  return (sum_sq - samples * mean * mean.transpose()) / (samples - 1);
}

TEST(GeolocatePixel, CovarianceMatchesMonteCarloWithinTenPercent) {
  const GeolocationSigmas sigmas;
  struct Case {
    double mount_deg, heading_deg, pitch_deg, roll_deg, u_px, v_px;
  };
  for (const Case& c :
       {Case{-90.0, 30.0, -5.0, 3.0, 70.0, 20.0}, Case{-45.0, 200.0, -8.0, -4.0, 20.0, 40.0},
        Case{-60.0, 0.0, 0.0, 0.0, 48.0, 32.0}}) {
    SCOPED_TRACE("mount " + std::to_string(c.mount_deg));
    CameraGeometry camera;
    camera.camera_pitch_deg = c.mount_deg;
    const ObserverPose pose =
        PoseAt({45.0, 7.0}, 100.0, c.heading_deg, c.pitch_deg, c.roll_deg, camera);
    const std::optional<GroundFix> fix = GeolocatePixel(pose, ImagePoint{c.u_px, c.v_px}, sigmas);
    ASSERT_TRUE(fix.has_value());
    // MonteCarloCovariance samples (north, east).
    const Eigen::Matrix2d predicted = common::SwapAxes(fix->covariance_en_m2);
    const Eigen::Matrix2d sampled =
        MonteCarloCovariance(pose, ImagePoint{c.u_px, c.v_px}, sigmas, 20000);
    EXPECT_NEAR(predicted(0, 0), sampled(0, 0), 0.1 * sampled(0, 0));
    EXPECT_NEAR(predicted(1, 1), sampled(1, 1), 0.1 * sampled(1, 1));
    // Off-diagonal: relative to the scale of the ellipse (it may be near zero).
    const double scale_m2 = std::sqrt(sampled(0, 0) * sampled(1, 1));
    EXPECT_NEAR(predicted(0, 1), sampled(0, 1), 0.1 * scale_m2);
    EXPECT_DOUBLE_EQ(predicted(0, 1), predicted(1, 0));
    // The pixel part is a part: positive and smaller than the whole.
    EXPECT_GT(fix->pixel_covariance_en_m2.trace(), 0.0);
    EXPECT_LT(fix->pixel_covariance_en_m2.trace(), predicted.trace());
    // GPS alone is 2.12 m per axis; the attitude adds to it.
    EXPECT_GT(predicted(0, 0), sigmas.horizontal_m * sigmas.horizontal_m);
  }
}

TEST(GeometryOf, TakesTheModelAndRejectsABadMount) {
  const common::CameraModel& lepton = common::CameraModelByName("lepton35");
  const CameraGeometry geometry = GeometryOf(lepton, -30.0);
  EXPECT_EQ(geometry.width_px, 160);
  EXPECT_EQ(geometry.height_px, 120);
  EXPECT_DOUBLE_EQ(geometry.hfov_deg, 57.0);
  EXPECT_DOUBLE_EQ(geometry.camera_pitch_deg, -30.0);
  try {
    GeometryOf(lepton, 10.0);
    FAIL() << "a mount looking up was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("camera_pitch_deg"), std::string::npos);
  }
}

TEST(SeedCentroid, AveragesPixelCentres) {
  const std::array<int, 3> cols = {10, 11, 12};
  const std::array<int, 3> rows = {5, 5, 8};
  const ImagePoint c = SeedCentroid(cols, rows);
  EXPECT_DOUBLE_EQ(c.u_px, 11.5);
  EXPECT_DOUBLE_EQ(c.v_px, 6.5);
}

// ---- The seed's formula with the seed's 96 x 64 px, 75 x 60 deg camera ----

// The WGS84 radii of curvature (meridian and prime vertical) lie between
// 6,335 and 6,400 km, so a distance on the seed's 6,371 km sphere is off the
// ellipsoid's by at most 0.57 % of itself: the tolerance for eq. 14-15.
constexpr double kSphereVsEllipsoidFraction = 0.006;

TEST(SeedFlatTerrainGeolocation, ImageCentreLiesAlongTheHeadingAtHTanOfTheAxisAngle) {
  SeedGeolocationInput input;  // 96 x 64 px, 75 x 60 deg
  input.centroid_x_px = 48.0;
  input.centroid_y_px = 32.0;
  input.gps_heading_deg = 30.0;
  input.frame_pitch_deg = 5.0;    // nose down
  input.camera_mount_deg = 45.0;  // 45 deg below the body
  input.height_m = 100.0;
  input.position = {45.0, 7.0};
  const SeedGeolocationResult result = SeedFlatTerrainGeolocation(input);
  EXPECT_DOUBLE_EQ(result.bearing_deg, 30.0);
  EXPECT_DOUBLE_EQ(result.angle_from_vertical_deg, 40.0);
  EXPECT_NEAR(result.ground_distance_m, 100.0 * std::tan((90.0 - (5.0 + 45.0)) * kDeg), 1e-9);
}

TEST(SeedFlatTerrainGeolocation, OneHalfFieldOfViewPerHalfImage) {
  SeedGeolocationInput input;
  input.camera_mount_deg = 45.0;
  input.centroid_x_px = 0.0;   // eq. 7: dx = 48 -> X_t = +37.5 deg
  input.centroid_y_px = 64.0;  // eq. 8: dy = -32 -> phi_t = -30 deg
  const SeedGeolocationResult result = SeedFlatTerrainGeolocation(input);
  EXPECT_DOUBLE_EQ(result.bearing_deg, 37.5);
  EXPECT_DOUBLE_EQ(result.angle_from_vertical_deg, 15.0);
}

TEST(SeedFlatTerrainGeolocation, Eq14And15AgreeWithLocalFrameWithinTheSphere) {
  for (const double lat_deg : {0.0, 45.0, 60.0}) {
    const common::LatLon drone{lat_deg, 7.0};
    const common::LocalFrame geo(drone);
    for (const double heading_deg : {0.0, 45.0, 135.0, 270.0}) {
      for (const double height_m : {50.0, 200.0, 1000.0}) {
        SeedGeolocationInput input;
        input.position = drone;
        input.gps_heading_deg = heading_deg;
        input.camera_mount_deg = 30.0;  // theta_t = 60 deg: D = 1.73 H
        input.height_m = height_m;
        const SeedGeolocationResult result = SeedFlatTerrainGeolocation(input);
        const double d = result.ground_distance_m;
        const common::EastNorth found = geo.ToLocal(result.position);
        const double error_m = std::hypot(found.east_m - d * std::sin(heading_deg * kDeg),
                                          found.north_m - d * std::cos(heading_deg * kDeg));
        EXPECT_LT(error_m, kSphereVsEllipsoidFraction * d + 1e-3)
            << "lat " << lat_deg << " heading " << heading_deg << " D " << d;
      }
    }
  }
}

// Eq. 10 adds dx = 48 - Xc to the bearing: the seed's columns count from the
// right. SeedInputFromImage mirrors ours so a fire right of centre bears right.
TEST(SeedFlatTerrainGeolocation, ColumnsCountFromTheRightAndSeedInputFromImageMirrors) {
  ObserverPose pose;
  pose.position = {45.0, 7.0};
  pose.altitude_m = 100.0;
  pose.heading_rad = 90.0 * kDeg;  // east
  pose.camera.camera_pitch_deg = -45.0;
  const ImagePoint right_of_centre{80.0, 32.0};

  SeedGeolocationInput raw = SeedInputFromImage(right_of_centre, pose);
  raw.centroid_x_px = right_of_centre.u_px;  // our column fed to eq. 7 unmirrored
  EXPECT_LT(SeedFlatTerrainGeolocation(raw).bearing_deg, 90.0);  // left: wrong side

  const SeedGeolocationResult seed =
      SeedFlatTerrainGeolocation(SeedInputFromImage(right_of_centre, pose));
  EXPECT_GT(seed.bearing_deg, 90.0);  // right of an eastward heading: south of east
  const std::optional<common::EastNorth> pinhole = IntersectGround(pose, right_of_centre);
  ASSERT_TRUE(pinhole.has_value());
  EXPECT_LT(pinhole->north_m, 0.0);
  EXPECT_GT(pinhole->east_m, 0.0);
}

// Along the image's centre column the seed and the pinhole both look along the
// heading; they differ only in eq. 11's constant angle per row where the
// pinhole has tan(angle) proportional to the row offset. For a half field of
// view a = 30 deg the largest gap, max over x in [0, 1] of |x a - atan(x tan a)|,
// is 1.1 deg (at x = 0.55); at the centre and the edges they agree.
TEST(SeedFlatTerrainGeolocation, AgreesWithThePinholeOnTheCentreColumnWithinTheLinearAngle) {
  const double half_vfov_deg = 30.0;
  double largest_gap_deg = 0.0;
  for (double x = 0.0; x <= 1.0; x += 1e-4) {
    largest_gap_deg = std::max(
        largest_gap_deg,
        std::abs(x * half_vfov_deg - std::atan(x * std::tan(half_vfov_deg * kDeg)) / kDeg));
  }
  EXPECT_NEAR(largest_gap_deg, 1.1, 0.05);

  for (const double mount_deg : {-30.0, -45.0, -60.0}) {
    for (const double pitch_deg : {0.0, -5.0, -12.0}) {
      ObserverPose pose;
      pose.position = {45.0, 7.0};
      pose.altitude_m = 120.0;
      pose.heading_rad = 20.0 * kDeg;
      pose.pitch_rad = pitch_deg * kDeg;
      pose.camera.camera_pitch_deg = mount_deg;
      double worst_deg = 0.0;
      for (double v = 0.0; v <= 64.0; v += 0.5) {
        const ImagePoint pixel{48.0, v};
        const SeedGeolocationResult seed =
            SeedFlatTerrainGeolocation(SeedInputFromImage(pixel, pose));
        const std::optional<common::EastNorth> pinhole = IntersectGround(pose, pixel);
        if (!pinhole || seed.angle_from_vertical_deg >= 89.0) continue;  // at the horizon
        const double pinhole_d = std::hypot(pinhole->east_m, pinhole->north_m);
        // The pinhole ray lies in the vertical plane of the heading: same bearing.
        const double along = pinhole->north_m * std::cos(pose.heading_rad) +
                             pinhole->east_m * std::sin(pose.heading_rad);
        EXPECT_NEAR(std::abs(along), pinhole_d, 1e-6);
        EXPECT_DOUBLE_EQ(seed.bearing_deg, 20.0);
        const double pinhole_angle_deg = std::atan2(along, pose.altitude_m) / kDeg;
        const double gap_deg = std::abs(pinhole_angle_deg - seed.angle_from_vertical_deg);
        worst_deg = std::max(worst_deg, gap_deg);
        if (v == 32.0 || v == 0.0 || v == 64.0) {
          EXPECT_NEAR(gap_deg, 0.0, 1e-9);
        }
      }
      EXPECT_LE(worst_deg, largest_gap_deg + 1e-9);
      EXPECT_GT(worst_deg, 0.5);  // the approximation is real, not a coincidence
    }
  }
}

}  // namespace
}  // namespace fireswarm::agents
