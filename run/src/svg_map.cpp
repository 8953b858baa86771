// The run's SVG map: the view and layout first (everything drawn decides the
// extent), then one layer after another, bottom to top, then the title and the
// legend beside the map. Coordinates are written with one decimal (a tenth of a
// pixel), so the same run gives the same file.
#include "fireswarm/run/svg_map.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/common/atomic_file.hpp"
#include "fireswarm/planner/area_io.hpp"
#include "svg_geometry.hpp"
#include "svg_legend.hpp"
#include "svg_markers.hpp"
#include "xml_text.hpp"

namespace fireswarm::run {
namespace {

using internal::Bounds;
using internal::CollisionMarker;
using internal::EllipseMarkup;
using internal::FalseTrackMarker;
using internal::FireMarker;
using internal::FixedNumber;
using internal::FusedMarker;
using internal::kAreaFill;
using internal::kAreaStroke;
using internal::kCollisionRadiusPx;
using internal::kNoFlyColour;
using internal::LaunchMarker;
using internal::MapView;
using internal::N;
using internal::Px;
using internal::TrackEndMarker;
using internal::XmlEscape;
using internal::XY;

// Layout, px.
constexpr double kMapMaxWidthPx = 960.0;
constexpr double kMapMaxHeightPx = 720.0;
constexpr double kMarginPx = 16.0;
constexpr double kTitleHeightPx = 52.0;
constexpr double kLegendGapPx = 20.0;
// Extent: one fire alone still gets a map a few hundred metres across.
constexpr double kMinExtentM = 100.0;
constexpr double kPaddingFraction = 0.05;
// Track thinning: what is under a pixel does not show.
constexpr double kMinStepPx = 1.0;
constexpr double kMaxDeviationPx = 0.5;
constexpr int kDecimals = 1;
constexpr double kScaleBarMaxShare = 0.25;  // of the map's width
// An ellipse smaller than this is hidden under its cross anyway.
constexpr double kMinEllipsePx = 0.5;
constexpr double kLabelOffsetPx = 9.0;

// The position in local metres, or nullopt for one that cannot be drawn.
std::optional<common::EastNorth> Local(const planner::SearchArea& area, common::LatLon position) {
  if (!common::IsValidLatLon(position)) return std::nullopt;
  const common::EastNorth local = area.frame.ToLocal(position);
  if (!std::isfinite(local.east_m) || !std::isfinite(local.north_m) ||
      std::hypot(local.east_m, local.north_m) > planner::kMaxDistanceFromOriginM) {
    return std::nullopt;
  }
  return local;
}

common::EastNorth EastNorthOf(const planner::Point& point) {
  return {point.x(), point.y()};
}

// Everything that is drawn on the map decides its extent.
Bounds MapBounds(const Report& report, const Scenario& scenario) {
  Bounds bounds;
  for (const planner::MultiPolygon* zones : {&scenario.area.area, &scenario.area.no_fly}) {
    for (const planner::Polygon& polygon : *zones) {
      for (const planner::Point& point : polygon.outer()) bounds.Add(EastNorthOf(point));
    }
  }
  const auto add = [&](common::LatLon position) {
    if (const auto local = Local(scenario.area, position)) bounds.Add(*local);
  };
  add(scenario.fleet.launch);
  for (const LaunchSiteConfig& site : scenario.fleet.launch_sites) add(site.position);
  for (const auto& [id, vehicle] : report.vehicles) {
    for (const common::LatLon& position : vehicle.track) add(position);
  }
  for (const FireOutcome& fire : report.fires) {
    add(fire.truth);
    if (fire.fused) add(*fire.fused);
  }
  for (const FalseTrack& track : report.false_tracks) add(track.position);
  for (const Collision& collision : report.collisions) add(collision.position);
  return bounds;
}

struct Label {
  Px at;
  std::string text;
};

// --- Map layers. ---

// One path per polygon, outer ring and holes together: with fill-rule evenodd the
// holes (lakes, cut-out no-fly zones) stay open.
std::string PolygonPath(const planner::Polygon& polygon, const MapView& view) {
  std::string d;
  const auto add_ring = [&](const planner::Polygon::ring_type& ring) {
    std::vector<Px> points;
    for (const planner::Point& point : ring) points.push_back(view.ToPx(EastNorthOf(point)));
    // The closing point repeats the first; "Z" closes the ring.
    if (points.size() > 1) points.pop_back();
    points = internal::ThinPolyline(points, kMinStepPx, 0.0);
    if (points.size() < 3) return;
    d += "M" + XY(points.front()) + "L";
    for (std::size_t i = 1; i < points.size(); ++i) d += (i > 1 ? " " : "") + XY(points[i]);
    d += "Z";
  };
  add_ring(polygon.outer());
  for (const auto& inner : polygon.inners()) add_ring(inner);
  return d.empty() ? "" : "<path d=\"" + d + "\"/>\n";
}

std::string AreaLayer(const Scenario& scenario, const MapView& view) {
  std::string svg = "<g id=\"area\" fill=\"" + std::string(kAreaFill) + "\" stroke=\"" +
                    kAreaStroke +
                    "\" stroke-width=\"1.5\""
                    " fill-rule=\"evenodd\">\n";
  for (const planner::Polygon& polygon : scenario.area.area) svg += PolygonPath(polygon, view);
  svg += "</g>\n<g id=\"no-fly\" fill=\"url(#no-fly-hatch)\" stroke=\"" +
         std::string(kNoFlyColour) + "\" stroke-width=\"1.5\" fill-rule=\"evenodd\">\n";
  for (const planner::Polygon& polygon : scenario.area.no_fly) svg += PolygonPath(polygon, view);
  return svg + "</g>\n";
}

std::string TrackLayer(const Report& report, const Scenario& scenario, const MapView& view) {
  std::string paths =
      "<g id=\"tracks\" fill=\"none\" stroke-width=\"1.6\" stroke-linejoin=\"round\""
      " stroke-linecap=\"round\">\n";
  std::string ends = "<g id=\"track-ends\">\n";
  for (const auto& [id, vehicle] : report.vehicles) {
    std::vector<Px> points;
    for (const common::LatLon& position : vehicle.track) {
      if (const auto local = Local(scenario.area, position)) points.push_back(view.ToPx(*local));
    }
    points = internal::ThinPolyline(points, kMinStepPx, kMaxDeviationPx);
    if (points.empty()) continue;
    const std::string colour = internal::DroneColour(id);
    std::string d = "M" + XY(points.front());
    for (std::size_t i = 1; i < points.size(); ++i) d += (i == 1 ? "L" : " ") + XY(points[i]);
    paths += "<path id=\"track-" + std::to_string(id) + "\" stroke=\"" + colour + "\" d=\"" + d +
             "\"/>\n";
    ends += TrackEndMarker(points.back(), colour);
  }
  return paths + "</g>\n" + ends + "</g>\n";
}

std::string FireLayer(const Report& report, const Scenario& scenario, const MapView& view,
                      std::vector<Label>& labels) {
  // Bottom to top: the fused fires' ellipses and error lines, the true fires' dots,
  // the fused fires' crosses (over the dot they should hit).
  std::string under = "<g id=\"fused-ellipses\">\n";
  std::string fires = "<g id=\"fires\">\n";
  std::string crosses = "<g id=\"fused-fires\">\n";
  for (std::size_t i = 0; i < report.fires.size(); ++i) {
    const FireOutcome& fire = report.fires[i];
    const std::string name = "F" + std::to_string(i + 1);
    const auto truth = Local(scenario.area, fire.truth);
    const auto fused = fire.fused ? Local(scenario.area, *fire.fused) : std::nullopt;
    if (fused) {
      const Px at = view.ToPx(*fused);
      if (truth) {
        under += "<line x1=\"" + N(at.x) + "\" y1=\"" + N(at.y) + "\" x2=\"" +
                 N(view.ToPx(*truth).x) + "\" y2=\"" + N(view.ToPx(*truth).y) +
                 "\" stroke=\"#444\" stroke-width=\"1\" stroke-dasharray=\"1 2\"/>\n";
      }
      if (fire.covariance_ne_m2) {
        const auto ellipse =
            internal::CovarianceEllipse(*fire.covariance_ne_m2, kFusedEllipseSigmas, view.px_per_m);
        if (ellipse && ellipse->rx >= kMinEllipsePx) under += EllipseMarkup(at, *ellipse);
      }
      crosses += FusedMarker(at);
    }
    if (truth) {
      const Px at = view.ToPx(*truth);
      fires += FireMarker(at);
      labels.push_back({{at.x + kLabelOffsetPx, at.y - kLabelOffsetPx},
                        fire.fused ? name : name + " not confirmed"});
    }
  }
  return under + "</g>\n" + fires + "</g>\n" + crosses + "</g>\n";
}

std::string FalseTrackLayer(const Report& report, const Scenario& scenario, const MapView& view,
                            std::vector<Label>& labels) {
  std::string svg = "<g id=\"false-tracks\">\n";
  for (const FalseTrack& track : report.false_tracks) {
    const auto local = Local(scenario.area, track.position);
    if (!local) continue;
    const Px at = view.ToPx(*local);
    svg += FalseTrackMarker(at);
    labels.push_back({{at.x + kLabelOffsetPx, at.y - kLabelOffsetPx},
                      "track " + std::to_string(track.track_id)});
  }
  return svg + "</g>\n";
}

std::string CollisionLayer(const Report& report, const Scenario& scenario, const MapView& view,
                           std::vector<Label>& labels) {
  std::string svg = "<g id=\"collisions\">\n";
  for (const Collision& collision : report.collisions) {
    const auto local = Local(scenario.area, collision.position);
    if (!local) continue;
    const Px at = view.ToPx(*local);
    svg += CollisionMarker(at);
    labels.push_back({{at.x + kCollisionRadiusPx + 2.0, at.y + 4.0},
                      "t=" + FixedNumber(collision.t_s, kDecimals) + " s (" +
                          std::to_string(collision.vehicle_a) + "\u00d7" +
                          std::to_string(collision.vehicle_b) + ")"});
  }
  return svg + "</g>\n";
}

// Labels last, over every marker, each on a white halo.
std::string LabelLayer(const std::vector<Label>& labels) {
  std::string svg =
      "<g id=\"labels\" font-size=\"11\" fill=\"#000\" stroke=\"#fff\" stroke-width=\"3\""
      " stroke-linejoin=\"round\" paint-order=\"stroke\">\n";
  for (const Label& label : labels) {
    svg += "<text x=\"" + N(label.at.x) + "\" y=\"" + N(label.at.y) + "\">" +
           XmlEscape(label.text) + "</text>\n";
  }
  return svg + "</g>\n";
}

std::string NorthArrowAndScaleBar(const MapView& view) {
  const double right = view.top_left.x + view.width_px;
  const double top = view.top_left.y;
  const Px tip{right - 20.0, top + 22.0};
  std::string svg = "<g id=\"north-arrow\"><path d=\"M" + XY(tip) + "L" +
                    XY({tip.x + 7.0, tip.y + 18.0}) + " " + XY({tip.x, tip.y + 13.0}) + " " +
                    XY({tip.x - 7.0, tip.y + 18.0}) + "Z\" fill=\"#000\"/>" + "<text x=\"" +
                    N(tip.x) + "\" y=\"" + N(tip.y - 4.0) +
                    "\" text-anchor=\"middle\" font-weight=\"bold\">N</text></g>\n";

  const double length_m =
      internal::ScaleBarLengthM(kScaleBarMaxShare * view.width_px / view.px_per_m);
  const double length_px = length_m * view.px_per_m;
  const Px left{view.top_left.x + 14.0, view.top_left.y + view.height_px - 14.0};
  const Px end{left.x + length_px, left.y};
  svg += "<g id=\"scale-bar\"><rect x=\"" + N(left.x - 6.0) + "\" y=\"" + N(left.y - 22.0) +
         "\" width=\"" + N(length_px + 12.0) + "\" height=\"28\" fill=\"#fff\"" +
         " fill-opacity=\"0.8\"/>" + "<line id=\"scale-bar-line\" x1=\"" + N(left.x) + "\" y1=\"" +
         N(left.y) + "\" x2=\"" + N(end.x) + "\" y2=\"" + N(end.y) +
         "\" stroke=\"#000\" stroke-width=\"3\"/>" + "<path d=\"M" + XY({left.x, left.y - 6.0}) +
         "V" + N(left.y) + "M" + XY({end.x, end.y - 6.0}) + "V" + N(end.y) +
         "\" stroke=\"#000\" stroke-width=\"1.5\"/>" + "<text id=\"scale-bar-label\" x=\"" +
         N((left.x + end.x) / 2.0) + "\" y=\"" + N(left.y - 8.0) + "\" text-anchor=\"middle\">" +
         internal::LengthLabel(length_m) + "</text></g>\n";
  return svg;
}

// The no-fly zones' fill: translucent red under red diagonal hatching.
std::string NoFlyHatch() {
  return "<pattern id=\"no-fly-hatch\" patternUnits=\"userSpaceOnUse\" width=\"8\" height=\"8\""
         " patternTransform=\"rotate(45)\"><rect width=\"8\" height=\"8\" fill=\"#ff0000\""
         " fill-opacity=\"0.15\"/><line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"8\" stroke=\"" +
         std::string(kNoFlyColour) + "\" stroke-width=\"3\"/></pattern>\n";
}

}  // namespace

std::string SvgMap(const Report& report, const Scenario& scenario) {
  const MapView view =
      internal::FitView(MapBounds(report, scenario), kMinExtentM, kPaddingFraction, kMapMaxWidthPx,
                        kMapMaxHeightPx, {kMarginPx, kMarginPx + kTitleHeightPx});
  const internal::LegendLayout legend =
      internal::LayOutLegend(report.vehicles.size(), view.height_px);
  const double width = view.top_left.x + view.width_px + kLegendGapPx + legend.width_px + kMarginPx;
  const double height = view.top_left.y + std::max(view.height_px, legend.height_px) + kMarginPx;
  const std::string name = report.scenario.empty() ? scenario.name : report.scenario;
  const Px map_end{view.top_left.x + view.width_px, view.top_left.y + view.height_px};

  std::vector<Label> labels;
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + N(width) +
         "\" height=\"" + N(height) + "\" viewBox=\"0 0 " + N(width) + " " + N(height) +
         "\" font-family=\"DejaVu Sans, Arial, sans-serif\" font-size=\"12\">\n";
  svg += "<title>fireswarm run: " + XmlEscape(name) + "</title>\n";
  svg += "<defs>\n" + NoFlyHatch();
  svg += "<clipPath id=\"map-clip\"><rect x=\"" + N(view.top_left.x) + "\" y=\"" +
         N(view.top_left.y) + "\" width=\"" + N(view.width_px) + "\" height=\"" +
         N(view.height_px) + "\"/></clipPath>\n</defs>\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  svg += "<g id=\"map\" clip-path=\"url(#map-clip)\">\n";
  svg += AreaLayer(scenario, view);
  svg += TrackLayer(report, scenario, view);
  // Every launch site (scenarios built in code may list none: their one launch).
  std::vector<common::LatLon> sites{scenario.fleet.launch};
  if (!scenario.fleet.launch_sites.empty()) {
    sites.clear();
    for (const LaunchSiteConfig& site : scenario.fleet.launch_sites) sites.push_back(site.position);
  }
  svg += "<g id=\"launch\">";
  for (const common::LatLon& site : sites) {
    if (const auto launch = Local(scenario.area, site)) svg += LaunchMarker(view.ToPx(*launch));
  }
  svg += "</g>\n";
  svg += FireLayer(report, scenario, view, labels);
  svg += FalseTrackLayer(report, scenario, view, labels);
  svg += CollisionLayer(report, scenario, view, labels);
  svg += LabelLayer(labels);
  svg += "</g>\n";
  svg += "<rect id=\"map-frame\" x=\"" + N(view.top_left.x) + "\" y=\"" + N(view.top_left.y) +
         "\" width=\"" + N(view.width_px) + "\" height=\"" + N(view.height_px) +
         "\" fill=\"none\" stroke=\"#888\" stroke-width=\"1\"/>\n";
  svg += NorthArrowAndScaleBar(view);
  svg += internal::TitleMarkup(report, name, {kMarginPx, kMarginPx});
  svg += internal::LegendMarkup(report, legend, {map_end.x + kLegendGapPx, view.top_left.y + 6.0});
  return svg + "</svg>\n";
}

void WriteSvgMap(const Report& report, const Scenario& scenario,
                 const std::filesystem::path& path) {
  common::WriteFileAtomically(path, SvgMap(report, scenario));
}

}  // namespace fireswarm::run
