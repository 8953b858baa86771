#include "fireswarm/common/camera_model.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace fireswarm::common {
namespace {

TEST(CameraModel, KnowsTheThreeModels) {
  const CameraModel& seed = CameraModelByName("seed");
  EXPECT_EQ(seed.width_px, 96);
  EXPECT_EQ(seed.height_px, 64);
  EXPECT_DOUBLE_EQ(seed.hfov_deg, 75.0);
  EXPECT_DOUBLE_EQ(seed.vfov_deg, 60.0);
  const CameraModel& amg = CameraModelByName("amg8833");
  EXPECT_EQ(amg.width_px, 8);
  EXPECT_DOUBLE_EQ(amg.vfov_deg, 60.0);
  EXPECT_DOUBLE_EQ(amg.frame_rate_hz, 10.0);
  const CameraModel& lepton = CameraModelByName("lepton35");
  EXPECT_EQ(lepton.width_px, 160);
  EXPECT_DOUBLE_EQ(lepton.frame_rate_hz, 8.7);
  // Square pixels: tan(vfov/2) / tan(hfov/2) = 120 / 160.
  EXPECT_NEAR(lepton.vfov_deg, 44.3, 0.1);
  EXPECT_EQ(CameraModels().size(), 3u);
}

TEST(CameraModel, UnknownNameIsAClearError) {
  EXPECT_EQ(FindCameraModel("flir"), nullptr);
  try {
    CameraModelByName("flir");
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "unknown camera model 'flir' (known: seed|amg8833|lepton35)");
  }
}

TEST(ValidateCamera, AcceptsEveryKnownModelOnEveryMount) {
  for (const CameraModel& model : CameraModels()) {
    for (const double pitch_deg : {-90.0, -45.0, 0.0}) {
      EXPECT_NO_THROW(ValidateCamera(model, pitch_deg, "test")) << model.name << " " << pitch_deg;
    }
  }
}

TEST(ValidateCamera, NamesTheContextAndTheFirstBadField) {
  const auto message = [](const CameraModel& model, double pitch_deg) {
    try {
      ValidateCamera(model, pitch_deg, "thermal camera");
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  const CameraModel seed = CameraModelByName("seed");
  CameraModel bad = seed;
  bad.width_px = 0;
  EXPECT_EQ(message(bad, -90.0), "thermal camera: width_px = 0 must be > 0");
  bad = seed;
  bad.vfov_deg = 180.0;
  EXPECT_EQ(message(bad, -90.0), "thermal camera: vfov_deg = 180 must be in (0, 180)");
  bad = seed;
  bad.netd_k = -0.1;
  EXPECT_EQ(message(bad, -90.0), "thermal camera: netd_k = -0.1 must be >= 0");
  EXPECT_EQ(message(seed, 10.0),
            "thermal camera: camera_pitch_deg = 10 must be in [-90, 0] (negative down)");
  EXPECT_EQ(message(seed, -91.0),
            "thermal camera: camera_pitch_deg = -91 must be in [-90, 0] (negative down)");
}

}  // namespace
}  // namespace fireswarm::common
