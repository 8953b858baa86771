// White-hot images: the fixed radiometric range and its saturation, automatic
// gain, distractors against fire, and PGM files.
#include "fireswarm/sim2d/thermal_image.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "fireswarm/sim2d/thermal_camera.hpp"

namespace fireswarm::sim2d {
namespace {

VehicleTruth Hovering(const Vec2& position_m, double altitude_m) {
  VehicleTruth v;
  v.position_m = position_m;
  v.altitude_m = altitude_m;
  v.phase = FlightPhase::kFlying;
  return v;
}

// A burning patch around (500, 500) and a 60 C rock at (560, 500).
struct FireAndRockScene {
  FireGrid fire{FireConfig{}, MakeRng(1, "fire")};
  TemperatureField field{fire, {{Vec2(560.0, 500.0), 8.0, 60.0}}};
  FireAndRockScene() {
    fire.AddIgnition({Vec2(500.0, 500.0), 0.0});
    fire.AdvanceTo(300.0);
  }
};

std::string ScratchPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("fireswarm_" + name + "_" +
           std::to_string(::testing::UnitTest::GetInstance()->random_seed())))
      .string();
}

TEST(ThermalImage, WhiteHotMapsRangeLinearlyAndClamps) {
  const std::vector<float> temps = {-10.0F, 0.0F, 50.0F, 100.0F, 150.0F};
  std::vector<std::uint8_t> grey(temps.size());
  MapWhiteHot(temps, 0.0, 100.0, grey);
  EXPECT_EQ(grey, (std::vector<std::uint8_t>{0, 0, 128, 255, 255}));
}

TEST(ThermalImage, FireSaturatesToWhiteInTheFixedRange) {
  FireAndRockScene scene;
  ASSERT_GT(scene.fire.burning_count(), 0U);
  ThermalCameraOptions options;
  options.keep_temperatures = true;
  ThermalCamera camera(common::CameraModelByName("seed"), {}, options);
  Rng rng = MakeRng(1, "camera");
  const ThermalImage image =
      camera.Render(Hovering(Vec2(500.0, 500.0), 100.0), scene.field, 3.5, rng);
  EXPECT_EQ(image.width_px, 96);
  EXPECT_EQ(image.height_px, 64);
  EXPECT_DOUBLE_EQ(image.capture_time_s, 3.5);
  const PixelCoord flame =
      *camera.GroundToPixel(Hovering(Vec2(500.0, 500.0), 100.0), Vec2(502, 502));
  EXPECT_EQ(image.At(flame.col(), flame.row()), 255);                     // fire: saturated
  EXPECT_FLOAT_EQ(image.TemperatureC(flame.col(), flame.row()), 150.0F);  // the seed's limit
  // Ambient 25 C in the fixed 0..150 C range is about 42 +- noise.
  EXPECT_NEAR(image.At(2, 2), 42.5, 1.5);
  // The rock, 60 m east (right of a north-facing camera), is warm but far below fire.
  const PixelCoord rock =
      *camera.GroundToPixel(Hovering(Vec2(500.0, 500.0), 100.0), Vec2(560, 500));
  const float rock_c = image.TemperatureC(rock.col(), rock.row());
  EXPECT_NEAR(rock_c, 60.0, 1.0);
  EXPECT_GT(image.At(rock.col(), rock.row()), image.At(2, 2) + 40);
  EXPECT_LT(image.At(rock.col(), rock.row()), 128);
}

TEST(ThermalImage, AmgSaturatesAtItsLowerLimit) {
  FireAndRockScene scene;
  ThermalCameraOptions options;
  options.keep_temperatures = true;
  ThermalCamera camera(common::CameraModelByName("amg8833"), {}, options);
  Rng rng = MakeRng(1, "camera");
  const ThermalImage image =
      camera.Render(Hovering(Vec2(500.0, 500.0), 30.0), scene.field, 0.0, rng);
  const float hottest =
      *std::max_element(image.apparent_temperature_c.begin(), image.apparent_temperature_c.end());
  EXPECT_FLOAT_EQ(hottest, 80.0F);
}

TEST(ThermalImage, AutomaticGainStretchesTheFrame) {
  FireGrid fire(FireConfig{}, MakeRng(1, "fire"));
  const TemperatureField field(fire, {{Vec2(520.0, 500.0), 6.0, 45.0}});
  ThermalCameraOptions options;
  options.gain = GainMode::kAuto;
  ThermalCamera agc(common::CameraModelByName("lepton35"), {}, options);
  ThermalCamera fixed(common::CameraModelByName("lepton35"));
  const VehicleTruth v = Hovering(Vec2(500.0, 500.0), 80.0);
  Rng rng = MakeRng(1, "camera");
  const ThermalImage stretched = agc.Render(v, field, 0.0, rng);
  const ThermalImage plain = fixed.Render(v, field, 0.0, rng);
  const auto [lo, hi] = std::minmax_element(stretched.pixels.begin(), stretched.pixels.end());
  EXPECT_EQ(*lo, 0);
  EXPECT_EQ(*hi, 255);
  const auto [plo, phi] = std::minmax_element(plain.pixels.begin(), plain.pixels.end());
  EXPECT_LT(*phi - *plo, 60);
  // A uniform scene is stretched no further than agc_min_span_k: noise stays small.
  FireGrid empty(FireConfig{}, MakeRng(1, "fire"));
  const TemperatureField flat(empty, {});
  const ThermalImage uniform = agc.Render(v, flat, 0.0, rng);
  const auto [ulo, uhi] = std::minmax_element(uniform.pixels.begin(), uniform.pixels.end());
  EXPECT_GT(*ulo, 60);
  EXPECT_LT(*uhi, 195);
}

