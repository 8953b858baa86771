// FireDetector on frames rendered by sim2d's camera: a fire is reported once
// per pass and where it is; rock and noise never; persistence, the end of a
// pass and the repeat interval.
#include "fireswarm/agents/fire_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "agents/thermal_scene.hpp"

namespace fireswarm::agents {
namespace {

using sim2d::Vec2;
using testing::ThermalScene;

constexpr double kFrameRateHz = 9.0;  // the seed camera

// A camera on a vehicle, a detector, and the reports so far.
struct Flight {
  Flight(const common::CameraModel& model, sim2d::ThermalCameraOptions options = {},
         std::uint64_t seed = 1)
      : camera(model, {}, options),
        detector(FireDetectorConfigFor(model)),
        rng(sim2d::MakeRng(seed, "camera")) {}

  // Renders one frame of `scene` from `v` at `time_s` and runs the detector on it.
  std::vector<FireDetection> Frame(const ThermalScene& scene, const sim2d::VehicleTruth& v,
                                   double time_s) {
    camera.Render(v, scene.field, time_s, rng, image);
    std::vector<FireDetection> found =
        detector.Process(time_s, testing::FrameOf(image), testing::PoseOf(v, camera, scene.geo));
    reports.insert(reports.end(), found.begin(), found.end());
    return found;
  }

