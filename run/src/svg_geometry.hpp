// The SVG map's arithmetic, apart from its drawing: the local-metres-to-pixels
// view, track thinning, the covariance ellipse, the scale bar's length and the
// drone colours. Private to the run library.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::run::internal {

/// A point on the picture: x right, y down, px.
struct Px {
  double x = 0.0;
  double y = 0.0;
};

/// The smallest east/north box holding every point added.
struct Bounds {
  double min_east_m = 0.0;
  double max_east_m = 0.0;
  double min_north_m = 0.0;
  double max_north_m = 0.0;
  bool empty = true;

  void Add(common::EastNorth point);
};

/// Local metres onto a rectangle of the picture, north up, one scale both ways.
struct MapView {
  double west_m = 0.0;   ///< east coordinate of the rectangle's left edge
  double north_m = 0.0;  ///< north coordinate of its top edge
  double px_per_m = 1.0;
  Px top_left;  ///< where the rectangle starts on the picture
  double width_px = 0.0;
  double height_px = 0.0;

  Px ToPx(common::EastNorth point) const {
    return {top_left.x + (point.east_m - west_m) * px_per_m,
            top_left.y + (north_m - point.north_m) * px_per_m};
  }
};

/// A view showing `bounds` (widened to `min_extent_m` across, about its centre, and
/// padded by `padding_fraction` of its larger side all round; an empty box is taken
/// as the origin) as large as fits `max_width_px` x `max_height_px`, at `top_left`.
MapView FitView(Bounds bounds, double min_extent_m, double padding_fraction, double max_width_px,
                double max_height_px, Px top_left);

/// `points` without what does not show: first every point closer than
/// `min_step_px` to the last one kept (the final point takes the place of the last
/// kept one when it is that close), then (Douglas-Peucker) every point within
/// `max_deviation_px` of the segment between the points kept around it. The first
/// and the final point stay, except that a track that never moved `min_step_px`
/// from its first point comes back as that one point.
std::vector<Px> ThinPolyline(const std::vector<Px>& points, double min_step_px,
                             double max_deviation_px);

/// An SVG ellipse about its centre: semi-axes in px, `rx` along the x axis after
/// rotating it by `rotate_deg` (SVG's rotate(): clockwise on the picture).
struct EllipsePx {
  double rx = 0.0;          ///< major semi-axis
  double ry = 0.0;          ///< minor semi-axis
  double rotate_deg = 0.0;  ///< in (-90, 90]
};

/// The ellipse `sigmas` standard deviations out along the principal axes of the
/// horizontal covariance `covariance_ne_m2` = [nn, ne, ee] (north, east; m^2), at
/// `px_per_m`. Nullopt when it is not finite or not symmetric positive semidefinite
/// (a negative eigenvalue beyond rounding).
std::optional<EllipsePx> CovarianceEllipse(const std::array<double, 3>& covariance_ne_m2,
                                           double sigmas, double px_per_m);

/// The longest 1, 2 or 5 times a power of ten metres not over `max_m` (> 0).
double ScaleBarLengthM(double max_m);
/// "500 m", "2 km".
std::string LengthLabel(double length_m);

/// The colour of the drone with `receiver_id`, "#rrggbb": twelve well-separated
/// colours for IDs 1..12 (no red: red is fire), then hues a golden angle apart.
std::string DroneColour(int receiver_id);

}  // namespace fireswarm::run::internal
