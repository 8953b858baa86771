#include "sortie_blocks.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <limits>

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

constexpr int kCutBisectionSteps = 24;
constexpr double kCutResolutionM = 1.0;
constexpr int kLimitBisectionSteps = 22;
// A unit goes on into the next piece of the snake when the hop there costs at
// most this share of the sortie limit.
constexpr double kMaxLinkShare = 0.1;

// What row r of the field has to fly between x_lo and x_hi: from its first span's
// start to its last span's end inside (the gaps between spans are flown over).
bool RowExtent(const LaneRow& row, double x_lo, double x_hi, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (const Span& s : row.spans) {
    if (s.hi_m <= x_lo || s.lo_m >= x_hi) continue;
    lo = std::min(lo, std::max(s.lo_m, x_lo));
    hi = std::max(hi, std::min(s.hi_m, x_hi));
  }
  return hi > lo;
}

// The x pieces of a stripe: its rows' spans united, split at gaps wider than gap_m.
std::vector<Span> StripePieces(const LaneField& field, std::size_t first, std::size_t end,
                               double gap_m) {
  std::vector<Span> spans;
  for (std::size_t r = first; r < end; ++r) {
    spans.insert(spans.end(), field.rows[r].spans.begin(), field.rows[r].spans.end());
  }
  return MergedSpans(std::move(spans), gap_m);
}

double NearestSiteSortieS(const SortieUnit& unit, const std::vector<Point>& sites,
                          const SortieSpec& spec, const TransitFn& distance_m) {
  double best_s = std::numeric_limits<double>::infinity();
  for (const Point& site : sites) {
    best_s = std::min(best_s, SortieTimeS(unit, site, spec, distance_m));
  }
  return best_s;
}

Point NearestSite(Point p, const std::vector<Point>& sites) {
  Point best = sites.front();
  for (const Point& site : sites) {
    if (bg::comparable_distance(site, p) < bg::comparable_distance(best, p)) best = site;
  }
  return best;
}

}  // namespace

std::vector<Pass> BlockPasses(const LaneField& field, const Block& block, bool bottom_up,
                              bool start_west) {
  std::vector<Pass> passes;
  bool east = start_west;
  const std::size_t n = block.end_row - block.first_row;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t r = bottom_up ? block.first_row + k : block.end_row - 1 - k;
    double lo = 0.0, hi = 0.0;
    if (!RowExtent(field.rows[r], block.x_lo_m, block.x_hi_m, lo, hi)) continue;
    const double y = field.rows[r].y_m;
    const Point west = field.frame.ToLocal(Point{lo, y});
    const Point east_end = field.frame.ToLocal(Point{hi, y});
    passes.push_back(east ? Pass{west, east_end} : Pass{east_end, west});
    east = !east;
  }
  return passes;
}

SweepTime PassesTime(const std::vector<Pass>& passes, double speed_mps, double turn_cost_s) {
  SweepTime t;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    t.sweep_s += bg::distance(passes[i].from, passes[i].to) / speed_mps;
    if (i > 0) {
      t.turn_s += turn_cost_s;
      t.hop_s += bg::distance(passes[i - 1].to, passes[i].from) / speed_mps;
    }
  }
  return t;
}

double SortieTimeS(const SortieUnit& unit, Point site, const SortieSpec& spec,
                   const TransitFn& distance_m) {
  return (distance_m(site, unit.entry) + distance_m(unit.exit, site)) / spec.speed_mps +
         unit.work_s + unit.link_s;
}

namespace {

// Orders the unit's blocks' passes for a drone from `site`: each block in the
// corner order whose start is nearest to where the drone is (the site, then the
// previous block's end), the last one also counting its way home.
void Orient(const LaneField& field, SortieUnit& unit, Point site, const SortieSpec& spec) {
  unit.passes.clear();
  unit.work_s = unit.link_s = 0.0;
  Point at = site;
  for (std::size_t b = 0; b < unit.blocks.size(); ++b) {
    const bool last = b + 1 == unit.blocks.size();
    std::vector<Pass> best;
    double best_cost = std::numeric_limits<double>::infinity();
    for (const bool bottom_up : {true, false}) {
      for (const bool start_west : {true, false}) {
        std::vector<Pass> passes = BlockPasses(field, unit.blocks[b], bottom_up, start_west);
        if (passes.empty()) continue;
        const double cost = bg::distance(at, passes.front().from) / spec.speed_mps +
                            PassesTime(passes, spec.speed_mps, spec.turn_cost_s).total_s() +
                            (last ? bg::distance(passes.back().to, site) / spec.speed_mps : 0.0);
        if (cost < best_cost) {
          best_cost = cost;
          best = std::move(passes);
        }
      }
    }
    if (best.empty()) continue;
    if (!unit.passes.empty()) {
      unit.link_s += bg::distance(at, best.front().from) / spec.speed_mps + spec.turn_cost_s;
    }
    unit.work_s += PassesTime(best, spec.speed_mps, spec.turn_cost_s).total_s();
    at = best.back().to;
    unit.passes.push_back(std::move(best));
  }
  if (!unit.passes.empty()) {
    unit.entry = unit.passes.front().front().from;
    unit.exit = unit.passes.back().back().to;
  }
}

}  // namespace

