// Uses the installed library: the §6.3.1 cone's performance index (1.288e-4 /um).
#include <needlekit/analysis/performance_index.hpp>

#include <cmath>

int main() {
  needlekit::analysis::ArrayDesign design;
  design.needle = {needlekit::needle::Shape::Cone, 30e-6, 150e-6, 0.0, 500e-6};
  design.material = needlekit::materials::material_preset("silicon");
  const auto result = needlekit::analysis::performance_index(design, {});
  return std::abs(result.performance_index * 1e-6 / 1.288e-4 - 1) < 2e-3 ? 0 : 1;
}
