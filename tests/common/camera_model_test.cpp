#include "fireswarm/common/camera_model.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

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

}  // namespace
}  // namespace fireswarm::common
