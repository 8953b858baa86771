#include "fireswarm/common/local_frame.hpp"

#include <gtest/gtest.h>

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
