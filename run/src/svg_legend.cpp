// The SVG map's title and legend (see svg_legend.hpp).
#include "svg_legend.hpp"

#include <algorithm>
#include <cmath>

#include "svg_markers.hpp"
#include "xml_text.hpp"

namespace fireswarm::run::internal {
namespace {

constexpr double kRowPx = 20.0;
constexpr double kSymbolColumnPx = 28.0;  // the symbol, before the text
constexpr double kMinWidthPx = 200.0;
constexpr double kDroneColumnPx = 80.0;
constexpr double kMinDroneRowsPerColumn = 8.0;
// "Legend", the symbols' rows and "Drones (receiver ID)" with the space before it.
constexpr double kFixedRows = 9.0;
constexpr double kHeadingRows = 2.5;
constexpr int kPercentDecimals = 1;
constexpr double kPercent = 100.0;
constexpr const char* kSeparator = " \u00b7 ";

}  // namespace

std::string TitleMarkup(const Report& report, const std::string& name, Px top_left) {
  std::size_t confirmed = 0;
  for (const FireOutcome& fire : report.fires) {
    if (fire.fused) ++confirmed;
  }
  const std::string summary =
      "fires confirmed " + std::to_string(confirmed) + "/" + std::to_string(report.fires.size()) +
      kSeparator + "coverage " + FixedNumber(report.coverage * kPercent, kPercentDecimals) + " %" +
      kSeparator + "false tracks " + std::to_string(report.false_tracks.size()) + kSeparator +
      "collisions " + std::to_string(report.collisions.size()) + kSeparator + "seed " +
      std::to_string(report.seed) + kSeparator + FixedNumber(report.sim_seconds, 0) +
      " s simulated";
  return "<text id=\"title\" x=\"" + N(top_left.x) + "\" y=\"" + N(top_left.y + 18.0) +
         "\" font-size=\"20\" font-weight=\"bold\">fireswarm run: " + XmlEscape(name) +
         "</text>\n<text id=\"summary\" x=\"" + N(top_left.x) + "\" y=\"" + N(top_left.y + 40.0) +
         "\" font-size=\"13\">" + summary + "</text>\n";
}

LegendLayout LayOutLegend(std::size_t drones, double map_height_px) {
  LegendLayout layout;
  layout.rows_per_column = std::max(kMinDroneRowsPerColumn,
                                    std::floor(map_height_px / kRowPx - kFixedRows - kHeadingRows));
  const double count = static_cast<double>(drones);
  const double columns = std::max(1.0, std::ceil(count / layout.rows_per_column));
  layout.width_px = std::max(kMinWidthPx, columns * kDroneColumnPx);
  layout.height_px = (kFixedRows + kHeadingRows + std::min(count, layout.rows_per_column)) * kRowPx;
  return layout;
}

std::string LegendMarkup(const Report& report, const LegendLayout& layout, Px top_left) {
  std::string svg = "<g id=\"legend\" font-size=\"12\">\n";
  double y = top_left.y;
  const auto row = [&](const std::string& symbol, const std::string& text) {
    svg += symbol + "<text x=\"" + N(top_left.x + kSymbolColumnPx) + "\" y=\"" + N(y + 4.0) +
           "\">" + text + "</text>\n";
    y += kRowPx;
  };
  const double symbol_x = top_left.x + kSymbolColumnPx / 2.0 - 4.0;
  const auto at = [&] { return Px{symbol_x, y}; };
  const auto swatch = [&](const std::string& fill, const std::string& stroke) {
    return "<rect x=\"" + N(symbol_x - 9.0) + "\" y=\"" + N(y - 6.0) +
           "\" width=\"18\" height=\"12\" fill=\"" + fill + "\" stroke=\"" + stroke +
           "\" stroke-width=\"1.5\"/>";
  };
  svg += "<text x=\"" + N(top_left.x) + "\" y=\"" + N(y + 4.0) +
         "\" font-weight=\"bold\">Legend</text>\n";
  y += kRowPx;
  row(swatch(kAreaFill, kAreaStroke), "search area (holes open)");
  row(swatch("url(#no-fly-hatch)", kNoFlyColour), "no-fly zone");
  row(LaunchMarker(at()), "launch site");
  row(FireMarker(at()), "true fire (F1, F2, ...)");
  row(FusedMarker(at()), "fused fire");
  constexpr EllipsePx kSampleEllipse{10.0, 5.0, 0.0};
  row(EllipseMarkup(at(), kSampleEllipse), "2\u03c3 ellipse of the fused fire");
  row(FalseTrackMarker(at()), "false track");
  row(CollisionMarker(at()), "collision (time, drones)");
  row(TrackEndMarker(at(), "#555"), "drone's last position");

  // With sorties, each drone's row says how many it flew of those planned.
  const bool sorties = std::ranges::any_of(
      report.vehicles, [](const auto& entry) { return entry.second.sorties_planned > 1; });
  svg += "<text x=\"" + N(top_left.x) + "\" y=\"" + N(y + 4.0 + kRowPx / 2.0) +
         "\" font-weight=\"bold\">" +
         (sorties ? "Drones (receiver ID: sorties flown/planned)" : "Drones (receiver ID)") +
         "</text>\n";
  const double drones_top = y + (kHeadingRows - 1.0) * kRowPx;
  double index = 0.0;
  for (const auto& [id, vehicle] : report.vehicles) {
    const double column = std::floor(index / layout.rows_per_column);
    const double x = top_left.x + column * kDroneColumnPx;
    const double row_y = drones_top + (index - column * layout.rows_per_column) * kRowPx;
    svg += "<path d=\"M" + XY({x, row_y}) + "H" + N(x + 20.0) + "\" stroke=\"" + DroneColour(id) +
           "\" stroke-width=\"3\"/><text x=\"" + N(x + 26.0) + "\" y=\"" + N(row_y + 4.0) + "\">" +
           std::to_string(id) +
           (sorties ? ": " + std::to_string(vehicle.sorties_flown) + "/" +
                          std::to_string(vehicle.sorties_planned)
                    : std::string()) +
           "</text>\n";
    index += 1.0;
  }
  return svg + "</g>\n";
}

}  // namespace fireswarm::run::internal
