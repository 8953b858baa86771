// FindHotRegions on frames rendered by sim2d's camera and on small synthetic
// frames: the relative threshold, the fire level, saturation, labelling.
#include "fireswarm/agents/hot_regions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "agents/thermal_scene.hpp"

namespace fireswarm::agents {
namespace {

using sim2d::Vec2;
using testing::FrameOf;
using testing::ThermalScene;

constexpr double kFireCentreM = 500.0;

// One burning 5 m cell at (500, 500) (forest: it burns ten minutes and spreads
// 0.3 m/min, so it stays one cell through every test).
// Open fuel around (500, 500), burned for `seconds`: a disc of flames and
// embers (all above 150 C), symmetric about the ignited cell in still air.
void GrowBigFire(ThermalScene& scene, double seconds) {
  scene.fire.SetFuelRect(Vec2(400.0, 400.0), Vec2(600.0, 600.0), sim2d::Fuel::kOpen);
  scene.fire.AddIgnition({Vec2(kFireCentreM, kFireCentreM), 0.0});
  scene.fire.AdvanceTo(seconds);
}

// Mean centre of the cells at or above `level_c`: the true hot area's centroid.
Vec2 HotCellsCentre(const sim2d::FireGrid& fire, double level_c) {
  Vec2 sum = Vec2::Zero();
  int count = 0;
  for (int row = 0; row < fire.rows(); ++row) {
    for (int col = 0; col < fire.cols(); ++col) {
      const sim2d::CellIndex cell{col, row};
      if (fire.CellTemperatureC(cell) < level_c) continue;
      sum += fire.CellCenter(cell);
      ++count;
    }
  }
  return sum / count;
}

TEST(ThermalImageRange, GreyLevelsMapBackToTheRenderedTemperatures) {
  ThermalScene scene({{Vec2(480.0, 510.0), 6.0, 60.0}});
  LightOneCell(scene);
  for (const sim2d::GainMode gain : {sim2d::GainMode::kFixed, sim2d::GainMode::kAuto}) {
    sim2d::ThermalCameraOptions options;
    options.gain = gain;
    options.keep_temperatures = true;
    sim2d::ThermalCamera camera(common::CameraModelByName("lepton35"), {}, options);
    sim2d::Rng rng = sim2d::MakeRng(3, "camera");
    const sim2d::ThermalImage image =
        camera.Render(testing::Flying({500.0, 500.0}, 100.0), scene.field, 1.0, rng);
    ASSERT_GT(image.range_max_c, image.range_min_c);
    const double step_k = (image.range_max_c - image.range_min_c) / 255.0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      const double t_c =
          std::clamp<double>(image.apparent_temperature_c[i], image.range_min_c, image.range_max_c);
      ASSERT_NEAR(image.range_min_c + image.pixels[i] * step_k, t_c, 0.5 * step_k + 1e-3) << i;
    }
  }
}

TEST(FindHotRegions, FindsAFireWhereTheCameraProjectsIt) {
  for (const common::CameraModel& model : common::CameraModels()) {
    for (const bool auto_gain : {false, true}) {
      SCOPED_TRACE(std::string(model.name) + (auto_gain ? " auto" : " fixed"));
      ThermalScene scene;
      LightOneCell(scene);
      const Vec2 truth = scene.fire.CellCenter(*scene.fire.CellAt({kFireCentreM, kFireCentreM}));
      sim2d::ThermalCamera camera(model, {},
                                  auto_gain ? testing::AutoGain() : sim2d::ThermalCameraOptions{});
      const sim2d::VehicleTruth v = testing::Flying({490.0, 490.0}, 100.0, 25.0, -4.0, 2.0);
      sim2d::Rng rng = sim2d::MakeRng(5, "camera");
      const sim2d::ThermalImage image = camera.Render(v, scene.field, 1.0, rng);
      const std::vector<HotRegion> regions =
          FindHotRegions(FrameOf(image), DetectorConfigFor(model));
      ASSERT_EQ(regions.size(), 1U);
      const HotRegion& fire = regions.front();
      EXPECT_TRUE(fire.is_fire);
      EXPECT_GE(fire.peak_temperature_c, std::min(150.0, model.max_scene_c) - 1.0);
      // The centroid is within a pixel of where the fire's centre projects.
      const std::optional<sim2d::PixelCoord> in_view = camera.GroundToPixel(v, truth);
      ASSERT_TRUE(in_view.has_value());
      const sim2d::PixelCoord expected = *in_view;
      EXPECT_NEAR(fire.centroid.u_px, expected.u_px, 1.0);
      EXPECT_NEAR(fire.centroid.v_px, expected.v_px, 1.0);
      EXPECT_LE(fire.min_col, expected.col());
      EXPECT_GE(fire.max_col, expected.col());
      EXPECT_LE(fire.min_row, expected.row());
      EXPECT_GE(fire.max_row, expected.row());
    }
  }
}

TEST(FindHotRegions, SunHeatedRockIsHotButNotFire) {
  for (const common::CameraModel& model : common::CameraModels()) {
    for (const bool auto_gain : {false, true}) {
      SCOPED_TRACE(std::string(model.name) + (auto_gain ? " auto" : " fixed"));
      ThermalScene scene({{Vec2(500.0, 500.0), 8.0, 70.0}});
      sim2d::ThermalCamera camera(model, {},
                                  auto_gain ? testing::AutoGain() : sim2d::ThermalCameraOptions{});
      sim2d::Rng rng = sim2d::MakeRng(6, "camera");
      const sim2d::ThermalImage image =
          camera.Render(testing::Flying({500.0, 500.0}, 60.0), scene.field, 0.0, rng);
      const std::vector<HotRegion> regions =
          FindHotRegions(FrameOf(image), DetectorConfigFor(model));
      ASSERT_EQ(regions.size(), 1U);          // seen as hot...
      EXPECT_FALSE(regions.front().is_fire);  // ...but no fire
      EXPECT_LT(regions.front().peak_temperature_c, 72.0);
    }
  }
}

TEST(FindHotRegions, NoiseAloneHasNoHotPixelEvenUnderAutomaticGain) {
  ThermalScene scene;
  for (const common::CameraModel& model : common::CameraModels()) {
    sim2d::ThermalCamera camera(model, {}, testing::AutoGain());
    sim2d::Rng rng = sim2d::MakeRng(8, "camera");
    const sim2d::ThermalImage image =
        camera.Render(testing::Flying({300.0, 300.0}, 100.0), scene.field, 0.0, rng);
    const CameraFrame frame = FrameOf(image);
    // Automatic gain stretches the noise over (nearly) the whole grey range...
    EXPECT_LT(frame.range_max_c - frame.range_min_c, 3.0);
    const FrameBackground background = EstimateBackground(frame, DetectorConfigFor(model));
    EXPECT_NEAR(background.background_c, 25.0, 0.5);
    EXPECT_LT(background.noise_k, 4.0 * model.netd_k + 0.05);
    // ...and the kelvin floor above the background keeps every pixel cold.
    EXPECT_TRUE(FindHotRegions(frame, DetectorConfigFor(model)).empty()) << model.name;
  }
}

TEST(FindHotRegions, SaturatedFireCentroidIsTheHotAreaCentre) {
  ThermalScene scene;
  GrowBigFire(scene, 400.0);
  const Vec2 truth = HotCellsCentre(scene.fire, 150.0);
  const common::CameraModel& model = common::CameraModelByName("seed");  // saturates at 150 C
  for (const bool auto_gain : {false, true}) {
    SCOPED_TRACE(auto_gain ? "auto" : "fixed");
    sim2d::ThermalCamera camera(model, {},
                                auto_gain ? testing::AutoGain() : sim2d::ThermalCameraOptions{});
    const sim2d::VehicleTruth v = testing::Flying({490.0, 485.0}, 100.0, 30.0, -5.0, 0.0);
    sim2d::Rng rng = sim2d::MakeRng(9, "camera");
    const sim2d::ThermalImage image = camera.Render(v, scene.field, 400.0, rng);
    const std::vector<HotRegion> regions = FindHotRegions(FrameOf(image), DetectorConfigFor(model));
    ASSERT_EQ(regions.size(), 1U);
    const HotRegion& fire = regions.front();
    EXPECT_TRUE(fire.is_fire);
    EXPECT_GT(fire.pixel_count, 200);
    EXPECT_NEAR(fire.peak_temperature_c, 150.0, 0.01);
    // Located on the ground, the centroid is within a pixel (1.6 m) of the truth.
    const ObserverPose pose = testing::PoseOf(v, camera, scene.geo);
    const std::optional<common::EastNorth> offset = IntersectGround(pose, fire.centroid);
    ASSERT_TRUE(offset.has_value());
    const Vec2 found = v.position_m + Vec2(offset->east_m, offset->north_m);
    EXPECT_LT((found - truth).norm(), 1.6);
  }
}

TEST(FindHotRegions, FireFillingMostOfTheFrameStaysHot) {
  ThermalScene scene;
  GrowBigFire(scene, 400.0);
  const common::CameraModel& model = common::CameraModelByName("seed");
  sim2d::ThermalCamera camera(model, {}, testing::AutoGain());
  sim2d::Rng rng = sim2d::MakeRng(10, "camera");
  const sim2d::ThermalImage image =
      camera.Render(testing::Flying({502.5, 502.5}, 22.0), scene.field, 400.0, rng);
  const CameraFrame frame = FrameOf(image);
  const FrameBackground background = EstimateBackground(frame, DetectorConfigFor(model));
  EXPECT_GT(background.background_c, 140.0);  // the median pixel is fire
  const std::vector<HotRegion> regions = FindHotRegions(frame, DetectorConfigFor(model));
  ASSERT_FALSE(regions.empty());
  EXPECT_TRUE(regions.front().is_fire);
  EXPECT_GT(regions.front().pixel_count, 96 * 64 / 2);
}

TEST(FindHotRegions, SaturationBelowTheFireLevelCountsAsFire) {
  ThermalScene scene;
  LightOneCell(scene);
  const common::CameraModel& amg = common::CameraModelByName("amg8833");  // saturates at 80 C
  sim2d::ThermalCamera camera(amg);
  sim2d::Rng rng = sim2d::MakeRng(11, "camera");
  const sim2d::ThermalImage image =
      camera.Render(testing::Flying({500.0, 500.0}, 100.0), scene.field, 1.0, rng);
  const std::vector<HotRegion> with_saturation =
      FindHotRegions(FrameOf(image), DetectorConfigFor(amg));
  ASSERT_EQ(with_saturation.size(), 1U);
  EXPECT_TRUE(with_saturation.front().is_fire);
  // Without knowing the sensor saturates, an 80 C peak is below 150 C: no fire.
  const std::vector<HotRegion> without = FindHotRegions(FrameOf(image), DetectorConfig{});
  ASSERT_EQ(without.size(), 1U);
  EXPECT_FALSE(without.front().is_fire);
}

// A synthetic 8 x 6 frame, grey 40 everywhere, range 0..255 C (1 K per grey).
struct SyntheticFrame {
  std::vector<std::uint8_t> pixels = std::vector<std::uint8_t>(48, 40);
  void Set(int col, int row, std::uint8_t grey) {
    pixels[static_cast<std::size_t>(row * 8 + col)] = grey;
  }
  CameraFrame Frame() const {
    CameraFrame frame;
    frame.width_px = 8;
    frame.height_px = 6;
    frame.pixels = pixels;
    frame.range_min_c = 0.0;
    frame.range_max_c = 255.0;
    return frame;
  }
};

TEST(FindHotRegions, LabelsEightConnectedRegionsAndDropsSmallOnes) {
  SyntheticFrame s;
  s.Set(1, 1, 200);  // a diagonal pair: one region
  s.Set(2, 2, 200);
  s.Set(6, 4, 60);  // a lone warm pixel: hot (20 K over), not fire
  const std::vector<HotRegion> regions = FindHotRegions(s.Frame(), DetectorConfig{});
  ASSERT_EQ(regions.size(), 2U);
  EXPECT_EQ(regions[0].pixel_count, 2);
  EXPECT_DOUBLE_EQ(regions[0].centroid.u_px, 2.0);  // mean of pixel centres 1.5 and 2.5
  EXPECT_DOUBLE_EQ(regions[0].centroid.v_px, 2.0);
  EXPECT_TRUE(regions[0].is_fire);
  EXPECT_DOUBLE_EQ(regions[0].peak_temperature_c, 200.0);
  EXPECT_FALSE(regions[1].is_fire);
  DetectorConfig config;
  config.min_region_px = 2;
  EXPECT_EQ(FindHotRegions(s.Frame(), config).size(), 1U);
  // Below the kelvin floor: 9 K over the background is not hot.
  SyntheticFrame faint;
  faint.Set(3, 3, 49);
  EXPECT_TRUE(FindHotRegions(faint.Frame(), DetectorConfig{}).empty());
}

// Frames settled without the histogram (every pixel within min_excess_k of the
// darkest) and frames just beyond: one hot pixel anywhere, in the vectorised
// blocks of 1024 and 64 pixels or in the remainder after them
// (97 x 13 = 1024 + 3 x 64 + 45).
TEST(FindHotRegions, OneWarmPixelAnywhereIsFoundOnlyBeyondTheKelvinFloor) {
  constexpr int kWidth = 97, kHeight = 13;
  for (const int where : {0, 63, 64, 1023, 1024, 1100, 1215, 1216, kWidth * kHeight - 1}) {
    for (const int darkest : {35, 40}) {
      CameraFrame frame;
      frame.width_px = kWidth;
      frame.height_px = kHeight;
      frame.range_min_c = 0.0;
      frame.range_max_c = 255.0;  // 1 K per grey level
      std::vector<std::uint8_t> pixels(kWidth * kHeight, 40);
      pixels[static_cast<std::size_t>((where + 7) % (kWidth * kHeight))] =
          static_cast<std::uint8_t>(darkest);
      frame.pixels = pixels;
      // Background 40 C, threshold 50 C: 10 K over is not hot, 11 K over is.
      for (const int grey : {45, 50, 51, 200}) {
        pixels[static_cast<std::size_t>(where)] = static_cast<std::uint8_t>(grey);
        frame.pixels = pixels;
        const std::vector<HotRegion> regions = FindHotRegions(frame, DetectorConfig{});
        SCOPED_TRACE("pixel " + std::to_string(where) + ", grey " + std::to_string(grey) +
                     ", darkest " + std::to_string(darkest));
        if (grey <= 50) {
          EXPECT_TRUE(regions.empty());
        } else {
          ASSERT_EQ(regions.size(), 1U);
          EXPECT_EQ(regions.front().pixel_count, 1);
          EXPECT_DOUBLE_EQ(regions.front().peak_temperature_c, grey);
          EXPECT_EQ(regions.front().is_fire, grey >= 150);
        }
      }
    }
  }
}

TEST(FindHotRegions, RejectsAMalformedFrame) {
  SyntheticFrame s;
  CameraFrame frame = s.Frame();
  frame.range_max_c = frame.range_min_c;
  EXPECT_THROW(FindHotRegions(frame, DetectorConfig{}), std::invalid_argument);
  frame = s.Frame();
  frame.height_px = 7;
  try {
    FindHotRegions(frame, DetectorConfig{});
    FAIL() << "a frame with too few pixels was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pixels"), std::string::npos);
  }
}

}  // namespace
}  // namespace fireswarm::agents
