#include "morton_order.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace needlekit::fem::detail {
namespace {

// The 21 bits of v spread to every third bit (the Morton code's interleaving). Written here: a few shifts and masks,
// where a library would add a dependency for one function.
uint64_t spread_bits(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

}  // namespace

std::vector<int> morton_order(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& low,
                              const Eigen::Vector3d& high) {
  constexpr double kCells = (1 << 21) - 1;
  const Eigen::Vector3d scale = kCells / (high - low).cwiseMax(1e-300).array();
  std::vector<uint64_t> code(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d cell = ((points[i] - low).array() * scale.array()).round().max(0.0).min(kCells);
    code[i] = spread_bits(static_cast<uint64_t>(cell.x())) | spread_bits(static_cast<uint64_t>(cell.y())) << 1 |
              spread_bits(static_cast<uint64_t>(cell.z())) << 2;
  }
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return code[a] < code[b]; });
  return order;
}

}  // namespace needlekit::fem::detail
