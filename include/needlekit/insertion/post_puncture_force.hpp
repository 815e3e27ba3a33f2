// Post-puncture insertion force (dissertation §3.6.2, Eqs 3.18-3.20, Algorithm 3.1, Figs 3.8-3.10): the force on a
// needle moving through tissue that it has already punctured, as a distributed load on the triangles that face the
// insertion direction (insertion/triangle_classification.hpp), counting only the part of the needle inside the tissue.
//
// Loads (SI: K in N/m² = Pa, "stiffness of the tissue per unit length of the needle"; S dimensionless):
//   α-triangles: uniform pressure K·S; resultant F_U = K·S·Σ A_i                                       (Eq 3.18)
//   β-triangles: triangular load by Algorithm 3.1, its resultant the volume of the load solid over the triangle,
//                summed over triangles                                                     (Eqs 3.19-3.20)
//
// needlekit's reading of Figure 3.10 (a, b and θ are not defined in words; docs/post-puncture.md):
//   - The "center axis" O1O2 is the axis of the puncture channel: the line along d through the centre of the
//     needle's tip (the foremost vertices). For axisymmetric needles it is the needle axis; for a bevel it runs
//     through the bevel's tip, where the tissue was cut.
//   - The reference plane contains the axis and the triangle's centroid CG_i; Q_k is P_k projected onto it, with
//     in-plane coordinates a(Q) = axial distance behind the tip plane and x(Q) = distance from the axis (toward
//     CG_i).
//   - Q1 is the vertex nearest the tip (smallest a); θ_Qk is the angle between the axis and Q1Qk (k = 2, 3): the
//     slope of the needle's meridian; θ̄ = (θ_Q2 + θ_Q3)/2 at Q1.
//   - a = a(Q_k) − a(Q1), the axial distance of Q_k behind Q1; b = x(Q1) − x_open ≥ 0, the distance of Q1 from the
//     opening line: the line parallel to the axis through the edge of the tip face in that plane (x_open = the
//     largest x of the tip vertices; 0 for a sharp tip on the axis).
//   - Then δ(Q1) = b/cos θ̄ and δ(Q_k) = a·tanθ_Qk + b/cosθ_Qk (Algorithm 3.1 with K·S factored out) is how far the
//     tissue, opened by the tip to the opening line, has been pushed perpendicular to the needle surface at Q: b/cosθ
//     is Q1's distance from the opening line measured along the surface normal, a·tanθ the radial widening from Q1
//     to Q_k. δ = 0 on the tip (Fig 3.9: vertices on the tip carry no load) and grows linearly along a slope
//     (Fig 3.8's triangular load). As the mesh is refined δ → (x − x_open)/cosθ (first order in the triangles'
//     axial size: the printed a·tanθ lacks the 1/cosθ of the continuum).
//   - Dimensions: as printed, the β resultant is K·S·(length³) while the α resultant is K·S·(length²). needlekit
//     makes the β load a pressure by dividing by a reference radius R (the needle's largest distance from the
//     channel axis, unless set): p_β = K·S·δ/R, capped at the cutting pressure K·S (a face that has pushed the tissue
//     a full radius aside presses as hard as the tip face). The resultant over a triangle is then the volume of the
//     load prism, A·(p1 + p2 + p3)/3 (Eqs 3.19-3.20: three tetrahedra).
//   - Eq 3.20 sums the load volumes, not their components along d; `axial_component` projects each triangle's load on
//     d instead.
#pragma once
#include <Eigen/Core>
#include <array>
#include <limits>
#include <string_view>
#include <vector>

#include "needlekit/geometry/triangle_mesh.hpp"
#include "needlekit/insertion/force_curve.hpp"
#include "needlekit/insertion/triangle_classification.hpp"

