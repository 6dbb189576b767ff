#include "ablmg/fem/p1_matrices.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"

#include <algorithm>
#include <cmath>

namespace ablmg::fem {
namespace {

/// The sorted vertex neighbours of v (itself included) into row (insertion sort: a row has
/// about 7 entries).
void sortedRow(const Mesh2& mesh, const Mesh2::VertexTriangles& vt, int v, std::vector<int>& row) {
  row.clear();
  for (int k = vt.offsets[v]; k < vt.offsets[v + 1]; ++k)
    for (int w : mesh.triangles[std::size_t(vt.ids[k])]) {
      std::size_t i = row.size();
      while (i > 0 && row[i - 1] > w) --i;
      if (i > 0 && row[i - 1] == w) continue;
      row.insert(row.begin() + std::ptrdiff_t(i), w);
    }
}

}  // namespace

P1Pattern p1Pattern(const Mesh2& mesh) {
  const int nv = mesh.numVertices();
  const Mesh2::VertexTriangles vt = mesh.vertexTriangles();
  P1Pattern p;
  std::vector<int> outer(std::size_t(nv) + 1, 0);
  ParallelFailure failure;  // the rows allocate: rethrown after each region, the lowest vertex's
#pragma omp parallel
  {
    std::vector<int> row;
#pragma omp for schedule(static)
    for (int v = 0; v < nv; ++v)
      failure.run(v, [&] {
        sortedRow(mesh, vt, v, row);
        outer[std::size_t(v) + 1] = int(row.size());
      });
  }
  failure.rethrow();
  for (int v = 0; v < nv; ++v) outer[std::size_t(v) + 1] += outer[std::size_t(v)];
  std::vector<int> inner(std::size_t(outer.back()));
#pragma omp parallel
  {
    std::vector<int> row;
#pragma omp for schedule(static)
    for (int v = 0; v < nv; ++v)
      failure.run(v, [&] {
        sortedRow(mesh, vt, v, row);
        std::copy(row.begin(), row.end(), inner.begin() + outer[std::size_t(v)]);
      });
  }
  failure.rethrow();
  // The pattern is symmetric, so the rows built above are also the columns (CSC).
  p.matrix = Eigen::SparseMatrix<double>(nv, nv);
  p.matrix.resizeNonZeros(Eigen::Index(inner.size()));
  std::copy(outer.begin(), outer.end(), p.matrix.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), p.matrix.innerIndexPtr());
  std::fill(p.matrix.valuePtr(), p.matrix.valuePtr() + inner.size(), 0.0);
  p.slots.resize(mesh.triangles.size());
#pragma omp parallel for schedule(static)
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tr = mesh.triangles[t];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const int col = tr[b];
        const int* first = inner.data() + outer[std::size_t(col)];
        const int* last = inner.data() + outer[std::size_t(col) + 1];
        p.slots[t][std::size_t(3 * a + b)] = int(std::lower_bound(first, last, tr[a]) - inner.data());
      }
  }
  return p;
}

Eigen::SparseMatrix<double> massMatrix(const Mesh2& mesh, const P1Pattern& pattern) {
  Eigen::SparseMatrix<double> M = pattern.matrix;
  double* val = M.valuePtr();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const double a = mesh.triangleArea(int(t)) / 12;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) val[pattern.slots[t][std::size_t(3 * i + j)]] += i == j ? 2 * a : a;
  }
  return M;
}

Eigen::SparseMatrix<double> massMatrix(const Mesh2& mesh) { return massMatrix(mesh, p1Pattern(mesh)); }

Eigen::SparseMatrix<double> stiffnessMatrix(const Mesh2& mesh, const P1Pattern& pattern, double kappa) {
  ABLMG_REQUIRE(kappa > 0 && std::isfinite(kappa), "stiffness matrix: kappa = " << kappa << " (must be positive)");
  Eigen::SparseMatrix<double> K = pattern.matrix;
  double* val = K.valuePtr();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tr = mesh.triangles[t];
    const Vec2 &p0 = mesh.vertices[tr[0]], &p1 = mesh.vertices[tr[1]], &p2 = mesh.vertices[tr[2]];
    // ∇λ_k = rot(e_k) / (2|T|), e_k the edge opposite vertex k
    const Vec2 e[3] = {p2 - p1, p0 - p2, p1 - p0};
    const double area2 = cross(p1 - p0, p2 - p0);
    const double s = kappa / (2 * area2);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) val[pattern.slots[t][std::size_t(3 * i + j)]] += s * e[i].dot(e[j]);
  }
  return K;
}

Eigen::SparseMatrix<double> stiffnessMatrix(const Mesh2& mesh, double kappa) {
  return stiffnessMatrix(mesh, p1Pattern(mesh), kappa);
}

Eigen::VectorXd lumpedMass(const Mesh2& mesh) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(mesh.numVertices());
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    const double a = mesh.triangleArea(t) / 3;
    for (int v : mesh.triangles[std::size_t(t)]) m[v] += a;
  }
  return m;
}

}  // namespace ablmg::fem
