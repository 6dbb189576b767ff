#include "ablmg/fem/structured_mesh.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace ablmg::fem {
namespace {

/// Tag of the domain segment containing the segment [a, b] (both on an axis-parallel segment).
int tagOfEdge(const Domain& domain, const Vec2& a, const Vec2& b, double tol) {
  const Vec2 m = 0.5 * (a + b);
  for (const auto& loop : domain.loops()) {
    const int n = int(loop.points.size());
    for (int k = 0; k < n; ++k) {
      const Vec2 &p = loop.points[k], &q = loop.points[(k + 1) % n];
      const Vec2 d = q - p;
      const double len2 = d.squaredNorm();
      const double s = (m - p).dot(d) / len2;
      if (s < 0 || s > 1) continue;
      if ((p + s * d - m).norm() <= tol) return loop.tags.empty() ? 1 : loop.tags[k];
    }
  }
  ABLMG_FAIL("structuredMesh: boundary edge at (" << m.x() << ", " << m.y() << ") lies on no domain segment");
}

/// Splits the cell a-b-c-d (counter-clockwise from its lower-left corner) into two triangles,
/// the diagonal alternating with the cell's parity so that the pattern has no preferred direction.
void splitCell(Mesh2& mesh, int a, int b, int c, int d, bool even) {
  if (even) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
  } else {
    mesh.triangles.push_back({a, b, d});
    mesh.triangles.push_back({b, c, d});
  }
}

}  // namespace

Mesh2 structuredMesh(const Domain& domain, int nx, int ny, double perturbation, std::uint64_t seed) {
  ABLMG_REQUIRE(nx >= 1 && ny >= 1, "structuredMesh: nx = " << nx << ", ny = " << ny << " (need ≥ 1)");
  ABLMG_REQUIRE(perturbation >= 0 && perturbation <= 0.2,
                "structuredMesh: perturbation = " << perturbation << " outside [0, 0.2]");
  ABLMG_REQUIRE(!domain.loops().empty(), "structuredMesh: empty domain");
  ABLMG_REQUIRE(!domain.hasSlits(), "structuredMesh: the domain has slits (a grid cannot keep the lips apart)");
  // Named copies, not a structured binding: the vertex lambda below captures them, which
  // C++20 allows but clang 14 rejects.
  const auto box = domain.boundingBox();
  const Vec2 lo = box.first, hi = box.second;
  const double hx = (hi.x() - lo.x()) / nx, hy = (hi.y() - lo.y()) / ny;
  const double tol = 1e-9 * std::max(hx, hy);
  for (std::size_t l = 0; l < domain.loops().size(); ++l) {
    const auto& pts = domain.loops()[l].points;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const Vec2 &p = pts[k], &q = pts[(k + 1) % pts.size()];
      ABLMG_REQUIRE(std::abs(p.x() - q.x()) <= tol || std::abs(p.y() - q.y()) <= tol,
                    "structuredMesh: segment " << k << " of loop " << l << " is not axis-parallel");
      const double gi = (p.x() - lo.x()) / hx, gj = (p.y() - lo.y()) / hy;
      ABLMG_REQUIRE(std::abs(gi - std::round(gi)) < 1e-9 && std::abs(gj - std::round(gj)) < 1e-9,
                    "structuredMesh: point " << k << " of loop " << l << " (" << p.x() << ", " << p.y()
                                             << ") is not a node of the " << nx << "×" << ny << " grid");
    }
  }

  // Grid node (i, j) → vertex id, created on first use by a kept cell.
  const auto node = [&](int i, int j) { return std::size_t(j) * (nx + 1) + i; };
  std::vector<int> id((nx + 1) * std::size_t(ny + 1), -1);
  Mesh2 mesh;
  auto vertex = [&](int i, int j) {
    int& v = id[node(i, j)];
    if (v < 0) {
      v = mesh.numVertices();
      // Exact coordinates on the box edges (lo + n·h may round off the domain's points).
      const double x = i == nx ? hi.x() : lo.x() + i * hx, y = j == ny ? hi.y() : lo.y() + j * hy;
      mesh.vertices.emplace_back(x, y);
    }
    return v;
  };
  mesh.triangles.reserve(2 * std::size_t(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 c(lo.x() + (i + 0.5) * hx, lo.y() + (j + 0.5) * hy);
      if (!domain.contains(c)) continue;
      splitCell(mesh, vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1), (i + j) % 2 == 0);
    }
  ABLMG_REQUIRE(!mesh.triangles.empty(), "structuredMesh: no cell centre lies in the domain");

  // Boundary edges: triangle sides with no neighbour, run with the triangle on their left.
  const auto nbr = mesh.triangleNeighbours();
  std::vector<char> onBoundary(mesh.numVertices(), 0);
  for (int t = 0; t < mesh.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k)
      if (nbr[t][k] < 0) {
        const int a = mesh.triangles[t][(k + 1) % 3], b = mesh.triangles[t][(k + 2) % 3];
        mesh.boundaryEdges.push_back({a, b, tagOfEdge(domain, mesh.vertices[a], mesh.vertices[b], tol)});
        onBoundary[a] = onBoundary[b] = 1;
      }

  if (perturbation > 0) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    const double amp = perturbation * std::min(hx, hy);
    for (int v = 0; v < mesh.numVertices(); ++v) {
      const double dx = U(rng), dy = U(rng);  // drawn for every vertex: the stream is layout-stable
      if (!onBoundary[v]) mesh.vertices[v] += amp * Vec2(dx, dy);
    }
  }
  mesh.requireValid("structuredMesh", domain.area(), 1e-9);
  return mesh;
}