namespace needlekit::insertion {

struct PostPunctureOptions {
  // The channel axis: a point on it, m. Default (NaN): the centroid of the tip vertices (the vertices within
  // tip_tolerance of the foremost point along d).
  Eigen::Vector3d axis_point = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  // Relative to the needle's extent along d, [0, 1e-2]: vertices this close to the foremost point (along d) are "on
  // the needle's tip" and carry no β load (Algorithm 3.1). Default 1e-6.
  double tip_tolerance = 1e-6;
  // m, >= 0: R of p_β = K·S·δ/R. 0 (default): the largest distance of a needle vertex from the channel axis.
  double reference_radius = 0;
  // Cap p_β at the cutting pressure K·S (δ/R <= 1). Default true.
  bool cap_at_cutting_pressure = true;
  // false (default, Eq 3.20): sum the load volumes; true: sum their components along d (times n·d).
  bool axial_component = false;
  // Relative to the needle's extent along d, [0, 1]: loaded triangles with an edge longer than this are bisected at
  // their longest edge (recursively) before Algorithm 3.1, whose vertex loads are first-order accurate in the
  // triangle size. 0: use the mesh as it is. Default 0.025 (25 um on a 1 mm needle; a bevel face is otherwise a fan
  // of slivers spanning its whole length).
  double max_edge_fraction = 0.025;
};

// The β load of one triangle by Algorithm 3.1, Fig 3.9's case (A: one vertex on the tip, B: two, C: none) and the
// loads at its vertices.
enum class BetaCase { OneVertexOnTip, TwoVerticesOnTip, NoVertexOnTip };

// One loaded triangle, ready for any insertion depth: its vertices' axial distances behind the tip and the pressure
// factors p/(K·S) at them (1 on α-triangles).
struct LoadedTriangle {
  int triangle = -1;                             // the mesh triangle it is (or is a part of)
  bool alpha = false;
  BetaCase beta_case = BetaCase::NoVertexOnTip;  // β only
  std::array<double, 3> depth{};                 // m, a(P_k): axial distance of each vertex behind the tip plane
  std::array<double, 3> load{};                  // p(P_k)/(K·S), dimensionless, in [0, 1] when capped
  double area = 0;                               // m²
  double weight = 1;                             // n·d when axial_component, else 1
};

// The geometry of the post-puncture load, independent of K, S and the depth: compute once, evaluate at many depths.
struct PostPunctureLoads {
  TriangleClassification classification;
  std::vector<LoadedTriangle> triangles;  // α first, then β
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  // m, the channel axis used
  double reference_radius = 0;            // m, R used
  double needle_length = 0;               // m, extent of the needle along d
  double alpha_area = 0;                  // m², Σ A of α-triangles
  int case_counts[3] = {0, 0, 0};         // β-triangles per BetaCase
  // Sorted tables for fast evaluation at many depths (built by post_puncture_loads).
  std::vector<int> by_first_depth;        // triangle indices sorted by their smallest vertex depth
  std::vector<double> last_depth_sorted;  // largest vertex depth of each triangle, ascending
  std::vector<double> full_prefix;        // Σ of full loads of the triangles in last_depth_sorted order (size + 1)
};

// Classifies the mesh (options of `classification`) and computes every loaded triangle. Throws InvalidInput for an
// invalid mesh (see classify_triangles) or options.
PostPunctureLoads post_puncture_loads(const geometry::TriangleMesh& needle,
                                      const TriangleClassificationOptions& classification = {},
                                      const PostPunctureOptions& options = {},
                                      const geometry::SurfaceMesh* surface = nullptr);

// The load factor Σ ∫ p/(K·S) dA over the part of the needle within `inserted_depth` of the tip (m², >= 0): the
// post-puncture force is K·S times it. Exact for the piecewise-linear load (each triangle clipped at the tissue
// surface a = inserted_depth).
double post_puncture_load_area(const PostPunctureLoads& loads, double inserted_depth);

// The post-puncture force (N) at one inserted depth: K·S·post_puncture_load_area.
double post_puncture_force(const PostPunctureLoads& loads, double inserted_depth, double stiffness, double scale);

// The force at many depths (any order; each >= 0), N. O(n log n + Σ active triangles).
std::vector<double> post_puncture_forces(const PostPunctureLoads& loads, const std::vector<double>& inserted_depths,
                                         double stiffness, double scale);

// The prism volume of Eqs 3.19-3.20 for a triangle p1 p2 p3 with load heights h1 h2 h3 along its normal, summed from
// three tetrahedra by Eq 3.19 (used to check the closed form A·(h1 + h2 + h3)/3).
double load_prism_volume(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, const Eigen::Vector3d& p3, double h1,
                         double h2, double h3);

// Least-squares fit of the post-puncture model to a measured curve (depth = inserted depth of the tip, m; force, N).
// The model is linear in the product K·S, so only K·S is determined: with `fit_stiffness` false (default) S is fitted
// for the given K; with it true K is fitted for the given S.
struct PostPunctureFitOptions {
  double stiffness = 0.2e6;   // N/m², > 0: K (fixed when fitting S)
  double scale = 0.168;       // > 0: S (fixed when fitting K)
  bool fit_stiffness = false;
};
struct PostPunctureFit {
  double stiffness = 0;       // N/m², K
  double scale = 0;           // S
  double rms_error = 0;       // N, root mean square of the residuals
  double relative_rms = 0;    // rms_error / rms of the measured force
  int samples = 0;
};
// Throws InvalidInput when the curve is empty, depths are not strictly increasing, negative or not finite, or the
// model load is zero at every measured depth.
PostPunctureFit fit_post_puncture(const PostPunctureLoads& loads, const ForceDepthCurve& measured,
                                  const PostPunctureFitOptions& options = {});

// Throws InvalidInput naming `what` if the curve's depths are not finite and strictly increasing or the sizes differ.
void validate_force_curve(const ForceDepthCurve& curve, std::string_view what);

}  // namespace needlekit::insertion