void OrientUnit(const LaneField& field, SortieUnit& unit, Point site, const SortieSpec& spec) {
  Orient(field, unit, site, spec);
}

namespace {

// One piece of a stripe in the snake order, and the way it is walked.
struct SnakePiece {
  std::size_t first_row = 0;
  std::size_t end_row = 0;
  Span span;
  bool eastward = true;  // cut from lo to hi, else from hi to lo
};

std::vector<SnakePiece> SnakeOrder(const LaneField& field, std::size_t rows_per_stripe,
                                   double gap_m) {
  std::vector<SnakePiece> pieces;
  const std::size_t stripes = (field.rows.size() + rows_per_stripe - 1) / rows_per_stripe;
  for (std::size_t s = 0; s < stripes; ++s) {
    const std::size_t first = s * rows_per_stripe;
    const std::size_t end = std::min(field.rows.size(), first + rows_per_stripe);
    std::vector<Span> spans = StripePieces(field, first, end, gap_m);
    const bool eastward = s % 2 == 0;
    if (!eastward) std::reverse(spans.begin(), spans.end());
    for (const Span& span : spans) pieces.push_back({first, end, span, eastward});
  }
  return pieces;
}

class SnakeCutter {
 public:
  SnakeCutter(const LaneField& field, const std::vector<SnakePiece>& pieces,
              const std::vector<Point>& sites, const SortieSpec& spec, const TransitFn& distance_m)
      : field_(field), pieces_(pieces), sites_(sites), spec_(spec), distance_m_(distance_m) {}

  // Units whose sortie from the nearest site takes <= limit_s, walking the snake;
  // empty when some piece of lane cannot be flown within the limit at all.
  std::vector<SortieUnit> Cut(double limit_s) const {
    std::vector<SortieUnit> units;
    SortieUnit current;
    for (const SnakePiece& piece : pieces_) {
      double at = piece.eastward ? piece.span.lo_m : piece.span.hi_m;
      const double end = piece.eastward ? piece.span.hi_m : piece.span.lo_m;
      while (at != end) {
        if (!current.blocks.empty() && !Linkable(current, piece, at, limit_s)) {
          Close(current, units);
        }
        const double reach = Reach(current, piece, at, end, limit_s);
        if (reach == at) {
          if (current.blocks.empty()) return {};
          Close(current, units);
          continue;
        }
        current = With(current, piece, at, reach);
        at = reach;
        if (at != end) Close(current, units);
      }
    }
    if (!current.blocks.empty()) Close(current, units);
    return units;
  }

  // The unit's sortie from the nearest site.
  double TimeS(const SortieUnit& unit) const {
    if (unit.passes.empty()) return 0.0;
    return NearestSiteSortieS(unit, sites_, spec_, distance_m_);
  }

 private:
  SortieUnit With(const SortieUnit& unit, const SnakePiece& piece, double from, double to) const {
    SortieUnit out = unit;
    out.blocks.push_back({piece.first_row, piece.end_row, std::min(from, to), std::max(from, to)});
    Orient(field_, out, NearestSite(Centre(out.blocks.front()), sites_), spec_);
    return out;
  }

  Point Centre(const Block& b) const {
    const double y = (field_.rows[b.first_row].y_m + field_.rows[b.end_row - 1].y_m) / 2.0;
    return field_.frame.ToLocal(Point{(b.x_lo_m + b.x_hi_m) / 2.0, y});
  }

  // The farthest point towards `end` the unit may take of the piece within the limit.
  double Reach(const SortieUnit& unit, const SnakePiece& piece, double at, double end,
               double limit_s) const {
    if (TimeS(With(unit, piece, at, end)) <= limit_s) return end;
    double ok = at, bad = end;
    for (int step = 0; step < kCutBisectionSteps && std::abs(bad - ok) > kCutResolutionM; ++step) {
      const double mid = (ok + bad) / 2.0;
      (TimeS(With(unit, piece, at, mid)) <= limit_s ? ok : bad) = mid;
    }
    return ok;
  }

  // A unit goes on into the next piece when the hop there is short.
  bool Linkable(const SortieUnit& unit, const SnakePiece& piece, double at, double limit_s) const {
    const double y = field_.rows[piece.first_row].y_m;
    const Point start = field_.frame.ToLocal(Point{at, y});
    return bg::distance(unit.exit, start) / spec_.speed_mps <= kMaxLinkShare * limit_s;
  }

  void Close(SortieUnit& unit, std::vector<SortieUnit>& units) const {
    if (!unit.passes.empty()) units.push_back(std::move(unit));
    unit = SortieUnit{};
  }

  const LaneField& field_;
  const std::vector<SnakePiece>& pieces_;
  const std::vector<Point>& sites_;
  const SortieSpec& spec_;
  const TransitFn& distance_m_;
};

}  // namespace

