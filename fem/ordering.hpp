#pragma once
/// Fill-reducing ordering of a sparse SPD matrix whose unknowns have 2D positions: geometric
/// nested dissection (recursive coordinate bisection; cf. A. George, "Nested dissection of a
/// regular finite element mesh", SIAM J. Numer. Anal. 10 (1973); Gilbert, Miller & Teng,
/// "Geometric mesh partitioning", SIAM J. Sci. Comput. 19 (1998)).
///
/// Why: at 10⁶ unknowns (uniform mesh, this 2-core machine) CHOLMOD's METIS ordering costs
/// ≈ 7 s for 1.4e10 factorisation flops, AMD ≈ 0.6 s for 3.3e10 flops; this ordering costs
/// ≈ 0.4 s for 1.9e10 flops (a P1 mesh is planar: a straight cut gives an O(√n) separator).
///
/// Each set of unknowns is cut at a coordinate m along one direction: lower = {c < m},
/// middle = {c = m}, upper = {c > m}. The cut (CutChoice::SmallestSeparator, the default) is
/// the one of x, y, x + y, x − y, each at the median or at the 0.4 or 0.6 quantile (an
/// off-centre cut's separator counted 1.1 times; the first cut always at a median), with the
/// smallest separator in the matrix graph (16.7 → 14.2 GFlop on the uniform 10⁶ grid): on an adapted mesh, whose vertices are dense and stretched along a layer or a
/// front, the geometrically longer axis often cuts across the layer, through every one of its
/// thin rows, and the factorisation then depends on the grading (tanh layer, 9.5·10⁴
/// unknowns: see docs/benchmarks.md, "Solver ordering"). Separators within 2 % of the
/// smallest count as equal, and of those the cut goes across the piece's longest extent along
/// its direction, so that the pieces stay compact (19.2 → 16.7 GFlop on the uniform 10⁶ grid,
/// the adapted meshes unchanged). CutChoice::LongerAxis is the older
/// rule (the longer bounding-box axis), kept for comparison. The separator is the middle plus a
/// minimum vertex cover of the edges between lower and upper (König's theorem, from a maximum
/// matching), never more than the smaller of (upper vertices adjacent to lower) and (lower
/// vertices adjacent to upper), which the choice of the cut counts; on a structured grid, and
/// on a jittered one, it is one grid line (the cover: uniform 10⁵ grid 0.370 → 0.354 GFlop,
/// 10⁶ 14.2 → 13.9, the wave front's mesh 0.970 → 0.946). Both sides are ordered recursively, then the
/// separator (by id). Sets of ≤ `leafSize` unknowns are ordered by approximate minimum degree
/// (SuiteSparse AMD), which beats dissection on small pieces. Deterministic: no ties decide.
#include "ablmg/core/vec2.hpp"

#include <Eigen/Sparse>

#include <vector>

namespace ablmg::fem {

enum class CutChoice {
  SmallestSeparator,  ///< of x, y, x ± y: the cut with the fewest separator vertices (default)
  LongerAxis          ///< across the longer side of the piece's bounding box
};

/// The first cut of the dissection: perm = [lower side (`lower` unknowns), upper side
/// (`upper`), separator (the rest)], and no edge of A joins the two sides. Both 0 when the
/// whole set was one leaf (n ≤ leafSize, or every point on the cut line).
struct TopCut {
  int lower = 0;
  int upper = 0;
};

/// `A`: n × n with a symmetric pattern (both halves stored, compressed); `points`: n
/// positions. Returns `perm` with perm[k] = the unknown placed k-th (a permutation of 0..n−1);
/// `top` (optional) receives the first cut (fem/split_cholesky.hpp factorises its sides apart).
std::vector<int> geometricNestedDissection(const Eigen::SparseMatrix<double>& A, const std::vector<Vec2>& points,
                                           int leafSize = 500, CutChoice cut = CutChoice::SmallestSeparator,
                                           TopCut* top = nullptr);

/// METIS' multilevel nested dissection (METIS_NodeND, default options) of A's graph (the
/// diagonal ignored), for comparison: it needs no coordinates, but costs ≈ 10× our geometric
/// ordering on this machine (docs/benchmarks.md, "Solver ordering"). Same contract as above.
std::vector<int> metisNestedDissection(const Eigen::SparseMatrix<double>& A);

}  // namespace ablmg::fem
