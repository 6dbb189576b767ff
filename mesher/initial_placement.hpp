#pragma once
/// Initial bubble placement (paper §3.1) and the domain geometry the bubbles move in.
///
/// DomainGeometry: the loops of a Domain as arc-length parametrised polylines, a bucket grid
/// of their segments, an O(1)-expected inside test (cell-centre status from one scanline per
/// grid row + crossings inside the cell) and metric distance to the boundary.
///
/// Placement:
///  1. Vertex nodes at the corners (Domain::corners), fixed.
///  2. Segment nodes: each boundary piece between consecutive corners (the whole loop if it
///     has none) is cut into n = round(metric length) pieces of equal metric length (metric
///     integrated along the polyline, sub-sampled to ≤ 1/4 metric unit); n ≥ 1 (≥ 3 for a
///     corner-less loop). Not the paper's literal halving, which leaves pieces near 0.9.
///  3. Interior nodes: a metric-hexagonal lattice grown breadth-first from a seed: each new
///     node p proposes the six points p + M_p^{-1/2} (cos kπ/3, sin kπ/3), accepted when
///     inside, at metric distance ≥ `minNodeDistance` from every node and ≥ `minWallDistance`
///     from every boundary segment (measured in M_p). For a constant metric this is exactly the
///     affine image M^{-1/2}·(unit hexagonal lattice); for graded metrics the lattice bends
///     coherently (M^{-1/2} is the symmetric root, continuous in M), with seams only where
///     fronts meet. Unreached pockets are seeded again from a coarse probe grid.
///     With an orientation other than Axes the six directions are first turned in metric
///     space so that one row runs along the node's long or short eigenvector: the step is
///     M_p^{-1/2} Q(φ_p) d (latticeMap in the .cpp), still exact for a constant metric.
///     Large problems (≥ 1.6·10⁵ expected nodes, no warm start, a constant or background
///     field) grow in horizontal bands, ~4·10⁴ nodes each: the even bands in parallel, then
///     the odd ones, each from its neighbours' nodes near it. A band's nodes depend on its own
///     inputs only (the same lattice on any thread count), and its seeds are snapped to the
///     lattice of the box centre's metric, so under a constant metric the bands' fronts meet
///     without seams. A metric whose spacing box is taller than a quarter band grows in one
///     piece.
#include "ablmg/core/bucket_grid.hpp"
#include "ablmg/core/domain.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/mesher/node_set.hpp"

#include <span>
#include <string>
#include <vector>

namespace ablmg::mesher {

struct LoopPolyline {
  std::vector<Vec2> points;  ///< the loop's points (closed: segment k = points[k] → points[k+1 mod n])
  std::vector<double> cum;   ///< cum[k] = Euclidean arc length at points[k]; cum[n] = length
  std::vector<int> tags;     ///< one per segment
  std::vector<int> corners;  ///< corner point indices (Domain::corners)
  std::vector<char> kept;    ///< per segment: BoundaryLoop::keptSegments (empty = none)
  double length = 0;
};

class DomainGeometry {
 public:
  explicit DomainGeometry(const Domain& domain);
  const std::vector<LoopPolyline>& loops() const { return loops_; }
  std::pair<Vec2, Vec2> boundingBox() const { return {lo_, hi_}; }

  /// Strictly-inside test (points on the boundary may go either way). Expected O(1).
  bool inside(const Vec2& p) const;
  /// min over boundary segments within Euclidean distance `searchRadius` of p of the metric
  /// (m) distance from p to the segment; +inf if none is that close.
  double metricDistanceToBoundary(const Vec2& p, const Metric2& m, double searchRadius) const;
  /// min over boundary segments meeting the box p ± halfWidths of the metric (m) distance from
  /// p to the segment; +inf if none. With halfWidths = reachBox(m, r) (adjacency.hpp) the
  /// result is exact whenever it is < r, and the box of a thin ellipse (anisotropy 10⁴) is
  /// ~10⁴× smaller than the disk of its long half-axis.
  double metricDistanceToBoundary(const Vec2& p, const Metric2& m, const Vec2& halfWidths) const;
  /// Side of the cells of the boundary segments' bucket grid (≈ 1/2 of the mean segment
  /// length, at least bounding box / 2000): a search radius of a few cells visits a few dozen
  /// cells.
  double segmentCellSize() const { return grid_.cellSize(); }