std::vector<SortieUnit> CutSortieUnits(const LaneField& field, std::size_t rows_per_stripe,
                                       std::size_t units_wanted, const std::vector<Point>& sites,
                                       const SortieSpec& spec, const TransitFn& distance_m,
                                       double gap_m) {
  const std::vector<SnakePiece> pieces = SnakeOrder(field, rows_per_stripe, gap_m);
  const SnakeCutter cutter(field, pieces, sites, spec, distance_m);
  std::vector<SortieUnit> best = cutter.Cut(spec.endurance_s);
  if (best.empty() || best.size() >= units_wanted) return best;
  // The shortest sortie limit that still needs no more than units_wanted units.
  // No unit of the cut at the endurance takes longer than its longest one.
  double low_s = 0.0, high_s = 0.0;
  for (const SortieUnit& unit : best) high_s = std::max(high_s, cutter.TimeS(unit));
  for (int step = 0; step < kLimitBisectionSteps; ++step) {
    const double mid_s = (low_s + high_s) / 2.0;
    std::vector<SortieUnit> units = cutter.Cut(mid_s);
    if (!units.empty() && units.size() <= units_wanted) {
      high_s = mid_s;
      best = std::move(units);
    } else {
      low_s = mid_s;
    }
  }
  return best;
}

namespace {

// Lane length of the rows' spans between the block's x_lo and x.
double LaneLengthTo(const LaneField& field, const Block& rows, double x) {
  double total_m = 0.0;
  for (std::size_t r = rows.first_row; r < rows.end_row; ++r) {
    for (const Span& s : field.rows[r].spans) {
      total_m += std::max(0.0, std::min(s.hi_m, x) - std::max(s.lo_m, rows.x_lo_m));
    }
  }
  return total_m;
}

constexpr std::size_t kMaxBlocksPerPiece = 4096;

}  // namespace

std::vector<SortieUnit> CutSortieUnitsByWork(const LaneField& field, std::size_t rows_per_stripe,
                                             double target_work_s, const std::vector<Point>& sites,
                                             const SortieSpec& spec, const TransitFn& distance_m,
                                             double gap_m) {
  std::vector<SortieUnit> blocks;  // one block each, in snake order
  for (const SnakePiece& piece : SnakeOrder(field, rows_per_stripe, gap_m)) {
    const Block whole{piece.first_row, piece.end_row, piece.span.lo_m, piece.span.hi_m};
    const double lane_m = LaneLengthTo(field, whole, piece.span.hi_m);
    if (lane_m <= 0.0) continue;
    auto unit_of = [&](double x_lo, double x_hi) {
      SortieUnit unit;
      unit.blocks = {Block{piece.first_row, piece.end_row, x_lo, x_hi}};
      const double y = field.rows[piece.first_row].y_m;
      Orient(field, unit, NearestSite(field.frame.ToLocal(Point{(x_lo + x_hi) / 2.0, y}), sites),
             spec);
      return unit;
    };
    const SortieUnit probe = unit_of(piece.span.lo_m, piece.span.hi_m);
    auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(probe.work_s / target_work_s)));
    std::vector<SortieUnit> cut;
    for (; n <= kMaxBlocksPerPiece; n += std::max<std::size_t>(1, n / 8)) {
      cut.clear();
      double x_lo = piece.span.lo_m;
      bool fits = true;
      for (std::size_t m = 1; m <= n && fits; ++m) {
        double x_hi = piece.span.hi_m;
        if (m < n) {  // equal lane length per block
          const double want_m = lane_m * static_cast<double>(m) / static_cast<double>(n);
          double a = x_lo, b = piece.span.hi_m;
          for (int step = 0; step < kCutBisectionSteps; ++step) {
            const double mid = (a + b) / 2.0;
            (LaneLengthTo(field, whole, mid) < want_m ? a : b) = mid;
          }
          x_hi = b;
        }
        SortieUnit unit = unit_of(x_lo, x_hi);
        if (!unit.passes.empty()) {
          fits = NearestSiteSortieS(unit, sites, spec, distance_m) <= spec.endurance_s;
          cut.push_back(std::move(unit));
        }
        x_lo = x_hi;
      }
      if (fits) break;
    }
    if (n > kMaxBlocksPerPiece) return {};
    if (!piece.eastward) std::reverse(cut.begin(), cut.end());
    for (SortieUnit& unit : cut) blocks.push_back(std::move(unit));
  }
  // Blocks with less than half the target chained with their neighbours.
  std::vector<SortieUnit> units;
  for (SortieUnit& block : blocks) {
    if (!units.empty()) {
      SortieUnit& last = units.back();
      const bool small = block.work_s < target_work_s / 2.0 || last.work_s < target_work_s / 2.0;
      const double link_s = bg::distance(last.exit, block.entry) / spec.speed_mps;
      if (small && last.work_s + last.link_s + block.work_s + link_s <= target_work_s &&
          link_s <= kMaxLinkShare * spec.endurance_s) {
        SortieUnit chained = last;
        chained.blocks.push_back(block.blocks.front());
        Orient(field, chained, NearestSite(chained.entry, sites), spec);
        if (NearestSiteSortieS(chained, sites, spec, distance_m) <= spec.endurance_s) {
          last = std::move(chained);
          continue;
        }
      }
    }
    units.push_back(std::move(block));
  }
  return units;
}

}  // namespace fireswarm::planner
