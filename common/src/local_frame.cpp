#include "fireswarm/common/local_frame.hpp"

#include <GeographicLib/AzimuthalEquidistant.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fireswarm::common {

struct LocalFrame::Impl {
  GeographicLib::AzimuthalEquidistant projection{GeographicLib::Geodesic::WGS84()};
};

bool IsValidLatLon(LatLon point) {
  return std::isfinite(point.lat_deg) && std::isfinite(point.lon_deg) &&
         std::abs(point.lat_deg) <= 90.0 && std::abs(point.lon_deg) <= 180.0;
}

LocalFrame::LocalFrame(LatLon origin) : origin_(origin), impl_(std::make_unique<Impl>()) {
  if (!IsValidLatLon(origin)) {
    throw std::invalid_argument("local frame origin out of range: lat " +
                                std::to_string(origin.lat_deg) + ", lon " +
                                std::to_string(origin.lon_deg));
  }
}

LocalFrame::~LocalFrame() = default;
LocalFrame::LocalFrame(const LocalFrame& other)
    : origin_(other.origin_), impl_(std::make_unique<Impl>()) {}
LocalFrame& LocalFrame::operator=(const LocalFrame& other) {
  origin_ = other.origin_;
  return *this;
}
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;

EastNorth LocalFrame::ToLocal(LatLon point) const {
  EastNorth local;
  double azimuth_deg = 0.0;
  double reduced_length_m = 0.0;
  impl_->projection.Forward(origin_.lat_deg, origin_.lon_deg, point.lat_deg, point.lon_deg,
                            local.east_m, local.north_m, azimuth_deg, reduced_length_m);
  return local;
}

LatLon LocalFrame::ToGeodetic(EastNorth point) const {
  LatLon geodetic;
  double azimuth_deg = 0.0;
  double reduced_length_m = 0.0;
  impl_->projection.Reverse(origin_.lat_deg, origin_.lon_deg, point.east_m, point.north_m,
                            geodetic.lat_deg, geodetic.lon_deg, azimuth_deg, reduced_length_m);
  return geodetic;
}

}  // namespace fireswarm::common
