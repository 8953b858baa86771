// What the SVG map shows beside the map: the title with the run's figures, and the
// legend (every symbol, then each drone's colour by receiver ID, in columns when
// there are many). Private to the run library.
#pragma once

#include <cstddef>
#include <string>

#include "fireswarm/run/report.hpp"
#include "svg_geometry.hpp"

namespace fireswarm::run::internal {

/// Two lines from `top_left`, about 50 px tall: "fireswarm run: <name>", then fires
/// confirmed n/N, coverage %, false tracks, collisions, seed and simulated time.
/// `name` is escaped here.
std::string TitleMarkup(const Report& report, const std::string& name, Px top_left);

/// The legend's size: drone rows per column as fit beside a map `map_height_px`
/// tall (at least 8), and the width and height it then takes, px.
struct LegendLayout {
  double rows_per_column = 0.0;
  double width_px = 0.0;
  double height_px = 0.0;
};
LegendLayout LayOutLegend(std::size_t drones, double map_height_px);

/// The legend from `top_left`, its drones from report.vehicles.
std::string LegendMarkup(const Report& report, const LegendLayout& layout, Px top_left);

}  // namespace fireswarm::run::internal
