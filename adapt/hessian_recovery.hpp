#pragma once
/// Recovery of the Hessian of a P1 (piecewise linear, nodal) field at the mesh vertices.
///
/// Input: a valid Mesh2 and one value per vertex (u.size() == mesh.numVertices()).
/// Output: one symmetric 2×2 matrix per vertex, H ≈ [u_xx u_xy; u_xy u_yy] (units of u over
/// coordinate units squared). Both methods reproduce the Hessian of a quadratic u exactly (up
/// to round-off) at every vertex, boundary included, on any mesh (tests/adapt/test_hessian_recovery).
///
/// Methods:
///  - LeastSquares: at each vertex v, the quadratic a0 + a1 dx + a2 dy + a3 dx² + a4 dx dy + a5 dy²
///    (dx = x − x_v, scaled by the patch radius) fitted to u on a vertex patch in the least-squares
///    sense; H = [2a3 a4; a4 2a5]. The patch is the 1-ring for interior vertices and grows ring by
///    ring (2-ring at least for boundary vertices, whose 1-ring is one-sided) until it has ≥ 9
///    points and the fit is well-posed (QR with column pivoting: |R_55| / |R_00| ≥ 1e-6). A
///    patch failing that test only for being thin (aspect ratio ≳ 10³, as across a boundary
///    layer) is refitted in its principal frame, each axis scaled by its extent, before it is
///    grown: the same least-squares quadratic, well-conditioned (growing such a patch instead
///    takes hundreds of rings across a layer: 13 s of recovery on a 32k-vertex tanh layer).
///  - DoubleRecovery: first the gradient at each vertex, from the same patch fit (polynomial
///    preserving recovery, Zhang & Naga, SIAM J. Sci. Comput. 26 (2005)), then the gradient of
///    each gradient component by the lumped L2 projection (area-weighted average of the P1
///    element gradients of the recovered field), symmetrised. Why not the area-weighted gradient
///    twice (the classic "double L2" recovery): it is exact for quadratics only on symmetric
///    patches, and exactness is wanted on unstructured meshes; the second pass only
///    needs exactness for linear fields, which the L2 projection has on any patch, boundary
///    vertices included. It is smoother than LeastSquares (one more averaging) on noisy data.
///
/// Subdomains: on a mesh with several triangle refs (Mesh2::triangleRefs) each subdomain is
/// recovered on its own (its patches never cross an interface, where a P1 solution with a
/// discontinuous κ has a kink), and a vertex shared by several subdomains gets the
/// intersection of their |H| (as metrics: the larger curvature along every direction).
/// Exactness for a quadratic then holds inside each subdomain, and |H| at the interfaces.
/// A subdomain too thin to determine a quadratic on its own (e.g. one row of triangles, all
/// its vertices on its two sides) takes the whole mesh's recovery at its vertices.
///
/// Deterministic; parallel over vertices (OpenMP), bitwise identical for any thread count.
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/vec2.hpp"
#include <Eigen/Core>
#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace ablmg::adapt {

using Hessian2 = Eigen::Matrix2d;  ///< symmetric

enum class HessianMethod { LeastSquares, DoubleRecovery };

/// "lsq" / "double" ↔ HessianMethod; parse throws InputError naming the valid names.
HessianMethod parseHessianMethod(const std::string& name);
std::string toString(HessianMethod m);

/// Per-vertex Hessians (see above). Throws InputError if u.size() != mesh.numVertices() or a
/// value is not finite (names the vertex).
std::vector<Hessian2> recoverHessians(const Mesh2& mesh, std::span<const double> u, HessianMethod method);

/// The Hessians of two fields on one mesh, {of u, of z}, each the same as recoverHessians gives
/// it; with LeastSquares on one subdomain the patches and their QR factorisations are shared
/// (a solution and its dual on one mesh: half the recovery's work).
std::array<std::vector<Hessian2>, 2> recoverHessians(const Mesh2& mesh, std::span<const double> u,
                                                     std::span<const double> z, HessianMethod method);

/// Per-vertex gradients from the patch quadratic fit (exact for quadratics at every vertex).
std::vector<Vec2> recoverGradients(const Mesh2& mesh, std::span<const double> u);

/// Lumped L2 projection of the P1 element gradients of u: at vertex v, Σ_T∋v |T| ∇u_h|_T / Σ |T|.
/// Exact for linear u on any mesh (first order otherwise).
std::vector<Vec2> areaWeightedGradients(const Mesh2& mesh, std::span<const double> u);

namespace detail {
/// Vertex-to-vertex adjacency in CSR form (sorted neighbour ids), shared by the methods.
struct VertexGraph {
  std::vector<int> offsets, ids;
  std::vector<char> onBoundary;
};
VertexGraph vertexGraph(const Mesh2& mesh);
/// Coefficients (a0..a5) of the patch fit at vertex v, in unscaled coordinates dx = x − x_v.
Eigen::Matrix<double, 6, 1> patchQuadraticFit(const Mesh2& mesh, const VertexGraph& g, std::span<const double> u, int v,
                                              std::vector<int>& patch, std::vector<int>& mark);
/// The same for several fields on one patch (the patch and its QR depend on the mesh only):
/// out[k] for fields[k], each as patchQuadraticFit gives it.
void patchQuadraticFits(const Mesh2& mesh, const VertexGraph& g, std::span<const std::span<const double>> fields, int v,
                        std::vector<int>& patch, std::vector<int>& mark, std::span<Eigen::Matrix<double, 6, 1>> out);
void checkField(const Mesh2& mesh, std::span<const double> u, const char* where);
/// fit(v, patch, mark) for v in [0, n), in parallel above a size (per-thread scratch `patch`,
/// `mark` of n zeros); an exception of any call is rethrown (the first in vertex order).
void forEachVertex(int n, const std::function<void(int, std::vector<int>&, std::vector<int>&)>& fit);
/// recoverHessians without the subdomain split.
std::vector<Hessian2> recoverHessiansOneDomain(const Mesh2& mesh, std::span<const double> u, HessianMethod method);
/// True when the mesh has one triangle ref per triangle and at least two distinct ones.
bool hasSeveralSubdomains(const Mesh2& mesh);
/// recoverHessians per subdomain (see above).
std::vector<Hessian2> recoverPerSubdomain(const Mesh2& mesh, std::span<const double> u, HessianMethod method);
/// Intersection of |a| and |b| as SPD forms: vᵀ|C|v ≥ max(vᵀ|a|v, vᵀ|b|v) along the common
/// axes, equality there; |a| when b = 0 (and |b| when a = 0).
Hessian2 combineSubdomainHessians(const Hessian2& a, const Hessian2& b);
}  // namespace detail

}  // namespace ablmg::adapt