  /// Arc length s ∈ [0, L) of loop l (wrapped) → segment index, point, unit tangent.
  int segmentAt(int l, double s) const;
  Vec2 pointAt(int l, double s) const;
  Vec2 tangentAt(int l, double s) const;
  double wrap(int l, double s) const;
  /// Arc length → "point index + fraction" (NodeSet::arc convention).
  double indexArc(int l, double s) const;

 private:
  /// Squared metric distance (eq. 3, constant m) from p to global segment `id`, ≥ 0: the
  /// boundary distances take one square root of the smallest (√ is monotone: the same value).
  double squaredMetricDistanceToSegment(int id, const Vec2& p, const Metric2& m) const;
  std::vector<LoopPolyline> loops_;
  std::vector<std::pair<int, int>> segs_;  ///< (loop, k) per global segment id
  BucketGrid grid_;
  std::vector<char> centreInside_;
  Vec2 lo_, hi_;
};

/// Boundary nodes of §3.1 (steps 1–2), loop by loop in arc order. `arcLength` receives each
/// node's Euclidean arc length along its loop (the NodeSet gets the index+fraction form).
void placeBoundaryNodes(const DomainGeometry& geo, const MetricField& metric, NodeSet& nodes,
                        std::vector<double>& arcLength);

/// How the interior lattice is turned in metric space (see placeInteriorNodes).
enum class LatticeOrientation {
  Axes,       ///< p + M^{-1/2} d: rows along the images of the x axis (symmetric root)
  LongAxis,   ///< one row along each node's long-size eigenvector e1
  ShortAxis,  ///< one row along each node's short-size eigenvector e2
  /// Axes where h1/h2 ≤ kAutoAlignFrom, ShortAxis where h1/h2 ≥ kAutoAlignRatio, blended
  /// between (the default of `mesh` and `remesh`). On a layer (h1/h2 = 10²–10⁴) the axes'
  /// rows cross the layer's thin rows at an angle and the population control spends tens of
  /// passes repairing the seams (docs/method.md §1); on mild anisotropy the axes are as good
  /// or better, and there the lattice is the axes' one, node for node.
  Auto,
};
inline constexpr double kAutoAlignFrom = 8;
inline constexpr double kAutoAlignRatio = 16;

/// "axes" | "long" | "short" | "auto" (InputError otherwise).
LatticeOrientation parseLatticeOrientation(const std::string& name);
const char* latticeOrientationName(LatticeOrientation orientation);

struct InteriorPlacementOptions {
  double minNodeDistance = 0.75;  ///< metric; lattice candidates closer to a node are dropped
  double minWallDistance = 0.55;  ///< metric; ≈ √3/2 − spacing tolerance for a boundary row
  LatticeOrientation orientation = LatticeOrientation::Auto;
  /// LongAxis/ShortAxis: full alignment from this anisotropy ratio h1/h2 on, blended towards
  /// Axes below it (the eigenframe of a near-isotropic metric is noise).
  double alignRatio = 1.5;
};

/// Interior nodes of §3.1 (step 3), appended to `nodes` (which holds the boundary nodes).
/// `spacingHint` = expected typical node spacing (coordinate units), sizes the bucket grid.
/// `seeds` (warm start, e.g. the previous mesh's vertices): taken first, in order, where they
/// pass the same tests as lattice points; the lattice then grows from them into the gaps.
void placeInteriorNodes(const DomainGeometry& geo, const MetricField& metric, NodeSet& nodes, double spacingHint,
                        const InteriorPlacementOptions& options = {}, std::span<const Vec2> seeds = {});

/// ∫Ω √det M dA (the domain's area in metric space) by midpoint quadrature on a g×g grid
/// over the bounding box (exact area × √det M for a constant field). OpenMP (inside tests,
/// and MetricField::sqrtDeterminants, which a background field runs in parallel); the same
/// value for any thread count.
double metricArea(const Domain& domain, const DomainGeometry& geo, const MetricField& metric, int g = 256);

/// N* = (2/√3) A_M + Nb/2 + 1 − holes: a triangulation with Nb boundary nodes and T unit
/// equilateral (in the metric) triangles has T·√3/4 = A_M and, by Euler, T = 2N − Nb − 2 + 2·holes.
long predictedNodeCount(double metricAreaValue, long boundaryNodes, int holes);

}  // namespace ablmg::mesher
