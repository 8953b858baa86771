#include "temperature_polygon.hpp"

#include <array>
#include <cassert>
#include <cmath>
#include <utility>

namespace fireswarm::sim2d {
namespace {

// A convex polygon in a fixed buffer: no allocation per pixel.
template <std::size_t kCapacity>
struct FixedPolygon {
  std::array<Vec2, kCapacity> v;
  std::size_t n = 0;
};
// A 32-gon clipped by 4 edges gains at most 4 vertices.
using Polygon = FixedPolygon<40>;
// A quad cut by at most 4 axis lines has at most 8 vertices (a few more when a
// vertex lies exactly on a line and is repeated).
using CellPiece = FixedPolygon<16>;

// Positive when p lies left of the directed edge a -> b.
double Side(const Vec2& a, const Vec2& b, const Vec2& p) {
  return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

void ClipByEdge(const Polygon& in, const Vec2& a, const Vec2& b, Polygon& out) {
  out.n = 0;
  // prev walks one behind cur, starting from the last vertex (no modulo per vertex).
  for (std::size_t i = 0, j = in.n - 1; i < in.n; j = i++) {
    const Vec2& cur = in.v[i];
    const Vec2& prev = in.v[j];
    const double s_cur = Side(a, b, cur);
    const double s_prev = Side(a, b, prev);
    if ((s_cur >= 0.0) != (s_prev >= 0.0)) {
      const double t = s_prev / (s_prev - s_cur);
      out.v[out.n++] = prev + t * (cur - prev);
    }
    if (s_cur >= 0.0) out.v[out.n++] = cur;
  }
}

// Keeps the part of `in` with coordinate `axis` above (or below) `bound`.
template <int kAxis, bool kKeepAbove>
void ClipByAxis(const Polygon& in, double bound, Polygon& out) {
  out.n = 0;
  // prev walks one behind cur, starting from the last vertex (no modulo per vertex).
  for (std::size_t i = 0, j = in.n - 1; i < in.n; j = i++) {
    const Vec2& cur = in.v[i];
    const Vec2& prev = in.v[j];
    const bool in_cur = kKeepAbove ? cur[kAxis] >= bound : cur[kAxis] <= bound;
    const bool in_prev = kKeepAbove ? prev[kAxis] >= bound : prev[kAxis] <= bound;
    if (in_cur != in_prev) {
      const double t = (bound - prev[kAxis]) / (cur[kAxis] - prev[kAxis]);
      out.v[out.n++] = prev + t * (cur - prev);
    }
    if (in_cur) out.v[out.n++] = cur;
  }
}

// Splits convex `in` by the line coordinate `kAxis` == bound into the part below
// and the part above it (either may come out empty).
template <int kAxis>
void SplitByAxis(const CellPiece& in, double bound, CellPiece& below, CellPiece& above) {
  below.n = 0;
  above.n = 0;
  // prev walks one behind cur, starting from the last vertex (no modulo per vertex).
  for (std::size_t i = 0, j = in.n - 1; i < in.n; j = i++) {
    const Vec2& cur = in.v[i];
    const Vec2& prev = in.v[j];
    const bool cur_below = cur[kAxis] < bound;
    if (cur_below != (prev[kAxis] < bound)) {
      const double t = (bound - prev[kAxis]) / (cur[kAxis] - prev[kAxis]);
      const Vec2 cut = prev + t * (cur - prev);
      below.v[below.n++] = cut;
      above.v[above.n++] = cut;
    }
    (cur_below ? below.v[below.n++] : above.v[above.n++]) = cur;
  }
  assert(below.n <= below.v.size() && above.n <= above.v.size());
}

template <std::size_t kCapacity>
double Area(const FixedPolygon<kCapacity>& p) {
  return p.n < 3 ? 0.0 : std::abs(SignedAreaM2(std::span<const Vec2>(p.v.data(), p.n)));
}

}  // namespace

double SignedAreaM2(std::span<const Vec2> polygon) {
  double twice = 0.0;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    twice += polygon[j].x() * polygon[i].y() - polygon[i].x() * polygon[j].y();
  }
  return 0.5 * twice;
}

double OverlapAreaM2(std::span<const Vec2> subject, const GroundQuad& ccw_quad) {
  assert(subject.size() <= 32);
  Polygon buffers[2];
  Polygon* in = &buffers[0];
  Polygon* out = &buffers[1];
  for (const Vec2& p : subject) in->v[in->n++] = p;
  for (std::size_t e = 0; e < 4 && in->n > 0; ++e) {
    ClipByEdge(*in, ccw_quad[e], ccw_quad[(e + 1) % 4], *out);
    std::swap(in, out);
  }
  if (in->n < 3) return 0.0;
  return std::abs(SignedAreaM2(std::span<const Vec2>(in->v.data(), in->n)));
}

double QuadBoxOverlapAreaM2(const GroundQuad& quad, const Vec2& lo_m, const Vec2& hi_m) {
  Polygon a, b;
  for (const Vec2& p : quad) a.v[a.n++] = p;
  ClipByAxis<0, true>(a, lo_m.x(), b);
  ClipByAxis<0, false>(b, hi_m.x(), a);
  ClipByAxis<1, true>(a, lo_m.y(), b);
  ClipByAxis<1, false>(b, hi_m.y(), a);
  if (a.n < 3) return 0.0;
  return std::abs(SignedAreaM2(std::span<const Vec2>(a.v.data(), a.n)));
}

int SplitQuadIntoCells(const GroundQuad& quad, const Vec2& origin_m, double cell_m,
                       CellOverlap* out, int max_out) {
  Vec2 lo = quad[0], hi = quad[0];
  for (const Vec2& p : quad) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const auto first = [&](double v, double o) {
    return static_cast<int>(std::floor((v - o) / cell_m));
  };
  const int c0 = first(lo.x(), origin_m.x()), c1 = first(hi.x(), origin_m.x());
  const int r0 = first(lo.y(), origin_m.y()), r1 = first(hi.y(), origin_m.y());
  if (static_cast<long>(c1 - c0 + 1) * (r1 - r0 + 1) > max_out) return -1;
  // Pieces live in fixed buffers and are passed around by pointer (no copies).
  std::array<CellPiece, 6> buffers;
  CellPiece* rest_cols = &buffers[0];
  CellPiece* next_col = &buffers[1];
  CellPiece* column_buffer = &buffers[2];
  CellPiece* row_buffer = &buffers[3];
  for (const Vec2& p : quad) rest_cols->v[rest_cols->n++] = p;
  int written = 0;
  for (int c = c0; c <= c1; ++c) {
    CellPiece* column = rest_cols;
    if (c < c1) {
      SplitByAxis<0>(*rest_cols, origin_m.x() + (c + 1) * cell_m, *column_buffer, *next_col);
      column = column_buffer;
      std::swap(rest_cols, next_col);
    }
    CellPiece* rest_rows = column;
    CellPiece* next_row = &buffers[4];
    for (int r = r0; r <= r1 && rest_rows->n >= 3; ++r) {
      const CellPiece* piece = rest_rows;
      if (r < r1) {
        SplitByAxis<1>(*rest_rows, origin_m.y() + (r + 1) * cell_m, *row_buffer, *next_row);
        piece = row_buffer;
        rest_rows = next_row;
        next_row = next_row == &buffers[4] ? &buffers[5] : &buffers[4];
      }
      const double area = Area(*piece);
      if (area > 0.0) out[written++] = {c, r, area};
    }
  }
  return written;
}

}  // namespace fireswarm::sim2d
