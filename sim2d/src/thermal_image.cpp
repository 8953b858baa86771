#include "fireswarm/sim2d/thermal_image.hpp"

#include <cassert>

namespace fireswarm::sim2d {

void MapWhiteHot(std::span<const float> temperatures_c, double min_c, double max_c,
                 std::span<std::uint8_t> out) {
  assert(max_c > min_c && out.size() == temperatures_c.size());
  const auto scale = static_cast<float>(255.0 / (max_c - min_c));
  const auto offset = static_cast<float>(min_c);
  for (std::size_t i = 0; i < temperatures_c.size(); ++i) {
    out[i] = WhiteHotGrey(temperatures_c[i], offset, scale);
  }
}

}  // namespace fireswarm::sim2d
