#include "fireswarm/common/local_frame.hpp"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <cmath>
#include <stdexcept>

namespace fireswarm::common {
namespace {

constexpr LatLon kOrigin{45.5017, -73.5673};  // Montreal

TEST(LocalFrame, OriginMapsToZero) {
  const LocalFrame frame(kOrigin);
  const EastNorth local = frame.ToLocal(kOrigin);
  EXPECT_NEAR(local.east_m, 0.0, 1e-9);
  EXPECT_NEAR(local.north_m, 0.0, 1e-9);
}

TEST(LocalFrame, RoundTripIsMillimetreExactOver20Km) {
  const LocalFrame frame(kOrigin);
  for (double east_m = -20'000.0; east_m <= 20'000.0; east_m += 2'500.0) {
    for (double north_m = -20'000.0; north_m <= 20'000.0; north_m += 2'500.0) {
      const EastNorth back = frame.ToLocal(frame.ToGeodetic({east_m, north_m}));
      EXPECT_NEAR(back.east_m, east_m, 1e-3) << east_m << "," << north_m;
      EXPECT_NEAR(back.north_m, north_m, 1e-3) << east_m << "," << north_m;
    }
  }
}

TEST(LocalFrame, RoundTripIsMicrometreExactFarOut) {
  const LocalFrame frame(kOrigin);
  for (const double distance_m : {50'000.0, 200'000.0, 1'000'000.0}) {
    for (double bearing_rad = 0.0; bearing_rad < 2.0 * M_PI; bearing_rad += M_PI / 6.0) {
      const EastNorth point{distance_m * std::sin(bearing_rad), distance_m * std::cos(bearing_rad)};
      const EastNorth back = frame.ToLocal(frame.ToGeodetic(point));
      EXPECT_NEAR(back.east_m, point.east_m, 1e-5) << distance_m << " m at " << bearing_rad;
      EXPECT_NEAR(back.north_m, point.north_m, 1e-5) << distance_m << " m at " << bearing_rad;
    }
  }
}

// The tangent plane's scale: a point d from the origin in the frame lies a
// geodesic distance of about d + d^3 / (6 R^2) away on the ground, in every direction.
TEST(LocalFrame, DistancesFromTheOriginAreTheGeodesicOnesToAFewMillimetresOver10Km) {
  const LocalFrame frame(kOrigin);
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  for (const double distance_m : {1'000.0, 10'000.0, 20'000.0}) {
    const double expected_excess_m =
        distance_m * distance_m * distance_m / (6.0 * 6.371e6 * 6.371e6);
    for (double bearing_rad = 0.0; bearing_rad < 2.0 * M_PI; bearing_rad += M_PI / 8.0) {
      const LatLon ground = frame.ToGeodetic(
          {distance_m * std::sin(bearing_rad), distance_m * std::cos(bearing_rad)});
      double geodesic_m = 0.0;
      double azimuth1_deg = 0.0;
      double azimuth2_deg = 0.0;
      wgs84.Inverse(kOrigin.lat_deg, kOrigin.lon_deg, ground.lat_deg, ground.lon_deg, geodesic_m,
                    azimuth1_deg, azimuth2_deg);
      EXPECT_NEAR(geodesic_m - distance_m, expected_excess_m, 0.02 * expected_excess_m + 1e-6)
          << distance_m << " m at " << bearing_rad;
      // The bearing from the origin is the frame's, to a micro-radian.
      const double bearing_deg = bearing_rad * 180.0 / M_PI;
      EXPECT_NEAR(std::remainder(azimuth1_deg - bearing_deg, 360.0), 0.0, 1e-4)
          << distance_m << " m at " << bearing_rad;
    }
  }
}

// The tangent plane alone would put the antipode on the origin.
TEST(LocalFrame, PointsOnTheFarSideOfTheEarthStayFarAway) {
  const LocalFrame frame(kOrigin);
  const auto distance_km = [&](LatLon point) {
    const EastNorth local = frame.ToLocal(point);
    return std::hypot(local.east_m, local.north_m) / 1e3;
  };
  EXPECT_GT(distance_km({-kOrigin.lat_deg, kOrigin.lon_deg + 180.0}), 12'000.0);
  EXPECT_GT(distance_km({0.0, 0.0}), 5'000.0);
  EXPECT_GT(distance_km({kOrigin.lat_deg + 20.0, kOrigin.lon_deg}), 2'000.0);
  // Within the folding depth the plane's own distance holds (about 1,000 km here).
  EXPECT_NEAR(distance_km({kOrigin.lat_deg + 9.0, kOrigin.lon_deg}), 1'000.0, 5.0);
}

TEST(LocalFrame, AxesPointEastAndNorth) {
  const LocalFrame frame(kOrigin);
  // 0.01 deg of latitude is about 1,111 m everywhere; of longitude, cos(lat) of that.
  const EastNorth north = frame.ToLocal({kOrigin.lat_deg + 0.01, kOrigin.lon_deg});
  EXPECT_NEAR(north.east_m, 0.0, 1e-6);
  EXPECT_NEAR(north.north_m, 1111.5, 2.0);
  const EastNorth east = frame.ToLocal({kOrigin.lat_deg, kOrigin.lon_deg + 0.01});
  EXPECT_NEAR(east.east_m, 1111.5 * std::cos(kOrigin.lat_deg * M_PI / 180.0), 3.0);
  EXPECT_NEAR(east.north_m, 0.0, 0.1);
}

TEST(LocalFrame, RejectsAnOriginOutOfRange) {
  EXPECT_THROW(LocalFrame({91.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(LocalFrame({0.0, -180.5}), std::invalid_argument);
  EXPECT_THROW(LocalFrame({NAN, 0.0}), std::invalid_argument);
  EXPECT_FALSE(IsValidLatLon({0.0, 200.0}));
  EXPECT_TRUE(IsValidLatLon({-90.0, 180.0}));
}

TEST(LocalFrame, CopiesProjectTheSame) {
  const LocalFrame frame(kOrigin);
  LocalFrame copy = frame;
  const EastNorth a = frame.ToLocal({45.6, -73.4});
  const EastNorth b = copy.ToLocal({45.6, -73.4});
  EXPECT_DOUBLE_EQ(a.east_m, b.east_m);
  EXPECT_DOUBLE_EQ(a.north_m, b.north_m);
}

}  // namespace
}  // namespace fireswarm::common
