#include "fireswarm/common/local_frame.hpp"

#include <GeographicLib/Ellipsoid.hpp>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fireswarm::common {
namespace {

// ToGeodetic stops correcting the depth below the tangent plane once the
// ground point it gives is within this much of the one asked for, horizontally.
constexpr double kHorizontalToleranceM = 1e-6;
// Enough for any point within ~1,000 km; one is taken over the areas fireswarm flies.
constexpr int kMaxDepthCorrections = 4;
// The far side of the Earth folds back onto the tangent plane (the antipode lands
// on the origin). A point this deep below the plane (about 1,100 km out) is put at
// its straight-line (chord) distance from the origin instead, along its bearing,
// so that every check of a distance from the origin still finds it far away.
constexpr double kFarDepthM = 100'000.0;

}  // namespace

struct LocalFrame::Impl {
  explicit Impl(LatLon origin)
      : tangent(origin.lat_deg, origin.lon_deg, 0.0, GeographicLib::Geocentric::WGS84()),
        meridional_radius_m(
            GeographicLib::Ellipsoid::WGS84().MeridionalCurvatureRadius(origin.lat_deg)),
        transverse_radius_m(
            GeographicLib::Ellipsoid::WGS84().TransverseCurvatureRadius(origin.lat_deg)) {}

  GeographicLib::LocalCartesian tangent;  // ENU at the origin, on the ellipsoid
  double meridional_radius_m;             // the ground's radii of curvature at the origin
  double transverse_radius_m;
};

bool IsValidLatLon(LatLon point) {
  return std::isfinite(point.lat_deg) && std::isfinite(point.lon_deg) &&
         std::abs(point.lat_deg) <= 90.0 && std::abs(point.lon_deg) <= 180.0;
}

LocalFrame::LocalFrame(LatLon origin) : origin_(origin) {
  if (!IsValidLatLon(origin)) {
    throw std::invalid_argument("local frame origin out of range: lat " +
                                std::to_string(origin.lat_deg) + ", lon " +
                                std::to_string(origin.lon_deg));
  }
  impl_ = std::make_unique<Impl>(origin);
}

LocalFrame::~LocalFrame() = default;
LocalFrame::LocalFrame(const LocalFrame& other)
    : origin_(other.origin_), impl_(std::make_unique<Impl>(other.origin_)) {}
LocalFrame& LocalFrame::operator=(const LocalFrame& other) {
  origin_ = other.origin_;
  impl_ = std::make_unique<Impl>(origin_);
  return *this;
}
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;

EastNorth LocalFrame::ToLocal(LatLon point) const {
  EastNorth local;
  double up_m = 0.0;
  impl_->tangent.Forward(point.lat_deg, point.lon_deg, 0.0, local.east_m, local.north_m, up_m);
  if (up_m < -kFarDepthM) {
    const double chord_m =
        std::sqrt(local.east_m * local.east_m + local.north_m * local.north_m + up_m * up_m);
    const double across_m = std::hypot(local.east_m, local.north_m);
    if (across_m > 0.0) {
      local.east_m *= chord_m / across_m;
      local.north_m *= chord_m / across_m;
    } else {
      local.east_m = chord_m;
    }
  }
  return local;
}

LatLon LocalFrame::ToGeodetic(EastNorth point) const {
  // The ground falls away below the tangent plane, by d^2 / (2 R) at d from the
  // origin (7.8 m at 10 km), R the ground's radius of curvature in that direction
  // (Euler's formula from the two at the origin). The point of the plane's
  // normal line through (east, north) at that depth is then within millimetres of
  // the ground; its height is taken off once more while it still moves the
  // ground point by more than the tolerance (height times d / R).
  const double east2 = point.east_m * point.east_m;
  const double north2 = point.north_m * point.north_m;
  double up_m = -0.5 * (north2 / impl_->meridional_radius_m + east2 / impl_->transverse_radius_m);
  const double slope = std::sqrt(east2 + north2) / impl_->meridional_radius_m;
  LatLon geodetic;
  double height_m = 0.0;
  impl_->tangent.Reverse(point.east_m, point.north_m, up_m, geodetic.lat_deg, geodetic.lon_deg,
                         height_m);
  for (int i = 0; i < kMaxDepthCorrections && std::abs(height_m) * slope > kHorizontalToleranceM;
       ++i) {
    up_m -= height_m;
    impl_->tangent.Reverse(point.east_m, point.north_m, up_m, geodetic.lat_deg, geodetic.lon_deg,
                           height_m);
  }
  return geodetic;
}

}  // namespace fireswarm::common
