#include "partition.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <limits>
#include <numeric>

namespace fireswarm::planner {
namespace bg = boost::geometry;

std::size_t Route::SegmentAt(double t_s) const {
  if (points.size() < 2) return 0;
  const auto it = std::upper_bound(time_s.begin(), time_s.end(), t_s);
  const auto index = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - time_s.begin() - 1, 0));
  return std::min(index, points.size() - 2);
}

Point Route::At(double t_s) const {
  if (points.empty()) return {};
  if (points.size() == 1 || t_s <= 0.0) return points.front();
  if (t_s >= TotalS()) return points.back();
  const std::size_t i = SegmentAt(t_s);
  const double flight_s = time_s[i + 1] - time_s[i] - turn_s[i];
  const double flown_s = t_s - time_s[i] - turn_s[i];
  if (flown_s <= 0.0 || flight_s <= 0.0) return points[i];
  const double f = std::min(1.0, flown_s / flight_s);
  return {points[i].x() + f * (points[i + 1].x() - points[i].x()),
          points[i].y() + f * (points[i + 1].y() - points[i].y())};
}

Path Route::Slice(double t0_s, double t1_s) const {
  Path path{At(t0_s)};
  if (points.size() >= 2) {
    for (std::size_t i = SegmentAt(t0_s) + 1; i < points.size() && time_s[i] < t1_s; ++i) {
      if (bg::distance(points[i], path.back()) > 0.0) path.push_back(points[i]);
    }
  }
  const Point last = At(t1_s);
  if (bg::distance(last, path.back()) > 0.0 || path.size() == 1) path.push_back(last);
  return path;
}

void Route::Extend(Point to, int lane, double turn) {
  if (points.empty()) {
    points.push_back(to);
    time_s.push_back(0.0);
    pending_turn_s_ = 0.0;
    return;
  }
  const double length_m = bg::distance(points.back(), to);
  if (length_m <= 0.0) {
    pending_turn_s_ += turn;
    return;
  }
  const double segment_turn_s = pending_turn_s_ + turn;
  pending_turn_s_ = 0.0;
  time_s.push_back(time_s.back() + segment_turn_s + length_m / speed_mps);
  turn_s.push_back(segment_turn_s);
  segment_lane.push_back(lane);
  points.push_back(to);
}

namespace {

constexpr int kBisectionSteps = 60;

// Route time of the route vertex nearest `p`.
double NearestTimeS(const Route& route, Point p) {
  double best_m = std::numeric_limits<double>::infinity(), best_s = 0.0;
  for (std::size_t i = 0; i < route.points.size(); ++i) {
    const double d = bg::distance(route.points[i], p);
    if (d < best_m) {
      best_m = d;
      best_s = route.time_s[i];
    }
  }
  return best_s;
}

class Splitter {
 public:
  Splitter(const Route& route, const std::vector<Point>& launches,
           const std::vector<std::size_t>& order, const DistanceFn& distance_m,
           const std::vector<double>& extra_s)
      : route_(route),
        launches_(launches),
        order_(order),
        distance_m_(distance_m),
        extra_s_(extra_s) {}

  // Drone's time for the share [begin, end].
  double TimeS(std::size_t drone, double begin_s, double end_s) const {
    const Point launch = launches_[drone];
    return (distance_m_(launch, route_.At(begin_s)) + distance_m_(route_.At(end_s), launch)) /
               route_.speed_mps +
           (end_s - begin_s) + (extra_s_.empty() ? 0.0 : extra_s_[drone]);
  }

  // Greedy shares whose time stays <= limit; true when they cover the route.
  bool Fill(double limit_s, std::vector<Share>& shares) const {
    const double total_s = route_.TotalS();
    double begin_s = 0.0;
    for (const std::size_t drone : order_) {
      Share& share = shares[drone];
      share.begin_s = share.end_s = begin_s;
      if (begin_s >= total_s) continue;
      if (TimeS(drone, begin_s, begin_s) > limit_s) return false;
      share.end_s = Reach(drone, begin_s, limit_s);
      begin_s = share.end_s;
    }
    return begin_s >= total_s;
  }

 private:
  // The farthest end such that the time stays <= limit all the way there.
  double Reach(std::size_t drone, double begin_s, double limit_s) const {
    double ok_s = begin_s;
    for (std::size_t i = route_.SegmentAt(begin_s) + 1; i < route_.points.size(); ++i) {
      const double t = route_.time_s[i];
      if (t <= ok_s) continue;
      if (TimeS(drone, begin_s, t) > limit_s) {
        double bad_s = t;
        for (int step = 0; step < kBisectionSteps && bad_s - ok_s > 1e-6; ++step) {
          const double mid_s = (ok_s + bad_s) / 2;
          (TimeS(drone, begin_s, mid_s) <= limit_s ? ok_s : bad_s) = mid_s;
        }
        return ok_s;
      }
      ok_s = t;
    }
    return route_.TotalS();
  }

  const Route& route_;
  const std::vector<Point>& launches_;
  const std::vector<std::size_t>& order_;
  const DistanceFn& distance_m_;
  const std::vector<double>& extra_s_;
};

}  // namespace

