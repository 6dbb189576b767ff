#pragma once
/// ABLMG connection (paper §4.1): every node's local mesh from its adjacency list, with the
/// non-satellite nodes removed by the anisotropic swap criterion eq. (12); the global mesh is
/// the union of the local meshes, repaired deterministically where they disagree.
///
///   1. links = adjacency pairs that stay inside the domain (no crossing of a boundary edge,
///      inside the interior angle at boundary nodes; exact predicates);
///   2. local meshes: each node's links sorted counter-clockwise; for consecutive
///      P_{j−1}, P_j, P_{j+1} with P_{j−1}–P_{j+1} linked and crossing P–P_j, eq. (12) with
///      M_avg of the four nodes deletes the losing link from both lists (tie sin(α+β) = 0:
///      the diagonal holding the node of smallest abscissa goes). Rounds over all nodes read
///      the lists of the previous round, so the result does not depend on thread count;
///   3. the union: a triangle (P, S_k, S_{k+1}) of consecutive satellites is kept when it is
///      in the local meshes of all three of its nodes (a "consistent" triangle);
///   If the consistent triangles already form a valid mesh of the polygon through the boundary
///   nodes (Mesh2::validate with that polygon's area: the usual case), they are the mesh, as in
///   the paper. Otherwise:
///   4. repair, always valid by construction: a constrained Delaunay triangulation of the
///      nodes (triangulation.hpp) with the boundary edges, then eq. (12) swaps, then every
///      edge of a consistent triangle recovered by flips and locked, then eq. (12) swaps of
///      the remaining edges. Every consistent triangle is in the output; the others
///      (`repairedTriangles`) fill what the local meshes left open or got wrong.
///
/// Interior nodes outside the polygon through the boundary nodes (possible on curved loops,
/// between a chord and its arc) are left out of the mesh (`droppedNodes`, `nodeOfVertex`).
#include "ablmg/core/domain.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/mesher/place_nodes.hpp"

namespace ablmg::mesher {

struct ConnectOptions {
  int threads = 0;          ///< 0 = OpenMP default; the result does not depend on it
  bool localRepair = true;  ///< try step 4a before the whole-domain scaffold (off: always the scaffold)
};

struct ConnectStats {
  long links = 0;              ///< adjacency pairs kept as candidate edges (inside the domain)
  long intersectionTests = 0;  ///< segment crossing tests (paper §4.3 reports 157317)
  long crossingsFound = 0;
  long deletedEdges = 0;  ///< non-satellite links removed by eq. (12)
  int deletionRounds = 0;
  long consistentTriangles = 0;  ///< triangles present in the local meshes of all three nodes
  long repairedTriangles = 0;    ///< output triangles that are not consistent ABLMG triangles
  long failedRecoveries = 0;     ///< consistent-triangle edges the repair could not keep (overlaps)
  long swaps = 0;                ///< eq. (12) edge swaps done by the repair
  bool swapCapHit = false;       ///< the swap cap (20 per edge) stopped the repair's swaps
  bool localRepair = false;      ///< the repair was local (step 4a), not the whole-domain scaffold
  long droppedNodes = 0;         ///< nodes outside the boundary polygon, not in the mesh
  double secondsLocalMeshes = 0;
  double secondsRepair = 0;  ///< validating the union, and the repair when it was needed
};

struct ConnectResult {
  Mesh2 mesh;                     ///< valid (Mesh2::validate)
  std::vector<int> nodeOfVertex;  ///< mesh vertex → placement node (identity unless droppedNodes > 0)
  ConnectStats stats;
  /// The union of the local meshes passed Mesh2::validate against the domain's area (polygonal
  /// loops) or the boundary polygon's (smooth loops) and is the mesh: meshDomain need not check again.
  bool validated = false;
  double secondsValidate = 0;  ///< time of that check
};

/// Connects the placed nodes. Throws ablmg::Error if the boundary cannot be recovered (a node
/// lying exactly on a boundary edge) and InputError for coincident nodes.
ConnectResult connect(const PlacementResult& placement, const Domain& domain, const ConnectOptions& options = {});

/// eq. (12): should diagonal x–z of the convex quadrilateral x, y, z, w (y and w on either
/// side of x–z) give way to y–w? Evaluated with M_avg = (M_x + M_y + M_z + M_w)/4; a tie
/// (|sin(α+β)| below round-off) deletes the diagonal holding the node of smallest abscissa.
bool swapCriterion(const Vec2& x, const Vec2& z, const Vec2& y, const Vec2& w, const Metric2& mAvg);

}  // namespace ablmg::mesher
