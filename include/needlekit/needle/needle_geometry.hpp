// The geometry of one microneedle (dissertation §4.3–4.5, Fig 4.9): a cylinder, a cone (frustum) or a bevel, solid
// or hollow. All lengths in metres.
//
// Coordinates used throughout needlekit for a needle: the axis is z, the base (fixed to the patch) is at z = 0 and
// the tip at z = L. "Distance from the tip" s = L − z.
//
// Bevel (Fig 4.7, 4.8): a cylinder of diameter D2 cut by a plane through the base edge. At distance s from the tip
// the plane removes the part x > x_cut(s) = r − c + c·s/L of the circle of radius r = D2/2, with c = D2 − D1, so
// the tip face is the circular segment of sagitta (height) D1 and the base is the full circle.
#pragma once
#include <string>
#include <string_view>

#include "needlekit/core/enum_table.hpp"

namespace needlekit::needle {

enum class Shape { Cylinder, Cone, Bevel };
inline constexpr EnumTable<Shape, 3> kShapeNames{{
    {Shape::Cylinder, "cylinder", "constant diameter (D1 = D2), flat tip"},
    {Shape::Cone, "cone", "frustum from the base diameter D2 to the tip diameter D1 < D2"},
    {Shape::Bevel, "bevel", "cylinder of diameter D2 cut by a plane through the base edge; D1 is the tip face's sagitta"},
}};

std::string_view to_string(Shape shape);
// Parses a name of kShapeNames; throws InvalidInput naming `what` otherwise.
Shape shape_from_string(std::string_view text, std::string_view what = "shape");

struct NeedleGeometry {
  Shape shape = Shape::Cylinder;
  double tip_diameter = 0;   // m, D1 > 0. Bevel: the sagitta of the tip's circular segment. Cylinder: D1 == D2.
  double base_diameter = 0;  // m, D2 >= D1.
  double bore_diameter = 0;  // m, D3 in [0, D1): 0 means a solid needle.
  double length = 0;         // m, L > 0.

  bool hollow() const { return bore_diameter > 0; }
};

// Throws InvalidInput naming the offending field (prefixed by `where`, e.g. "needle") if the geometry is not a
// valid needle: sizes not finite or not positive, D1 > D2, a cylinder with D1 != D2, a bore not smaller than the tip
// and the base.
void validate(const NeedleGeometry& needle, std::string_view where = "needle");

// Interfacial (tip) area A (§4.2, notes): π/4·D1² for cylinders and cones; for a bevel the circular segment of
// sagitta D1 cut from the D2 circle. The full tip face: the bore is not subtracted (notes, "Tip area").
double tip_area(const NeedleGeometry& needle);

// Outer diameter at distance s from the tip (cone: linear D1 → D2; cylinder and bevel: D2, the bevel's circle).
double outer_diameter_at(const NeedleGeometry& needle, double distance_from_tip);

// Volume of needle material (the bore removed), m³.
double volume(const NeedleGeometry& needle);

}  // namespace needlekit::needle