std::vector<Share> PartitionRoute(const Route& route, const std::vector<Point>& launches,
                                  const DistanceFn& distance_m,
                                  const std::vector<double>& extra_s) {
  const std::size_t n = launches.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<double> key(n);
  for (std::size_t i = 0; i < n; ++i) key[i] = NearestTimeS(route, launches[i]);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return key[a] < key[b]; });

  const Splitter splitter(route, launches, order, distance_m, extra_s);
  std::vector<Share> shares(n);
  double low_s = route.TotalS() / static_cast<double>(n);
  double high_s = route.TotalS();
  for (std::size_t i = 0; i < n; ++i) {
    high_s = std::max(high_s, splitter.TimeS(i, 0.0, route.TotalS()));
  }
  for (int step = 0; step < kBisectionSteps && high_s - low_s > 1e-7 * high_s; ++step) {
    const double mid_s = (low_s + high_s) / 2;
    (splitter.Fill(mid_s, shares) ? high_s : low_s) = mid_s;
  }
  splitter.Fill(high_s, shares);
  for (std::size_t i = 0; i < n; ++i) {
    Share& share = shares[i];
    share.time_s =
        share.end_s > share.begin_s ? splitter.TimeS(i, share.begin_s, share.end_s) : 0.0;
  }
  return shares;
}

namespace {

struct StripBox {
  std::size_t cell = 0;
  double y_lo = 0, y_hi = 0, x_lo = 0, x_hi = 0;
  bool whole = false;  // spans the whole lane
};

std::vector<StripBox> ShareStrips(const Route& route, const Share& share) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kEndToleranceM = 1e-6;
  std::vector<StripBox> strips;
  if (share.end_s <= share.begin_s || route.points.size() < 2) return strips;
  for (std::size_t i = route.SegmentAt(share.begin_s); i + 1 < route.points.size(); ++i) {
    if (route.time_s[i] >= share.end_s) break;
    if (route.segment_lane[i] < 0) continue;
    const double t0 = std::max(share.begin_s, route.time_s[i]);
    const double t1 = std::min(share.end_s, route.time_s[i + 1]);
    if (t1 <= t0) continue;
    const RouteLane& lane = route.lanes[static_cast<std::size_t>(route.segment_lane[i])];
    const LaneFrame& frame = route.cells[lane.cell].frame;
    const double xa = frame.ToLane(route.At(t0)).x();
    const double xb = frame.ToLane(route.At(t1)).x();
    StripBox strip{lane.cell,        lane.lane.band_lo_m, lane.lane.band_hi_m,
                   std::min(xa, xb), std::max(xa, xb),    false};
    // A lane's own ends stand for the cell's edge: its strip reaches the boundary.
    if (strip.x_lo <= lane.lane.x_min_m + kEndToleranceM) strip.x_lo = -kInf;
    if (strip.x_hi >= lane.lane.x_max_m - kEndToleranceM) strip.x_hi = kInf;
    strip.whole = std::isinf(strip.x_lo) && std::isinf(strip.x_hi);
    StripBox* last = strips.empty() ? nullptr : &strips.back();
    if (last != nullptr && last->whole && strip.whole && last->cell == strip.cell) {
      last->y_lo = std::min(last->y_lo, strip.y_lo);
      last->y_hi = std::max(last->y_hi, strip.y_hi);
    } else {
      strips.push_back(strip);
    }
  }
  return strips;
}

}  // namespace

MultiPolygon ShareRegion(const Route& route, const Share& share) {
  MultiPolygon region;
  for (const StripBox& strip : ShareStrips(route, share)) {
    const SweptCell& swept = route.cells[strip.cell];
    // Decomposition cells may come out with Boost's non-default winding (their
    // lanes do not care), which makes the intersection below empty: corrected here.
    Polygon cell = swept.cell;
    bg::correct(cell);
    Box envelope;
    bg::envelope(cell, envelope);
    // A box edge lying on the cell's bottom or top edge (the first and last lanes'
    // bands end there) is a collinear overlap Boost.Geometry's intersection can
    // get wrong (it returned nothing for a whole strip): such edges reach past it.
    constexpr double kEdgeToleranceM = 1e-6;
    const double y_lo = strip.y_lo <= envelope.min_corner().y() + kEdgeToleranceM
                            ? envelope.min_corner().y() - 1.0
                            : strip.y_lo;
    const double y_hi = strip.y_hi >= envelope.max_corner().y() - kEdgeToleranceM
                            ? envelope.max_corner().y() + 1.0
                            : strip.y_hi;
    const Box box{{std::max(strip.x_lo, envelope.min_corner().x() - 1.0), y_lo},
                  {std::min(strip.x_hi, envelope.max_corner().x() + 1.0), y_hi}};
    MultiPolygon piece;
    bg::intersection(cell, box, piece);
    MultiPolygon local;
    for (const Polygon& polygon : piece) local.push_back(swept.frame.ToLocal(polygon));
    // Strips do not overlap, so the union keeps both areas; when it does not (a
    // decomposition cell that touches itself at a point made Boost.Geometry's
    // union drop a whole strip) the pieces are kept side by side instead.
    constexpr double kAreaTolerance = 1e-6;
    MultiPolygon merged;
    bg::union_(region, local, merged);
    const double expected_m2 = AreaM2(region) + AreaM2(local);
    if (AreaM2(merged) >= expected_m2 * (1.0 - kAreaTolerance)) {
      region = std::move(merged);
    } else {
      region.insert(region.end(), local.begin(), local.end());
    }
  }
  return region;
}

}  // namespace fireswarm::planner