TEST(ThermalImage, PlainGroundFastPathMatchesTheGeneralSensor) {
  // Without keep_temperatures a frame of plain ground maps noise to grey levels
  // through a per-camera grey table (many levels: the same noise samples as the
  // general path, so the same pixels) or 64 pixels at a time from bit-sliced
  // samples (a few levels: other samples, so the same levels equally often).
  FireGrid empty(FireConfig{}, MakeRng(1, "fire"));
  const TemperatureField field(empty, {});
  // A narrow range, so noise shows in many grey levels (0.1 K NETD over 2 K).
  ThermalCameraOptions narrow;
  narrow.fixed_min_c = 24.0;
  narrow.fixed_max_c = 26.0;
  ThermalCameraOptions narrow_kept = narrow;
  narrow_kept.keep_temperatures = true;
  const VehicleTruth v = Hovering(Vec2(500.0, 500.0), 50.0);
  {
    ThermalCamera fast(common::CameraModelByName("seed"), {}, narrow);
    ThermalCamera general(common::CameraModelByName("seed"), {}, narrow_kept);
    Rng a = MakeRng(5, "camera"), b = MakeRng(5, "camera");
    for (int frame = 0; frame < 2; ++frame) {
      const ThermalImage fast_image = fast.Render(v, field, frame, a);
      const ThermalImage general_image = general.Render(v, field, frame, b);
      EXPECT_TRUE(fast_image.apparent_temperature_c.empty());
      EXPECT_EQ(fast_image.pixels, general_image.pixels);
      const auto [lo, hi] = std::minmax_element(fast_image.pixels.begin(), fast_image.pixels.end());
      EXPECT_GE(*hi - *lo, 20);
    }
  }
  // The default range (0 C to saturation), where 25 C sits on a grey boundary.
  for (const char* name : {"seed", "lepton35"}) {
    SCOPED_TRACE(name);
    ThermalCameraOptions kept;
    kept.keep_temperatures = true;
    ThermalCamera fast(common::CameraModelByName(name));
    ThermalCamera general(common::CameraModelByName(name), {}, kept);
    Rng a = MakeRng(4, "camera"), b = MakeRng(4, "camera");
    std::array<double, 256> fast_count{}, general_count{};
    double n = 0.0;
    for (int frame = 0; frame < 10; ++frame) {
      for (const std::uint8_t grey : fast.Render(v, field, frame, a).pixels) {
        fast_count[grey] += 1.0;
      }
      for (const std::uint8_t grey : general.Render(v, field, frame, b).pixels) {
        general_count[grey] += 1.0;
        n += 1.0;
      }
    }
    int levels = 0;
    for (std::size_t grey = 0; grey < 256; ++grey) {
      const double p = general_count[grey] / n;
      levels += general_count[grey] > 0.0 ? 1 : 0;
      // Two binomial counts of one probability: within 5 sigma of their difference.
      EXPECT_NEAR(fast_count[grey], general_count[grey],
                  5.0 * std::sqrt(2.0 * n * p * (1.0 - p)) + 1.0)
          << "grey " << grey;
    }
    EXPECT_GE(levels, 2);  // the noise does spread plain ground over levels
  }
}

TEST(ThermalImage, PgmIsWrittenAndReadBack) {
  ThermalImage image;
  image.width_px = 5;
  image.height_px = 3;
  for (int i = 0; i < 15; ++i) image.pixels.push_back(static_cast<std::uint8_t>(i * 17));
  const std::string path = ScratchPath("roundtrip.pgm");
  WritePgm(path, image);
  const ThermalImage back = ReadPgm(path);
  EXPECT_EQ(back.width_px, 5);
  EXPECT_EQ(back.height_px, 3);
  EXPECT_EQ(back.pixels, image.pixels);
  std::filesystem::remove(path);
}

TEST(ThermalImage, BadPgmFilesAreReportedWithThePath) {
  EXPECT_THROW(ReadPgm("/nonexistent/dir/x.pgm"), std::runtime_error);
  const std::string path = ScratchPath("bad.pgm");
  {
    std::ofstream out(path, std::ios::binary);
    out << "P5\n4 4\n255\nabc";  // 3 of 16 raster bytes
  }
  try {
    ReadPgm(path);
    ADD_FAILURE() << "short raster accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  {
    std::ofstream out(path, std::ios::binary);
    out << "P2\n1 1\n255\n0\n";
  }
  EXPECT_THROW(ReadPgm(path), std::runtime_error);
  std::filesystem::remove(path);
  EXPECT_THROW(WritePgm("/nonexistent/dir/x.pgm", ThermalImage{}), std::runtime_error);
}

}  // namespace
}  // namespace fireswarm::sim2d
