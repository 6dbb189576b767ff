#pragma once
/// Solution transfer: P1 fields on an old mesh → P1 fields on a new mesh of the same domain,
/// any number of fields at once (the state of a time integrator: u^n, u^(n−1), ...).
///
/// Interpolation (TransferMethod::Interpolation): each new vertex is located in the old mesh
/// (core/point_locator.hpp: grid start + visibility walk on exact orientation tests) and gets
/// the old field's value there (barycentric). A new vertex outside the old mesh — on a curved
/// boundary, the new boundary polyline cuts the old one's chords — takes the value at the
/// closest point of the old boundary. Exact for linear fields; not conservative.
///
/// Conservative L2 projection (TransferMethod::L2Projection): u_new ∈ P1(new) with
///   ∫ u_new φ_i = ∫ u_old φ_i   for every new hat function φ_i,
/// the right-hand side integrated exactly on the supermesh (every non-empty intersection of
/// an old and a new triangle). Each intersection is a convex polygon (≤ 7 sides), found by
/// clipping the old triangle against the new one's three edge lines (Sutherland–Hodgman).
/// Which side of a line a point is on is decided by core::orient2d (a floating-point filter,
/// exact arithmetic only when the filter cannot decide); the sides of an old vertex against
/// the new triangle's lines are computed once and shared by the old triangles around it, so an
/// old triangle with its corners all outside one line is rejected, and one with its corners
/// inside a line is not clipped by it, without a test. On each piece u_old is affine, and
/// ∫ u_old, ∫ u_old x, ∫ u_old y follow exactly from the polygon's moments ∫1, ∫x, ∫x xᵀ
/// (Green's theorem on its edges; coordinates relative to a vertex of the new triangle); φ_i
/// being affine on the whole new triangle, ∫ u_old φ_i follows from their sums over its
/// pieces. The old triangles meeting a new triangle T are found by an advancing front
/// (P. E. Farrell, J. R. Maddison, "Conservative interpolation between volume meshes by local
/// Galerkin projection", CMAME 200 (2011)): start at the old triangle containing T's centroid
/// (a walk from the previous new triangle's start; at the start of each block of 256 new
/// triangles, or when that walk fails, a walk from a coarse grid of the old triangles, and the
/// PointLocator, built only then, when this one fails too), then visit the old neighbours across every old
/// edge a piece runs along. Cost linear in the mesh sizes (a few old triangles per new one).
///
/// The mass system M x = b (M the new consistent P1 mass matrix, applied triangle by
/// triangle without being assembled) is solved by conjugate gradients with the Jacobi
/// preconditioner, to ‖r‖ ≤ 1e−15 ‖b‖ (or stagnation), in one parallel region: the vectors
/// are cut into 64 fixed blocks whatever the thread count, M x is gathered per vertex over its
/// triangles (in triangle order), and each dot product is the sum of its blocks' partial sums
/// in block order. Why not a Cholesky factorisation: the Jacobi-scaled P1 mass matrix
/// has its spectrum in [1/2, 2] on any triangle mesh, however anisotropic (A. J. Wathen,
/// "Realistic eigenvalue bounds for the Galerkin mass matrix", IMA J. Numer. Anal. 7 (1987)),
/// so CG converges by a factor ≈ 1/3 per iteration: ≈ 25 triangle sweeps per field, cheaper
/// than one factorisation at 10⁵ vertices.
/// Properties (where old and new meshes cover the same polygon): Σ b_i = ∫ u_old (the hats
/// sum to 1), so ∫ u_new = 1ᵀ M x = ∫ u_old up to the solver's residual (≈ 1e−15 relative);
/// a linear u_old lies in P1(new) and is reproduced.
///
/// Bound preservation (TransferOptions::boundPreserving, projection only): the projection may
/// overshoot; the values are clipped to [min, max] of the old field and the mass the clip
/// changed (Σ m_i δ_i, m_i = ∫ φ_i) is given back to the vertices with room left, in
/// proportion to m_i × their room: the result lies in [min, max] and keeps ∫ u.
///
/// Deterministic: every new triangle's contributions are computed alone (OpenMP over blocks
/// of 256 new triangles; a block's first triangle is located from the grid, the next ones
/// walk from their predecessor's start, so no hint crosses a block) and summed in triangle
/// order, and the mass solve's sums are over fixed blocks in a fixed order, so the bits do not
/// depend on the thread count.
#include "ablmg/core/mesh2.hpp"

#include <Eigen/Core>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace ablmg::adapt {

enum class TransferMethod { Interpolation, L2Projection };

/// "interpolation" / "projection" ↔ TransferMethod; parse throws InputError naming the valid names.
TransferMethod parseTransferMethod(const std::string& name);
std::string toString(TransferMethod method);

struct TransferOptions {
  TransferMethod method = TransferMethod::L2Projection;
  bool boundPreserving = false;  ///< projection only: clip to the old field's [min, max], mass kept
};

struct TransferStats {
  long supermeshPieces = 0;        ///< non-empty old ∩ new intersections (projection)
  double supermeshArea = 0;        ///< Σ of their areas (= the domain's area when both cover it)
  long outsideVertices = 0;        ///< new vertices outside the old mesh (interpolation)
  int solverIterations = 0;        ///< CG iterations, largest over the fields (projection)
  std::vector<double> massOld;     ///< ∫ u_old per field, on the old mesh
  std::vector<double> massNew;     ///< ∫ u_new per field, on the new mesh
  std::vector<double> absMassOld;  ///< Σ_i |u_old,i| ∫ φ_i per field (≈ ∫ |u_old|): the scale of the defect
  double seconds = 0;              ///< wall time of the whole transfer
  /// Largest |∫u_new − ∫u_old| / absMassOld over the fields: the relative mass defect.
  double maxRelativeMassDefect() const;
};

/// Transfers every field (one value per old vertex each) to the new mesh. Both meshes valid.
/// Throws InputError if a field's size is not the old mesh's vertex count (naming the field)
/// or a value is not finite.
std::vector<Eigen::VectorXd> transferFields(const Mesh2& oldMesh, const Mesh2& newMesh,
                                            std::span<const Eigen::VectorXd> fields,
                                            const TransferOptions& options = {}, TransferStats* stats = nullptr);

/// ∫ u over the mesh, u one value per vertex (P1): Σ_i u_i ∫ φ_i.
double integrate(const Mesh2& mesh, const Eigen::VectorXd& u);

/// The supermesh, piece by piece: calls visit(oldTriangle, newTriangle, polygon) for every
/// non-empty intersection (polygon convex, counter-clockwise, ≥ 3 vertices), new triangles
/// in increasing order, serially. For tests and pictures; the projection uses the same code.
void forEachSupermeshPiece(const Mesh2& oldMesh, const Mesh2& newMesh,
                           const std::function<void(int, int, std::span<const Vec2>)>& visit);

/// Intersection of two counter-clockwise triangles as a convex counter-clockwise polygon
/// (empty if they meet in a set of zero area). In/out decisions by orient2d.
std::vector<Vec2> clipTriangles(const std::array<Vec2, 3>& subject, const std::array<Vec2, 3>& clip);

}  // namespace ablmg::adapt
