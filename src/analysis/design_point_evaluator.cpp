#include "needlekit/analysis/design_point_evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "needlekit/analysis/bending.hpp"
#include "needlekit/analysis/skin_permeation.hpp"
#include "needlekit/needle/section_properties.hpp"

namespace needlekit::analysis {

using needle::Shape;

DesignPointEvaluator::DesignPointEvaluator(const DesignSpace& space, const BucklingOptions& buckling,
                                           double buckling_safety_factor)
    : space_(space), buckling_(buckling), safety_factor_(buckling_safety_factor) {
  materials::validate(space.material, "material");
  validate(space.conditions.tissue, "tissue");
  n_ = grid_values(space.needles_per_row, "needles_per_row");
  d1_ = grid_values(space.tip_diameter, "tip_diameter");
  d2_ = space.shape == Shape::Cylinder ? std::vector<double>{0.0} : grid_values(space.base_diameter, "base_diameter");
  d3_ = space.hollow ? grid_values(space.bore_diameter, "bore_diameter") : std::vector<double>{0.0};
  w_ = grid_values(space.width, "width");
  l_ = grid_values(space.length, "length");

  const std::size_t pairs = d1_.size() * d2_.size();
  deformation_.resize(pairs);
  force_.resize(pairs);
  for (std::size_t i1 = 0; i1 < d1_.size(); ++i1) {
    for (std::size_t i2 = 0; i2 < d2_.size(); ++i2) {
      needle::NeedleGeometry g = geometry(i1, i2, 0, 0);
      const double area = needle::tip_area(g);
      deformation_[i1 * d2_.size() + i2] = skin_deformation(area, space.conditions.tissue).depth;
      force_[i1 * d2_.size() + i2] = angled_buckling_force(puncture_force(area, space.conditions.tissue), 0.0);
    }
  }
  const std::size_t triples = pairs * d3_.size();
  m_cache_ = std::make_unique<std::atomic<double>[]>(triples);
  for (std::size_t i = 0; i < triples; ++i) m_cache_[i].store(std::numeric_limits<double>::quiet_NaN());
}

std::size_t DesignPointEvaluator::d2_count() const { return d2_.size(); }

needle::NeedleGeometry DesignPointEvaluator::geometry(std::size_t i1, std::size_t i2, std::size_t i3,
                                                      std::size_t il) const {
  needle::NeedleGeometry g;
  g.shape = space_.shape;
  g.tip_diameter = d1_[i1];
  g.base_diameter = space_.shape == Shape::Cylinder ? d1_[i1] : d2_[i2];
  g.bore_diameter = d3_[i3];
  g.length = l_[il];
  return g;
}

double DesignPointEvaluator::deformation(std::size_t i1, std::size_t i2) const {
  return deformation_[i1 * d2_.size() + i2];
}
double DesignPointEvaluator::buckling_force(std::size_t i1, std::size_t i2) const {
  return force_[i1 * d2_.size() + i2];
}

double DesignPointEvaluator::tapered_factor(std::size_t i1, std::size_t i2, std::size_t i3) const {
  std::atomic<double>& slot = m_cache_[(i1 * d2_.size() + i2) * d3_.size() + i3];
  double m = slot.load(std::memory_order_relaxed);
  if (std::isnan(m)) {  // two threads may both compute it; they store the same value
    m = tapered_column_factor(geometry(i1, i2, i3, 0));
    slot.store(m, std::memory_order_relaxed);
  }
  return m;
}

bool DesignPointEvaluator::needle_buckles(std::size_t i1, std::size_t i2, std::size_t i3, double length) const {
  const double demand = safety_factor_ * force_[i1 * d2_.size() + i2];
  needle::NeedleGeometry g = geometry(i1, i2, i3, 0);
  g.length = length;
  if (space_.shape == Shape::Cylinder || buckling_.end_condition != EndCondition::FixedFree) {
    return !(demand < critical_buckling_load(g, space_.material, buckling_).critical_load);
  }
  // Tapered column, fixed-free: P = m·E·I2/L² with π²/4·I_tip/I2 <= m <= π²/4 (the column is bracketed by uniform
  // columns of its weakest and strongest sections; Sturm comparison), so most points need no eigenvalue.
  const double e = space_.material.youngs_modulus;
  const double i2_base = needle::section_at(g, length).second_moment_min;
  const double scale = e * i2_base / (length * length);
  const double m_max = M_PI * M_PI / 4;
  if (demand >= m_max * scale) return true;
  const double i_tip = needle::section_at(g, 0.0).second_moment_min;
  if (demand < m_max * (i_tip / i2_base) * scale) return false;
  return !(demand < tapered_factor(i1, i2, i3) * scale);
}

double DesignPointEvaluator::embedded(const needle::NeedleGeometry& g, double h) const {
  return embedded_volume(g, h);
}

double DesignPointEvaluator::g_of(const needle::NeedleGeometry& g, double d) const {
  const double h = g.length - d;
  const double big_h = ideal_permeation_depth(g.hollow(), g.length, d, space_.conditions.target_depth);
  if (big_h <= 0 || h <= 0) return 0;
  return permeation_factor(g, h) / big_h;  // Q/H
}

DesignPointEvaluator::NeedleOutcome DesignPointEvaluator::needle_outcome(std::size_t i1, std::size_t i2,
                                                                         std::size_t i3, std::size_t il) const {
  const needle::NeedleGeometry g = geometry(i1, i2, i3, il);
  // §4.8 constraints with the strict D1 < D2 for cones and bevels (notes).
  if (space_.shape != Shape::Cylinder && !(g.tip_diameter < g.base_diameter)) return {PointStatus::InvalidGeometry, 0};
  if (g.hollow() && !(g.bore_diameter < g.tip_diameter && g.bore_diameter < g.base_diameter)) {
    return {PointStatus::InvalidGeometry, 0};
  }
  if (space_.shape == Shape::Cylinder &&
      (g.base_diameter < space_.base_diameter.min * (1 - 1e-12) ||
       g.base_diameter > space_.base_diameter.max * (1 + 1e-12))) {
    return {PointStatus::InvalidGeometry, 0};  // a cylinder's D = D1 must also lie in the D2 range
  }
  const double d = deformation(i1, i2);
  if (g.length < d + space_.conditions.target_depth) return {PointStatus::TooShort, 0};
  if (needle_buckles(i1, i2, i3, g.length)) return {PointStatus::Buckles, 0};
  return {PointStatus::Feasible, g_of(g, d)};
}

std::size_t DesignPointEvaluator::smallest_spacing_width(std::size_t in, double base_diameter) const {
  const double needed = space_.spacing_factor * n_[in] * base_diameter * (1 - 1e-12);
  return static_cast<std::size_t>(std::lower_bound(w_.begin(), w_.end(), needed) - w_.begin());
}

}  // namespace needlekit::analysis
