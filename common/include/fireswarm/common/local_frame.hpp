// Geodetic <-> local metres: the one place fireswarm converts between WGS84 and
// the flat local frame that the planner and the simulator work in.
#pragma once

#include <memory>

namespace fireswarm::common {

/// A WGS84 position: latitude and longitude in degrees.
struct LatLon {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
};

/// A horizontal position in the local frame, metres east and north of its origin.
struct EastNorth {
  double east_m = 0.0;
  double north_m = 0.0;
};

/// A local East-North frame on the ground around a geodetic origin.
///
/// The projection is azimuthal equidistant on the WGS84 ellipsoid (GeographicLib):
/// the distance and bearing of every point from the origin are exactly the
/// geodesic ones, and a round trip is exact to well below a millimetre. Scale
/// grows away from the origin by about d^2 / (6 R^2): 1.6e-6 at 20 km, so local
/// distances between far-apart points are off by at most centimetres over the
/// areas fireswarm flies. Altitudes are metres above the (flat) ground, kept
/// beside the projection, not in it.
class LocalFrame {
 public:
  /// Throws std::invalid_argument when the origin is not a valid latitude
  /// ([-90, 90]) and longitude ([-180, 180]), or not finite.
  explicit LocalFrame(LatLon origin);
  ~LocalFrame();
  LocalFrame(const LocalFrame& other);
  LocalFrame& operator=(const LocalFrame& other);
  LocalFrame(LocalFrame&&) noexcept;
  LocalFrame& operator=(LocalFrame&&) noexcept;

  LatLon origin() const { return origin_; }

  /// Projects a WGS84 position to local metres. Precondition: valid lat/lon
  /// (see IsValidLatLon); points more than ~1,000 km away are not meaningful.
  EastNorth ToLocal(LatLon point) const;

  /// The inverse of ToLocal.
  LatLon ToGeodetic(EastNorth point) const;

 private:
  struct Impl;
  LatLon origin_;
  std::unique_ptr<Impl> impl_;
};

/// True when the latitude is in [-90, 90] and the longitude in [-180, 180], both finite.
bool IsValidLatLon(LatLon point);

}  // namespace fireswarm::common
