// The SVG map's symbols (see svg_markers.hpp).
#include "svg_markers.hpp"

#include "xml_text.hpp"

namespace fireswarm::run::internal {
namespace {

constexpr int kDecimals = 1;
// The triangle's base sits this share of its half-size below the centre.
constexpr double kTriangleBaseShare = 0.75;

}  // namespace

std::string N(double value_px) {
  return FixedNumber(value_px, kDecimals);
}
std::string XY(Px p) {
  return N(p.x) + " " + N(p.y);
}

std::string FireMarker(Px p) {
  return "<circle cx=\"" + N(p.x) + "\" cy=\"" + N(p.y) + "\" r=\"" + N(kFireRadiusPx) +
         "\" fill=\"" + kFireColour + "\" stroke=\"#7a0000\" stroke-width=\"1\"/>\n";
}

std::string FusedMarker(Px p) {
  return "<path class=\"fused\" d=\"M" + XY({p.x - kCrossHalfPx, p.y}) + "H" +
         N(p.x + kCrossHalfPx) + "M" + XY({p.x, p.y - kCrossHalfPx}) + "V" + N(p.y + kCrossHalfPx) +
         "\" stroke=\"#000\" stroke-width=\"2\" fill=\"none\"/>\n";
}

std::string EllipseMarkup(Px centre, const EllipsePx& ellipse) {
  std::string markup = "<ellipse class=\"fused-ellipse\" cx=\"" + N(centre.x) + "\" cy=\"" +
                       N(centre.y) + "\" rx=\"" + N(ellipse.rx) + "\" ry=\"" + N(ellipse.ry) + "\"";
  if (N(ellipse.rotate_deg) != N(0.0)) {
    markup += " transform=\"rotate(" + N(ellipse.rotate_deg) + " " + XY(centre) + ")\"";
  }
  return markup + " fill=\"#000\" fill-opacity=\"0.06\" stroke=\"#000\" stroke-width=\"1\"" +
         " stroke-dasharray=\"4 3\"/>\n";
}

std::string FalseTrackMarker(Px p) {
  return "<path class=\"false-track\" d=\"M" + XY({p.x, p.y - kTriangleHalfPx}) + "L" +
         XY({p.x + kTriangleHalfPx, p.y + kTriangleHalfPx * kTriangleBaseShare}) + "L" +
         XY({p.x - kTriangleHalfPx, p.y + kTriangleHalfPx * kTriangleBaseShare}) +
         "Z\" fill=\"#fff\"" + " stroke=\"" + kFalseTrackColour + "\" stroke-width=\"2\"/>\n";
}

std::string CollisionMarker(Px p) {
  const double a = kCollisionArmPx;
  return "<g class=\"collision\"><circle cx=\"" + N(p.x) + "\" cy=\"" + N(p.y) + "\" r=\"" +
         N(kCollisionRadiusPx) + "\" fill=\"#ffd400\" stroke=\"#000\" stroke-width=\"1\"/>" +
         "<path d=\"M" + XY({p.x - a, p.y - a}) + "L" + XY({p.x + a, p.y + a}) + "M" +
         XY({p.x + a, p.y - a}) + "L" + XY({p.x - a, p.y + a}) +
         "\" stroke=\"#000\" stroke-width=\"2.5\"/></g>\n";
}

std::string LaunchMarker(Px p) {
  return "<rect class=\"launch\" x=\"" + N(p.x - kLaunchHalfPx) + "\" y=\"" +
         N(p.y - kLaunchHalfPx) + "\" width=\"" + N(2.0 * kLaunchHalfPx) + "\" height=\"" +
         N(2.0 * kLaunchHalfPx) + "\" fill=\"#fff\" stroke=\"#000\" stroke-width=\"2\"/>\n";
}

std::string TrackEndMarker(Px p, const std::string& colour) {
  return "<circle cx=\"" + N(p.x) + "\" cy=\"" + N(p.y) + "\" r=\"" + N(kTrackEndRadiusPx) +
         "\" fill=\"" + colour + "\" stroke=\"#fff\" stroke-width=\"1\"/>\n";
}
}  // namespace fireswarm::run::internal
