// Sortie-sized pieces of the lane field and how one is flown. The large-area
// planner groups the field's rows into stripes of a few rows, cuts each stripe
// along its lanes into blocks of about one sortie's work (a lane may be split
// between two sorties: a cut is any x), chains blocks too small for a sortie of
// their own with their neighbours, and flies each unit out of a launch site and
// back to it.
#pragma once

#include <functional>
#include <vector>

#include "fireswarm/planner/geometry.hpp"
#include "lane_field.hpp"

namespace fireswarm::planner {

/// Rows [first_row, end_row) of a lane field between x_lo_m and x_hi_m (lane frame).
struct Block {
  std::size_t first_row = 0;
  std::size_t end_row = 0;
  double x_lo_m = 0.0;
  double x_hi_m = 0.0;
};

/// One straight pass over a row of a block, local frame.
struct Pass {
  Point from;
  Point to;
};

/// A block's passes in flying order, boustrophedon: the first row flown is the
/// bottom one or the top one, the first pass heads east or west in the lane frame.
/// Rows with nothing to fly inside the block are skipped.
std::vector<Pass> BlockPasses(const LaneField& field, const Block& block, bool bottom_up,
                              bool start_west);

/// How long a drone flies the passes: lanes at `speed_mps`, `turn_cost_s` at every
/// pass after the first, the hops between passes straight.
struct SweepTime {
  double sweep_s = 0.0;
  double turn_s = 0.0;
  double hop_s = 0.0;
  double total_s() const { return sweep_s + turn_s + hop_s; }
};
SweepTime PassesTime(const std::vector<Pass>& passes, double speed_mps, double turn_cost_s);

/// Distance between two points as a drone flies it (around no-fly zones), m.
using TransitFn = std::function<double(Point, Point)>;

/// What the sortie planner needs of the fleet.
struct SortieSpec {
  double speed_mps = 1.0;
  double turn_cost_s = 0.0;
  double endurance_s = 0.0;
};

/// A sortie's work: blocks flown one after the other, each in its chosen order.
struct SortieUnit {
  std::size_t field = 0;  ///< which of the plan's lane fields its blocks are in
  std::vector<Block> blocks;
  std::vector<std::vector<Pass>> passes;  ///< per block, flying order
  double work_s = 0.0;                    ///< passes, turns and hops inside blocks
  double link_s = 0.0;                    ///< between blocks
  Point entry;                            ///< first pass's start, local frame
  Point exit;                             ///< last pass's end
};

/// Orders the unit's blocks' passes for a drone flying from and back to `site`
/// (each block in the corner order that starts nearest to where the drone is) and
/// sets its work, links, entry and exit.
void OrientUnit(const LaneField& field, SortieUnit& unit, Point site, const SortieSpec& spec);

/// Flight time of `unit` out of and back to `site`: transit out, the unit, back.
double SortieTimeS(const SortieUnit& unit, Point site, const SortieSpec& spec,
                   const TransitFn& distance_m);

/// Cuts `field` into sortie units: stripes of `rows_per_stripe` rows (bottom up),
/// each split at x gaps wider than `gap_m` where no row has anything to fly, the
/// pieces walked as a snake (one stripe eastward, the next westward); a unit takes
/// of the walk as far as its sortie from the nearest of `sites` stays within a
/// limit, and goes on into the next piece when the hop there is short. The limit
/// is the least that needs no more than `units_wanted` units (so they come out of
/// about equal time), or the endurance when even that needs more. Empty when some
/// piece of lane cannot be flown within the endurance from any site.
std::vector<SortieUnit> CutSortieUnits(const LaneField& field, std::size_t rows_per_stripe,
                                       std::size_t units_wanted, const std::vector<Point>& sites,
                                       const SortieSpec& spec, const TransitFn& distance_m,
                                       double gap_m);

/// The other way to cut: each piece of the snake into blocks of equal lane length,
/// as few as keep a block's work <= `target_work_s` and its sortie from the nearest
/// site within the endurance; blocks with less than half the target chained with
/// their neighbours while the chain stays within the target and the endurance.
/// Units of unequal time, for an assignment that mixes them. Empty as above.
std::vector<SortieUnit> CutSortieUnitsByWork(const LaneField& field, std::size_t rows_per_stripe,
                                             double target_work_s, const std::vector<Point>& sites,
                                             const SortieSpec& spec, const TransitFn& distance_m,
                                             double gap_m);

}  // namespace fireswarm::planner
