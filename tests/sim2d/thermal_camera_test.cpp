// ThermalCamera geometry (pinhole, attitude, mount) and the radiometry of a
// frame: sub-pixel coverage and NETD noise. The white-hot mapping and files are
// in thermal_image_test.cpp.
#include "fireswarm/sim2d/thermal_camera.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "fireswarm/common/angles.hpp"

namespace fireswarm::sim2d {
namespace {

constexpr double kDeg = common::kRadPerDeg;

VehicleTruth Hovering(double altitude_m, double heading_deg = 0.0) {
  VehicleTruth v;
  v.position_m = Vec2(500.0, 500.0);
  v.altitude_m = altitude_m;
  v.heading_rad = heading_deg * kDeg;
  v.phase = FlightPhase::kFlying;
  return v;
}

// The model without noise and without saturation, for exact geometry and radiometry.
common::CameraModel Ideal(const common::CameraModel& model) {
  common::CameraModel ideal = model;
  ideal.netd_k = 0.0;
  ideal.max_scene_c = 2000.0;
  return ideal;
}

ThermalCameraOptions KeepTemperatures() {
  ThermalCameraOptions options;
  options.keep_temperatures = true;
  return options;
}

// (col, row) of the hottest pixel.
std::pair<int, int> Hottest(const ThermalImage& image) {
  const auto it =
      std::max_element(image.apparent_temperature_c.begin(), image.apparent_temperature_c.end());
  const auto i = static_cast<int>(it - image.apparent_temperature_c.begin());
  return {i % image.width_px, i / image.width_px};
}

struct Scene {
  FireGrid fire{FireConfig{}, MakeRng(1, "fire")};
};

TEST(ThermalCamera, PointStraightBelowIsAtTheImageCentreForEveryModel) {
  for (const common::CameraModel& model : common::CameraModels()) {
    SCOPED_TRACE(std::string(model.name));
    ThermalCamera camera(Ideal(model), {}, KeepTemperatures());
    const VehicleTruth v = Hovering(120.0, 37.0);
    const std::optional<PixelCoord> p = camera.GroundToPixel(v, v.position_m);
    ASSERT_TRUE(p.has_value());
    EXPECT_NEAR(p->u_px, model.width_px / 2.0, 1e-9);
    EXPECT_NEAR(p->v_px, model.height_px / 2.0, 1e-9);
    // Rendered: a small hot rock at the nadir warms the four centre pixels alike.
    Scene scene;
    const TemperatureField field(scene.fire, {{v.position_m, 0.3, 70.0}});
    Rng rng = MakeRng(1, "camera");
    const ThermalImage image = camera.Render(v, field, 0.0, rng);
    const int cc = model.width_px / 2, cr = model.height_px / 2;
    const float centre = image.TemperatureC(cc, cr);
    EXPECT_GT(centre, 25.0F);
    for (const auto& [dc, dr] : {std::pair{-1, -1}, {-1, 0}, {0, -1}}) {
      EXPECT_NEAR(image.TemperatureC(cc + dc, cr + dr), centre, 1e-3);
    }
    EXPECT_FLOAT_EQ(image.TemperatureC(0, 0), 25.0F);
  }
}

TEST(ThermalCamera, OffsetPointLandsWhereThePinholeModelPredicts) {
  for (const common::CameraModel& model : common::CameraModels()) {
    SCOPED_TRACE(std::string(model.name));
    ThermalCamera camera(Ideal(model), {}, KeepTemperatures());
    const VehicleTruth v = Hovering(100.0);  // heading north: forward = +y, right = +x
    const Vec2 point = v.position_m + 100.0 * Vec2(std::tan(15.0 * kDeg), std::tan(20.0 * kDeg));
    const double u = model.width_px / 2.0 + camera.focal_x_px() * std::tan(15.0 * kDeg);
    const double vv = model.height_px / 2.0 - camera.focal_y_px() * std::tan(20.0 * kDeg);
    const std::optional<PixelCoord> p = camera.GroundToPixel(v, point);
    ASSERT_TRUE(p.has_value());
    EXPECT_NEAR(p->u_px, u, 1e-9);
    EXPECT_NEAR(p->v_px, vv, 1e-9);
    EXPECT_TRUE(camera.PixelToGround(v, p->u_px, p->v_px)->isApprox(point, 1e-9));
    // The renderer agrees: a tiny rock there makes that pixel the hottest.
    Scene scene;
    const TemperatureField field(scene.fire, {{point, 0.05, 70.0}});
    Rng rng = MakeRng(1, "camera");
    const ThermalImage image = camera.Render(v, field, 0.0, rng);
    EXPECT_EQ(Hottest(image), (std::pair{static_cast<int>(u), static_cast<int>(vv)}));
  }
}

TEST(ThermalCamera, HeadingRotatesTheImageWithTheVehicle) {
  ThermalCamera camera(common::CameraModelByName("seed"));
  const VehicleTruth east = Hovering(100.0, 90.0);
  // Heading east: a point east is forward (top half), a point south is to the right.
  const PixelCoord ahead = *camera.GroundToPixel(east, east.position_m + Vec2(30.0, 0.0));
  EXPECT_NEAR(ahead.u_px, 48.0, 1e-9);
  EXPECT_LT(ahead.v_px, 32.0);
  const PixelCoord right = *camera.GroundToPixel(east, east.position_m + Vec2(0.0, -30.0));
  EXPECT_GT(right.u_px, 48.0);
  EXPECT_NEAR(right.v_px, 32.0, 1e-9);
}

TEST(ThermalCamera, RollAndPitchShiftTheImage) {
  for (const common::CameraModel& model : common::CameraModels()) {
    SCOPED_TRACE(std::string(model.name));
    ThermalCamera camera(model);
    VehicleTruth v = Hovering(80.0, 210.0);
    v.roll_rad = 10.0 * kDeg;  // right wing down: the camera looks left, nadir moves right
    PixelCoord p = *camera.GroundToPixel(v, v.position_m);
    EXPECT_NEAR(p.u_px, model.width_px / 2.0 + camera.focal_x_px() * std::tan(10.0 * kDeg), 1e-9);
    EXPECT_NEAR(p.v_px, model.height_px / 2.0, 1e-9);
    v.roll_rad = 0.0;
    v.pitch_rad = -12.0 * kDeg;  // nose down (flying forward): the nadir moves up the image
    p = *camera.GroundToPixel(v, v.position_m);
    EXPECT_NEAR(p.u_px, model.width_px / 2.0, 1e-9);
    EXPECT_NEAR(p.v_px, model.height_px / 2.0 - camera.focal_y_px() * std::tan(12.0 * kDeg), 1e-9);
  }
}

TEST(ThermalCamera, TiltedMountSeesAheadAndSkyAboveTheHorizon) {
  ThermalCamera tilted(common::CameraModelByName("seed"), {-60.0});
  const VehicleTruth v = Hovering(100.0);
  const Vec2 ahead = v.position_m + Vec2(0.0, 100.0 / std::tan(60.0 * kDeg));
  const PixelCoord p = *tilted.GroundToPixel(v, ahead);
  EXPECT_NEAR(p.u_px, 48.0, 1e-9);
  EXPECT_NEAR(p.v_px, 32.0, 1e-9);
  EXPECT_FALSE(tilted.GroundToPixel(v, v.position_m).has_value());  // below: out of view

  ThermalCameraOptions options = KeepTemperatures();
  ThermalCamera forward(Ideal(common::CameraModelByName("seed")), {0.0}, options);
  EXPECT_FALSE(forward.PixelToGround(v, 48.0, 10.0).has_value());
  EXPECT_TRUE(forward.PixelToGround(v, 48.0, 60.0).has_value());
  Scene scene;
  const TemperatureField field(scene.fire, {}, -20.0);
  Rng rng = MakeRng(1, "camera");
  const ThermalImage image = forward.Render(v, field, 0.0, rng);
  EXPECT_NEAR(image.TemperatureC(10, 5), -20.0, 1e-3);  // sky
  EXPECT_NEAR(image.TemperatureC(10, 60), 25.0, 1e-3);  // ground
}

TEST(ThermalCamera, SmallFireFarAwayWarmsItsPixelInProportion) {
  // AMG8833 nadir at the altitude where one pixel covers 25 m x 25 m.
  const common::CameraModel model = Ideal(common::CameraModelByName("amg8833"));
  ThermalCamera camera(model, {}, KeepTemperatures());
  VehicleTruth v = Hovering(0.0);
  v.altitude_m = 25.0 * camera.focal_x_px();
  FireConfig config;
  config.jitter_fraction = 0.0;
  FireGrid fire(config, MakeRng(1, "fire"));
  // Pixel (4, 4) is right of and behind the nadir: x in [500, 525], y in [475, 500].
  fire.AddIgnition({Vec2(512.0, 487.0), 0.0});
  fire.AdvanceTo(0.0);
  const TemperatureField field(fire, {});
  Rng rng = MakeRng(1, "camera");
  const ThermalImage one = camera.Render(v, field, 0.0, rng);
  const double ambient_w = RadianceFromC(25.0), flame_w = RadianceFromC(700.0);
  const double expected_c = ApparentCFromRadiance(ambient_w + (flame_w - ambient_w) * 25.0 / 625.0);
  EXPECT_NEAR(one.TemperatureC(4, 4), expected_c, 0.01);
  EXPECT_GT(one.TemperatureC(4, 4), 100.0);
  EXPECT_LT(one.TemperatureC(4, 4), 700.0);
  EXPECT_FLOAT_EQ(one.TemperatureC(3, 4), 25.0F);
  // A second burning cell in the same pixel doubles the excess radiance.
  fire.AddIgnition({Vec2(517.0, 482.0), 0.0});
  fire.AdvanceTo(0.0);
  const ThermalImage two = camera.Render(v, field, 0.0, rng);
  const double excess_one = RadianceFromC(one.TemperatureC(4, 4)) - ambient_w;
  const double excess_two = RadianceFromC(two.TemperatureC(4, 4)) - ambient_w;
  EXPECT_NEAR(excess_two / excess_one, 2.0, 1e-4);
}

TEST(ThermalCamera, NoiseOnAUniformSceneHasTheModelsNetd) {
  for (const char* name : {"seed", "lepton35"}) {
    SCOPED_TRACE(name);
    const common::CameraModel& model = common::CameraModelByName(name);
    ThermalCamera camera(model, {}, KeepTemperatures());
    Scene scene;
    const TemperatureField field(scene.fire, {});
    Rng rng = MakeRng(2, "camera");
    double sum = 0.0, sum_sq = 0.0, n = 0.0;
    for (int frame = 0; frame < 5; ++frame) {
      const ThermalImage image = camera.Render(Hovering(60.0), field, frame, rng);
      for (const float t : image.apparent_temperature_c) {
        const double d = static_cast<double>(t) - 25.0;
        sum += d;
        sum_sq += d * d;
        n += 1.0;
      }
    }
    const double mean = sum / n;
    const double sigma = std::sqrt(sum_sq / n - mean * mean);
    EXPECT_NEAR(mean, 0.0, 4.0 * model.netd_k / std::sqrt(n));
    EXPECT_NEAR(sigma, model.netd_k, 0.03 * model.netd_k);
    // Consecutive frames differ (fresh noise), same seed repeats exactly.
    Rng a = MakeRng(3, "camera"), b = MakeRng(3, "camera");
    const ThermalImage f1 = camera.Render(Hovering(60.0), field, 0.0, a);
    EXPECT_NE(camera.Render(Hovering(60.0), field, 0.1, a).apparent_temperature_c,
              f1.apparent_temperature_c);
    EXPECT_EQ(camera.Render(Hovering(60.0), field, 0.0, b).apparent_temperature_c,
              f1.apparent_temperature_c);
  }
}

TEST(ThermalCamera, BadMountOrOptionsAreRejectedNamingTheField) {
  const common::CameraModel& seed = common::CameraModelByName("seed");
  const auto expect_field = [&](CameraMount mount, ThermalCameraOptions options,
                                const std::string& field) {
    try {
      ThermalCamera camera(seed, mount, options);
      ADD_FAILURE() << field << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  expect_field({10.0}, {}, "camera_pitch_deg");
  expect_field({-95.0}, {}, "camera_pitch_deg");
  ThermalCameraOptions options;
  options.fixed_max_c = -5.0;
  expect_field({}, options, "fixed_max_c");
  options = {};
  options.max_range_m = 0.0;
  expect_field({}, options, "max_range_m");
  options = {};
  options.agc_min_span_k = -1.0;
  expect_field({}, options, "agc_min_span_k");
  common::CameraModel broken = seed;
  broken.hfov_deg = 0.0;
  EXPECT_THROW(ThermalCamera{broken}, std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::sim2d
