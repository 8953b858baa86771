#include "fireswarm/planner/footprint.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fireswarm/planner/plan.hpp"

namespace fireswarm::planner {
namespace {

using ::testing::HasSubstr;

double TanHalfDeg(double deg) {
  return std::tan(deg * std::numbers::pi / 360.0);
}

TEST(Footprint, NadirWidthForEachCamera) {
  const double h = 60.0;
  EXPECT_NEAR(FootprintWidthM(common::CameraModelByName("seed"), h, -90), 2 * h * TanHalfDeg(75),
              1e-9);
  EXPECT_NEAR(FootprintWidthM(common::CameraModelByName("seed"), h, -90), 92.08, 0.01);
  EXPECT_NEAR(FootprintWidthM(common::CameraModelByName("amg8833"), h, -90), 69.28, 0.01);
  EXPECT_NEAR(FootprintWidthM(common::CameraModelByName("lepton35"), h, -90), 65.16, 0.01);
}

TEST(Footprint, TiltedMountUsesTheNearEdge) {
  const common::CameraModel& camera = common::CameraModelByName("amg8833");
  const double h = 50.0;
  // Axis 30 deg below the horizon, vfov 60: the near edge looks 60 deg down, at
  // slant range along the axis h / (sin 30 + tan 30 cos 30) = h / 1.
  const double width = FootprintWidthM(camera, h, -30);
  EXPECT_NEAR(width, 2 * h * TanHalfDeg(60) / 1.0, 1e-9);
  // Here the near edge looks 60 deg down at the same depth as nadir: same width.
  EXPECT_NEAR(width, FootprintWidthM(camera, h, -90), 1e-9);
  // At -45 the near edge (75 deg down) is at depth h / (sin 45 + tan 30 cos 45).
  const double r45 = std::sqrt(0.5);
  EXPECT_NEAR(FootprintWidthM(camera, h, -45),
              2 * h * TanHalfDeg(60) / (r45 + TanHalfDeg(60) * r45), 1e-9);
  // Always narrower than the row through the optical axis.
  const double axis_depth = h / std::sin(45 * std::numbers::pi / 180);
  EXPECT_LT(FootprintWidthM(camera, h, -45), 2 * axis_depth * TanHalfDeg(60));
}

TEST(Footprint, SweepWidthAppliesTheOverlap) {
  FleetSpec fleet;
  fleet.camera = &common::CameraModelByName("seed");
  fleet.altitude_m = 60;
  fleet.side_overlap = 0.1;
  EXPECT_NEAR(SweepWidthM(fleet), 0.9 * 2 * 60 * TanHalfDeg(75), 1e-9);
}

TEST(Footprint, RejectsBadInputNamingTheField) {
  const common::CameraModel& camera = common::CameraModelByName("seed");
  try {
    FootprintWidthM(camera, 0.0, -90);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("altitude_m"));
  }
  try {
    FootprintWidthM(camera, 60.0, 10);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("camera_pitch_deg"));
  }
  FleetSpec fleet;
  try {
    SweepWidthM(fleet);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("camera"));
  }
  fleet.camera = &camera;
  fleet.side_overlap = 1.0;
  try {
    SweepWidthM(fleet);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("side_overlap"));
  }
}

}  // namespace
}  // namespace fireswarm::planner