  sim2d::ThermalCamera camera;
  FireDetector detector;
  sim2d::Rng rng;
  sim2d::ThermalImage image;
  std::vector<FireDetection> reports;
};

// One burning forest cell at (500, 500); returns its centre.
// Flies north over x = 505 at 100 m, 10 m/s, nose 5 deg down, one frame per
// 1/9 s from y = 350 to y = 650, the time starting at `t0_s`.
void FlyNorthOver(Flight& flight, const ThermalScene& scene, double t0_s = 1.0) {
  for (int k = 0; k <= 270; ++k) {
    const double dt = k / kFrameRateHz;
    flight.Frame(scene, testing::Flying({505.0, 350.0 + 10.0 * dt}, 100.0, 0.0, -5.0), t0_s + dt);
  }
}

TEST(FireDetector, ReportsAFireOnceWithinAFewMetresOfTruth) {
  for (const common::CameraModel& model : common::CameraModels()) {
    SCOPED_TRACE(std::string(model.name));
    ThermalScene scene;
    const Vec2 truth = LightOneCell(scene);
    Flight flight(model);
    FlyNorthOver(flight, scene);
    ASSERT_EQ(flight.reports.size(), 1U);
    const FireDetection& d = flight.reports.front();
    // A fire smaller than a pixel is located to within half a pixel's footprint
    // per axis: the AMG8833's pixels are 14.4 m across at 100 m (10.2 m on the
    // diagonal), the seed camera's 1.6 m, the Lepton's 0.7 m.
    const double tolerance_m = model.width_px < 16 ? 10.2 : 3.0;
    EXPECT_LT((scene.Local(d.position) - truth).norm(), tolerance_m);
    // GPS 2.12 m per axis and attitude errors at 100 m: a few metres.
    EXPECT_GT(d.sigma_north_m, 2.12);
    EXPECT_LT(d.sigma_north_m, 6.0);
    EXPECT_GT(d.sigma_east_m, 2.12);
    EXPECT_LT(d.sigma_east_m, 6.0);
    EXPECT_LE(std::abs(d.correlation_ne), 1.0);
    EXPECT_GE(d.confidence, 0.0);
    EXPECT_LE(d.confidence, 1.0);
    EXPECT_NEAR(d.observer_altitude_m, 100.0, 1e-9);
    EXPECT_GE(d.peak_temperature_c, std::min(150.0, model.max_scene_c) - 1.0);
    EXPECT_GE(d.pixel_count, 1);
    // Reported from the lane flown over it.
    const Vec2 observer = scene.Local(d.observer);
    EXPECT_LT(std::abs(observer.x() - 505.0), 1e-6);
  }
}

// The pose given lazily: asked for only on frames with fire in view (or a pass
// ending), once per frame, and the reports are those of the plain pose.
TEST(FireDetector, AsksForThePoseOnlyWhenAFrameNeedsIt) {
  const common::CameraModel& model = common::CameraModelByName("seed");
  ThermalScene scene;
  LightOneCell(scene);
  Flight plain(model);
  Flight lazy(model);
  int frames_with_pose = 0;
  constexpr int kFrames = 270;
  for (int k = 0; k <= kFrames; ++k) {
    const double t = 1.0 + k / kFrameRateHz;
    const sim2d::VehicleTruth v = testing::Flying({505.0, 350.0 + 10.0 * (t - 1.0)}, 100.0);
    plain.Frame(scene, v, t);
    lazy.camera.Render(v, scene.field, t, lazy.rng, lazy.image);
    int asked = 0;
    const std::vector<FireDetection> found =
        lazy.detector.Process(t, testing::FrameOf(lazy.image), [&] {
          ++asked;
          return testing::PoseOf(v, lazy.camera, scene.geo);
        });
    lazy.reports.insert(lazy.reports.end(), found.begin(), found.end());
    EXPECT_LE(asked, 1);
    frames_with_pose += asked;
  }
  ASSERT_EQ(plain.reports.size(), 1U);
  ASSERT_EQ(lazy.reports.size(), 1U);
  EXPECT_EQ(lazy.reports.front().position.lat_deg, plain.reports.front().position.lat_deg);
  EXPECT_EQ(lazy.reports.front().position.lon_deg, plain.reports.front().position.lon_deg);
  EXPECT_EQ(lazy.reports.front().observer.lat_deg, plain.reports.front().observer.lat_deg);
  // The fire is in view for a few seconds of the 30 s flown.
  EXPECT_GT(frames_with_pose, 0);
  EXPECT_LT(frames_with_pose, kFrames / 2);
}

TEST(FireDetector, SunHeatedRockIsNeverReported) {
  const std::vector<sim2d::Distractor> rocks = {{Vec2(500.0, 450.0), 8.0, 70.0},
                                                {Vec2(510.0, 520.0), 3.0, 65.0},
                                                {Vec2(490.0, 600.0), 5.0, 40.0}};
  for (const common::CameraModel& model : common::CameraModels()) {
    for (const bool auto_gain : {false, true}) {
      SCOPED_TRACE(std::string(model.name) + (auto_gain ? " auto" : " fixed"));
      ThermalScene scene(rocks);
      Flight flight(model, auto_gain ? testing::AutoGain() : sim2d::ThermalCameraOptions{});
      int frames_with_hot_rock = 0;
      for (int k = 0; k <= 270; ++k) {
        const double t = k / kFrameRateHz;
        flight.Frame(scene, testing::Flying({505.0, 350.0 + 10.0 * t}, 100.0, 0.0, -5.0), t);
        frames_with_hot_rock +=
            FindHotRegions(testing::FrameOf(flight.image), flight.detector.config().regions).empty()
                ? 0
                : 1;
      }
      EXPECT_GT(frames_with_hot_rock, 50);  // the rock was seen, as hot...
      EXPECT_TRUE(flight.reports.empty());  // ...and never reported
      EXPECT_EQ(flight.detector.candidate_count(), 0U);
    }
  }
}

TEST(FireDetector, SensorNoiseAloneIsNeverReported) {
  ThermalScene scene;
  for (const common::CameraModel& model : common::CameraModels()) {
    for (const bool auto_gain : {false, true}) {
      for (const std::uint64_t seed : {1U, 2U, 3U}) {
        SCOPED_TRACE(std::string(model.name) + (auto_gain ? " auto" : " fixed") + " seed " +
                     std::to_string(seed));
        Flight flight(model, auto_gain ? testing::AutoGain() : sim2d::ThermalCameraOptions{}, seed);
        int hot_frames = 0;
        for (int k = 0; k < 500; ++k) {
          const double t = k / kFrameRateHz;
          flight.Frame(scene, testing::Flying({200.0 + t, 300.0}, 100.0, 45.0, -3.0, 1.0), t);
          hot_frames +=
              FindHotRegions(testing::FrameOf(flight.image), flight.detector.config().regions)
                      .empty()
                  ? 0
                  : 1;
        }
        EXPECT_EQ(hot_frames, 0);
        EXPECT_TRUE(flight.reports.empty());
      }
    }
  }
}

TEST(FireDetector, ReportsAPassOfAtLeastPersistFramesWhenItEnds) {
  ThermalScene scene;
  LightOneCell(scene);
  Flight flight(common::CameraModelByName("seed"));
  ASSERT_EQ(flight.detector.config().persist_frames, 3);
  const sim2d::VehicleTruth over_fire = testing::Flying({505.0, 490.0}, 100.0);
  const sim2d::VehicleTruth elsewhere = testing::Flying({505.0, 800.0}, 100.0);
  double t = 1.0;
  const auto next = [&](const sim2d::VehicleTruth& v) {
    t += 1.0 / kFrameRateHz;
    return flight.Frame(scene, v, t);
  };
  EXPECT_TRUE(next(over_fire).empty());
  EXPECT_TRUE(next(over_fire).empty());
  EXPECT_TRUE(next(elsewhere).empty());  // two in a row, then a gap: not a fire
  EXPECT_TRUE(next(over_fire).empty());
  EXPECT_TRUE(next(over_fire).empty());
  EXPECT_EQ(flight.detector.candidate_count(), 1U);  // one candidate, remembered across the gap
  EXPECT_TRUE(next(over_fire).empty());              // the third in a row: a fire, still in view
  EXPECT_TRUE(next(over_fire).empty());
  EXPECT_EQ(next(elsewhere).size(), 1U);  // the pass is over: reported
  EXPECT_TRUE(next(elsewhere).empty());
}

TEST(FireDetector, APassIsLocatedByTheMeanOfAllItsFrames) {
  // The attitude the vehicle reads is off by 1 deg (1-sigma, roll and pitch,
  // new in every frame): 1.7 m on the ground from 100 m per frame. Without the
  // noise every pass is located 0.7 m off (the cell's pixels, fixed across the
  // lane). Reported after its first three frames, the mean error is 1.9 m; the
  // mean of the frames of the whole pass (10 s, 90 frames) brings it to 0.7 m.
  std::mt19937_64 random(3);
  std::normal_distribution<double> attitude_error_rad(0.0, 1.0 * testing::kDeg);
  double sum_error_m = 0.0;
  constexpr int kPasses = 10;
  for (int pass = 0; pass < kPasses; ++pass) {
    SCOPED_TRACE(pass);
    ThermalScene scene;
    const Vec2 truth = LightOneCell(scene);
    Flight flight(common::CameraModelByName("seed"), {}, static_cast<std::uint64_t>(pass) + 1);
    for (int k = 0; k <= 270; ++k) {
      const double t = 1.0 + k / kFrameRateHz;
      const sim2d::VehicleTruth v = testing::Flying({505.0, 350.0 + 10.0 * (t - 1.0)}, 100.0);
      flight.camera.Render(v, scene.field, t, flight.rng, flight.image);
      ObserverPose pose = testing::PoseOf(v, flight.camera, scene.geo);
      pose.roll_rad += attitude_error_rad(random);
      pose.pitch_rad += attitude_error_rad(random);
      for (const FireDetection& d :
           flight.detector.Process(t, testing::FrameOf(flight.image), pose)) {
        flight.reports.push_back(d);
      }
    }
    ASSERT_EQ(flight.reports.size(), 1U);
    // Reported after the fire had passed under the vehicle.
    EXPECT_GT(scene.Local(flight.reports.front().observer).y(), truth.y() + 30.0);
    sum_error_m += (scene.Local(flight.reports.front().position) - truth).norm();
  }
  EXPECT_LT(sum_error_m / kPasses, 1.0);
}

TEST(FireDetector, ReportsAgainOnlyAfterTheIntervalInViewOrNot) {
  ThermalScene scene;
  LightOneCell(scene);
  Flight flight(common::CameraModelByName("seed"));
  const double interval_s = flight.detector.config().report_interval_s;
  const double wait_s = flight.detector.config().max_pass_wait_s;
  ASSERT_EQ(interval_s, 15.0);
  ASSERT_EQ(wait_s, 10.0);
  const sim2d::VehicleTruth over_fire = testing::Flying({505.0, 490.0}, 100.0);
  const sim2d::VehicleTruth elsewhere = testing::Flying({505.0, 800.0}, 100.0);
  // In view 0-30 s, away 30-32 s, in view 32-40 s, away 40-42 s, in view 42-60 s.
  const auto in_view = [](double t) {
    return !(t >= 30.0 && t < 32.0) && !(t >= 40.0 && t < 42.0);
  };
  std::vector<double> report_times;
  for (int k = 0; k < 60 * 9; ++k) {
    const double t = k / kFrameRateHz;
    for (const FireDetection& d : flight.Frame(scene, in_view(t) ? over_fire : elsewhere, t)) {
      report_times.push_back(d.time_s);
    }
  }
  // In view from 0 s: when it had been in view 10 s, then 15 s later (the
  // interval); that view's end at 30 s is not reported again. The view 32-40 s
  // when it ends; the view from 42 s once 15 s had passed since 40 s.
  const std::vector<double> expected = {wait_s, wait_s + interval_s, 40.0, 40.0 + interval_s};
  ASSERT_EQ(report_times.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_GE(report_times[i], expected[i] - 1e-9) << i;
    EXPECT_LT(report_times[i], expected[i] + 1.0 / kFrameRateHz) << i;
  }
}

TEST(FireDetector, ForgetsCandidatesLongUnseen) {
  ThermalScene scene;
  LightOneCell(scene);
  Flight flight(common::CameraModelByName("seed"));
  const sim2d::VehicleTruth over_fire = testing::Flying({505.0, 490.0}, 100.0);
  const sim2d::VehicleTruth elsewhere = testing::Flying({505.0, 800.0}, 100.0);
  flight.Frame(scene, over_fire, 0.0);
  EXPECT_EQ(flight.detector.candidate_count(), 1U);
  flight.Frame(scene, elsewhere, 4.0);
  EXPECT_EQ(flight.detector.candidate_count(), 1U);
  flight.Frame(scene, elsewhere, 6.0);  // unseen for more than forget_after_s (5 s)
  EXPECT_EQ(flight.detector.candidate_count(), 0U);
}

TEST(FireDetector, RejectsBadConfigAndTimeGoingBack) {
  FireDetectorConfig config;
  config.persist_frames = 0;
  try {
    FireDetector detector(config);
    FAIL() << "persist_frames = 0 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("persist_frames"), std::string::npos);
  }
  config = FireDetectorConfig{};
  config.regions.min_excess_k = -1.0;
  EXPECT_THROW(FireDetector{config}, std::invalid_argument);

  ThermalScene scene;
  Flight flight(common::CameraModelByName("seed"));
  flight.Frame(scene, testing::Flying({300.0, 300.0}, 100.0), 5.0);
  EXPECT_THROW(flight.Frame(scene, testing::Flying({300.0, 300.0}, 100.0), 4.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::agents
