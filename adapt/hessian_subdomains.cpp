// Hessian recovery on a mesh with several subdomains (hessian_recovery.hpp): each subdomain's
// patches stay inside it, so a field whose gradient jumps across a material interface (the
// P1 solution of a problem with a discontinuous κ) is not fitted by one quadratic across the
// kink, which would read the kink as a huge curvature all along the interface.
#include "ablmg/adapt/hessian_recovery.hpp"

#include "ablmg/core/error.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace ablmg::adapt {
namespace detail {
namespace {

std::uint64_t directedKey(int a, int b) { return std::uint64_t(std::uint32_t(a)) << 32 | std::uint32_t(b); }

/// The triangles of ref `ref` as a mesh of their own (vertices renumbered in increasing
/// order; `global` receives each local vertex's id in `mesh`), its boundary edges the edges of
/// one of its triangles (so that the recovery grows the patches of its boundary vertices).
Mesh2 subdomainMesh(const Mesh2& mesh, int ref, std::vector<int>& global) {
  std::vector<int> local(std::size_t(mesh.numVertices()), -1);
  Mesh2 sub;
  for (int t = 0; t < mesh.numTriangles(); ++t)
    if (mesh.triangleRefs[std::size_t(t)] == ref)
      for (int v : mesh.triangles[std::size_t(t)]) local[std::size_t(v)] = 0;
  global.clear();
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (local[std::size_t(v)] == 0) {
      local[std::size_t(v)] = int(global.size());
      global.push_back(v);
      sub.vertices.push_back(mesh.vertices[std::size_t(v)]);
    }
  std::unordered_set<std::uint64_t> directed;
  for (int t = 0; t < mesh.numTriangles(); ++t)
    if (mesh.triangleRefs[std::size_t(t)] == ref) {
      const auto& tri = mesh.triangles[std::size_t(t)];
      sub.triangles.push_back({local[std::size_t(tri[0])], local[std::size_t(tri[1])], local[std::size_t(tri[2])]});
      for (int k = 0; k < 3; ++k)
        directed.insert(directedKey(sub.triangles.back()[k], sub.triangles.back()[(k + 1) % 3]));
    }
  for (const auto& tri : sub.triangles)
    for (int k = 0; k < 3; ++k)
      if (!directed.count(directedKey(tri[(k + 1) % 3], tri[k])))
        sub.boundaryEdges.push_back({tri[k], tri[(k + 1) % 3], 1});
  return sub;
}

/// |H| = Q |Λ| Qᵀ, its eigenvalues floored at `floor`.
Eigen::Matrix2d absFloored(const Hessian2& h, double floor) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(0.5 * (h + h.transpose()));
  const Eigen::Vector2d l = eig.eigenvalues().cwiseAbs().cwiseMax(floor);
  return eig.eigenvectors() * l.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace

Hessian2 combineSubdomainHessians(const Hessian2& a, const Hessian2& b) {
  const double na = a.norm(), nb = b.norm();
  if (!(na > 0)) return absFloored(b, 0);
  if (!(nb > 0)) return absFloored(a, 0);
  const double floor = 1e-12 * std::max(na, nb);
  const Eigen::Matrix2d A = absFloored(a, floor), B = absFloored(b, floor);
  // Simultaneous reduction: with A = L Lᵀ, C = L⁻¹ B L⁻ᵀ = P D Pᵀ, the intersection is
  // L P max(I, D) Pᵀ Lᵀ (the largest of the two quadratic forms along each common axis).
  const Eigen::LLT<Eigen::Matrix2d> llt(A);
  const Eigen::Matrix2d L = llt.matrixL();
  const Eigen::Matrix2d Li = L.inverse();
  const Eigen::Matrix2d C = Li * B * Li.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(0.5 * (C + C.transpose()));
  const Eigen::Vector2d d = eig.eigenvalues().cwiseMax(1.0);
  const Eigen::Matrix2d LP = L * eig.eigenvectors();
  const Eigen::Matrix2d out = LP * d.asDiagonal() * LP.transpose();
  return 0.5 * (out + out.transpose());
}

bool hasSeveralSubdomains(const Mesh2& mesh) {
  return mesh.triangleRefs.size() == mesh.triangles.size() &&
         std::adjacent_find(mesh.triangleRefs.begin(), mesh.triangleRefs.end(), std::not_equal_to<>()) !=
             mesh.triangleRefs.end();
}

std::vector<Hessian2> recoverPerSubdomain(const Mesh2& mesh, std::span<const double> u, HessianMethod method) {
  std::vector<int> refs = mesh.triangleRefs;
  std::sort(refs.begin(), refs.end());
  refs.erase(std::unique(refs.begin(), refs.end()), refs.end());
  std::vector<Hessian2> out(std::size_t(mesh.numVertices()), Hessian2::Zero());
  std::vector<char> seen(std::size_t(mesh.numVertices()), 0);
  std::vector<int> global;
  std::vector<double> subU;
  std::vector<Hessian2> whole;  // the recovery on the whole mesh, when a subdomain needs it
  for (int ref : refs) {
    const Mesh2 sub = subdomainMesh(mesh, ref, global);
    subU.resize(global.size());
    for (std::size_t k = 0; k < global.size(); ++k) subU[k] = u[std::size_t(global[k])];
    std::vector<Hessian2> h;
    try {
      h = recoverHessiansOneDomain(sub, subU, method);
    } catch (const InputError&) {  // too thin for a quadratic of its own: the whole mesh's fit
      if (whole.empty()) whole = recoverHessiansOneDomain(mesh, u, method);
      h.resize(global.size());
      for (std::size_t k = 0; k < global.size(); ++k) h[k] = whole[std::size_t(global[k])];
    }
    for (std::size_t k = 0; k < global.size(); ++k) {
      const auto v = std::size_t(global[k]);
      out[v] = seen[v] ? combineSubdomainHessians(out[v], h[k]) : h[k];
      seen[v] = 1;
    }
  }
  return out;
}

}  // namespace detail
}  // namespace ablmg::adapt
