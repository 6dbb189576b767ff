#pragma once
/// Quality of a mesh with respect to the metric it was built for (paper §4.2 and §6).
///
/// Edges: metric length l = sqrt(eᵀ M_avg e), M_avg = (M_a + M_b)/2 (eq. 3; dimensionless, the
/// target is l0 = 1) and deviation ε = |l − l0| / l0 (eq. 13), binned as in the paper's Table 1.
/// Triangles (2D): q = 4√3 A_M / (l1² + l2² + l3²) (Borouchaki, George et al. 1997) with
/// M = (M_a + M_b + M_c)/3, A_M = |T| √det M and l_k the side lengths in M; q ∈ (0, 1] for a
/// counter-clockwise triangle, 1 exactly for the equilateral triangle of M (any size).
/// An inverted triangle gets q ≤ 0 (counted in the lowest bin).
/// Triangles (3D surfaces): Lee's α, eqs. (19)–(20), from surface.hpp's leeQuality().
/// The element distribution has the 5 bins of the paper's Table 2.
///
/// With the identity metric (Metric2() / isotropicMetric3(1)) every length is Euclidean.
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"
#include "ablmg/mesher/surface.hpp"

#include <array>
#include <span>
#include <string>
#include <vector>

namespace ablmg::mesher {

/// Metric length of each edge of mesh.edges() (same order), eq. (3) with the averaged tensor.
/// metrics.size() == mesh.numVertices() (else InputError).
std::vector<double> edgeMetricLengths(const Mesh2& mesh, std::span<const Metric2> metrics);

/// q of the triangle a, b, c (counter-clockwise) in the constant metric m. See above.
double triangleQuality(const Vec2& a, const Vec2& b, const Vec2& c, const Metric2& m);
/// q of every triangle of the mesh, with the vertex-averaged metric. metrics.size() == numVertices().
std::vector<double> elementQualities(const Mesh2& mesh, std::span<const Metric2> metrics);
/// Lee's α of every triangle of a planar mesh, eqs. (19)–(20): the smallest over the three
/// vertices of the triangle's q in that vertex's own metric (q with M_i, Det read as √det M_i,
/// the area scale of M_i). α ≤ 1; α = q for a constant metric; sensitive to metric variation
/// across the triangle, which q (averaged metric) smooths. metrics.size() == numVertices().
std::vector<double> leeAlphas(const Mesh2& mesh, std::span<const Metric2> metrics);

/// Share of the triangles' sides (an interior edge counted from each of its two triangles) whose
/// lengths in their two end metrics, sqrt(eᵀ M_a e) and sqrt(eᵀ M_b e), differ by more than the
/// factor `ratio` (> 1). Where it is large the metric changes by more than its own size within
/// one element, and no mesh gives it unit edges there (eq. 3 averages what differs). Meshes of
/// smooth or graded metrics: ≤ 0.1 % at ratio 2 (docs/limitations.md, "Fast-varying metrics").
/// 0 for a mesh without triangles; metrics.size() == numVertices().
double metricJumpShare(const Mesh2& mesh, std::span<const Metric2> metrics, double ratio = 2.0);

struct EdgeLengthStats {
  long count = 0;
  double min = 0, mean = 0, max = 0;  ///< of l (all 0 when count == 0)
  double inSqrt2 = 0;                 ///< fraction with l ∈ [1/√2, √2]
  double within10 = 0;                ///< fraction with |l − 1| ≤ 0.1
  double e = 0.05;                    ///< bin width of the deviation histogram (paper: e = 5%)
  /// Fractions of edges with ε ≤ e, e < ε ≤ 2e, …, 4e < ε ≤ 5e, ε > 5e (Table 1 plus the
  /// tail). Sum to 1 when count > 0.
  std::array<double, 6> deviation{};
};
/// Statistics of metric lengths l (target 1), with deviation bins of width e > 0.
EdgeLengthStats edgeLengthStats(std::span<const double> lengths, double e = 0.05);

struct ElementQualityStats {
  long count = 0;
  double min = 0, mean = 0, max = 0;  ///< (all 0 when count == 0)
  /// Fractions with q in [0, 0.2), [0.2, 0.4), [0.4, 0.6), [0.6, 0.8), [0.8, 1] (Table 2); q < 0
  /// counts in the first bin, q > 1 (round-off) in the last. Sum to 1 when count > 0.
  std::array<double, 5> bins{};
};
ElementQualityStats elementQualityStats(std::span<const double> q);

/// Everything `ablmg stats` reports.
struct MeshQuality {
  int dimension = 2;  ///< 2: planar Mesh2; 3: surface (element measure = Lee's α)
  long vertices = 0, triangles = 0, edges = 0;
  bool valid = true;         ///< Mesh2::validate() (2D) / checkManifold() (3D)
  std::string firstProblem;  ///< empty when valid
  EdgeLengthStats edgeLengths;
  ElementQualityStats elements;
  ElementQualityStats leeAlpha;  ///< 2D: leeAlphas(); 3D: the same as elements (α is the measure there)
};

/// 2D: lengths, q and validity in the per-vertex metrics (metrics.size() == numVertices()).
MeshQuality meshQuality(const Mesh2& mesh, std::span<const Metric2> metrics, double e = 0.05);
/// 3D surface: metric lengths sqrt(eᵀ M_avg e) and Lee's α under m3; validity = checkManifold().
MeshQuality surfaceQuality(const SurfaceMesh& mesh, const Metric3Field& m3, double e = 0.05);

/// (The JSON form is cli::qualityJson, cli/stats_json.hpp: this target links no JSON library.)
/// A short human-readable table (several lines, each ending in '\n').
std::string toText(const MeshQuality& q);

}  // namespace ablmg::mesher