Mesh2 unitSquareMesh(int n, double perturbation, std::uint64_t seed) {
  return structuredMesh(Domain::rectangle(0, 0, 1, 1), n, n, perturbation, seed);
}

Mesh2 gridRegionMesh(const std::vector<double>& xs, const std::vector<double>& ys,
                     const std::function<int(double x, double y)>& refOfCell) {
  for (const auto* v : {&xs, &ys}) {
    ABLMG_REQUIRE(v->size() >= 2,
                  "gridRegionMesh: " << (v == &xs ? "xs" : "ys") << " has " << v->size() << " breakpoints (need >= 2)");
    for (std::size_t k = 0; k < v->size(); ++k)
      ABLMG_REQUIRE(std::isfinite((*v)[k]) && (k == 0 || (*v)[k] > (*v)[k - 1]),
                    "gridRegionMesh: " << (v == &xs ? "xs" : "ys") << "[" << k << "] = " << (*v)[k]
                                       << " (breakpoints must be finite and strictly increasing)");
  }
  const int nx = int(xs.size()) - 1, ny = int(ys.size()) - 1;
  Mesh2 mesh;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) mesh.vertices.emplace_back(xs[std::size_t(i)], ys[std::size_t(j)]);
  const auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  std::vector<int> cellRef(std::size_t(nx) * std::size_t(ny));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int ref = refOfCell(0.5 * (xs[std::size_t(i)] + xs[std::size_t(i) + 1]),
                                0.5 * (ys[std::size_t(j)] + ys[std::size_t(j) + 1]));
      cellRef[std::size_t(j) * std::size_t(nx) + std::size_t(i)] = ref;
      splitCell(mesh, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 0);
      mesh.triangleRefs.insert(mesh.triangleRefs.end(), 2, ref);
    }
  const auto refAt = [&](int i, int j) { return cellRef[std::size_t(j) * std::size_t(nx) + std::size_t(i)]; };
  const auto interfaceRef = [](int a, int b) { return 10 * std::min(a, b) + std::max(a, b); };
  for (int i = 0; i < nx; ++i) {
    mesh.boundaryEdges.push_back({id(i, 0), id(i + 1, 0), 1});
    mesh.boundaryEdges.push_back({id(i + 1, ny), id(i, ny), 3});
  }
  for (int j = 0; j < ny; ++j) {
    mesh.boundaryEdges.push_back({id(nx, j), id(nx, j + 1), 2});
    mesh.boundaryEdges.push_back({id(0, j + 1), id(0, j), 4});
  }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx && refAt(i, j) != refAt(i + 1, j))
        mesh.interfaceEdges.push_back({id(i + 1, j), id(i + 1, j + 1), interfaceRef(refAt(i, j), refAt(i + 1, j))});
      if (j + 1 < ny && refAt(i, j) != refAt(i, j + 1))
        mesh.interfaceEdges.push_back({id(i, j + 1), id(i + 1, j + 1), interfaceRef(refAt(i, j), refAt(i, j + 1))});
    }
  return mesh;
}

}  // namespace ablmg::fem
