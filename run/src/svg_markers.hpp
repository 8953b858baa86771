// The SVG map's symbols, drawn the same on the map and in its legend, and the one
// way it writes coordinates. Private to the run library.
#pragma once

#include <string>

#include "svg_geometry.hpp"

namespace fireswarm::run::internal {

/// Sizes of the symbols, px.
inline constexpr double kFireRadiusPx = 5.0;
inline constexpr double kCrossHalfPx = 7.0;
inline constexpr double kTriangleHalfPx = 7.0;
inline constexpr double kCollisionRadiusPx = 9.0;
inline constexpr double kCollisionArmPx = 5.0;
inline constexpr double kLaunchHalfPx = 6.0;
inline constexpr double kTrackEndRadiusPx = 3.0;

inline constexpr const char* kFireColour = "#e01b1b";
inline constexpr const char* kFalseTrackColour = "#c000c0";
inline constexpr const char* kNoFlyColour = "#c62828";
inline constexpr const char* kAreaFill = "#e4f2d9";
inline constexpr const char* kAreaStroke = "#3b7a2a";

/// A coordinate or length on the picture: one decimal, a tenth of a pixel.
std::string N(double value_px);
/// "x y".
std::string XY(Px p);

/// True fire: red dot.
std::string FireMarker(Px p);
/// Fused fire: black cross.
std::string FusedMarker(Px p);
/// The fused fire's uncertainty ellipse about `centre`.
std::string EllipseMarkup(Px centre, const EllipsePx& ellipse);
/// False track: hollow magenta triangle.
std::string FalseTrackMarker(Px p);
/// Collision: black X on a yellow disc.
std::string CollisionMarker(Px p);
/// Launch site: white square.
std::string LaunchMarker(Px p);
/// Where a drone's track ends: a dot in its colour.
std::string TrackEndMarker(Px p, const std::string& colour);

}  // namespace fireswarm::run::internal
