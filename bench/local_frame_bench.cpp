// WGS84 <-> local metres (common::LocalFrame): every simulated GPS fix goes
// through ToGeodetic and every vehicle's estimate through ToLocal, ten times a
// second per drone. Beside them GeographicLib's azimuthal equidistant projection,
// which LocalFrame used before 2026-12-01, for the ratio.
#include <benchmark/benchmark.h>

#include <GeographicLib/AzimuthalEquidistant.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <cstddef>
#include <vector>

#include "fireswarm/common/local_frame.hpp"

namespace {

namespace common = fireswarm::common;

constexpr common::LatLon kOrigin{46.48, -74.66};
// Points spread over a 10 km x 10 km area around the origin.
constexpr std::size_t kPoints = 1024;
constexpr double kSpanM = 10'000.0;

common::EastNorth PointAt(std::size_t i) {
  const auto fraction = [](std::size_t k) {
    return static_cast<double>(k % kPoints) / static_cast<double>(kPoints);
  };
  return {kSpanM * (fraction(i) - 0.5), kSpanM * (0.5 - fraction(i * 37))};
}

void BM_LocalFrameToLocal(benchmark::State& state) {
  const common::LocalFrame frame(kOrigin);
  std::vector<common::LatLon> points;
  for (std::size_t i = 0; i < kPoints; ++i) points.push_back(frame.ToGeodetic(PointAt(i)));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(frame.ToLocal(points[i++ % kPoints]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LocalFrameToLocal);

void BM_LocalFrameToGeodetic(benchmark::State& state) {
  const common::LocalFrame frame(kOrigin);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(frame.ToGeodetic(PointAt(i++ % kPoints)));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LocalFrameToGeodetic);

void BM_AzimuthalEquidistantForward(benchmark::State& state) {
  const common::LocalFrame frame(kOrigin);
  const GeographicLib::AzimuthalEquidistant projection(GeographicLib::Geodesic::WGS84());
  std::vector<common::LatLon> points;
  for (std::size_t i = 0; i < kPoints; ++i) points.push_back(frame.ToGeodetic(PointAt(i)));
  std::size_t i = 0;
  for (auto _ : state) {
    const common::LatLon& p = points[i++ % kPoints];
    double east_m = 0.0, north_m = 0.0, azimuth_deg = 0.0, scale = 0.0;
    projection.Forward(kOrigin.lat_deg, kOrigin.lon_deg, p.lat_deg, p.lon_deg, east_m, north_m,
                       azimuth_deg, scale);
    benchmark::DoNotOptimize(east_m);
    benchmark::DoNotOptimize(north_m);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AzimuthalEquidistantForward);

void BM_AzimuthalEquidistantReverse(benchmark::State& state) {
  const GeographicLib::AzimuthalEquidistant projection(GeographicLib::Geodesic::WGS84());
  std::size_t i = 0;
  for (auto _ : state) {
    const common::EastNorth p = PointAt(i++ % kPoints);
    double lat_deg = 0.0, lon_deg = 0.0, azimuth_deg = 0.0, scale = 0.0;
    projection.Reverse(kOrigin.lat_deg, kOrigin.lon_deg, p.east_m, p.north_m, lat_deg, lon_deg,
                       azimuth_deg, scale);
    benchmark::DoNotOptimize(lat_deg);
    benchmark::DoNotOptimize(lon_deg);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AzimuthalEquidistantReverse);

}  // namespace

BENCHMARK_MAIN();
