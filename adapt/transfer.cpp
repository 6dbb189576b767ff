#include "ablmg/adapt/transfer.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/core/point_locator.hpp"
#include "ablmg/core/predicates.hpp"
#include "ablmg/fem/p1_matrices.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace ablmg::adapt {
namespace {

/// A convex polygon of at most 9 vertices (a triangle clipped by three half-planes has ≤ 6).
/// label[i] names the line the edge p[i] → p[i+1] lies on: −1 for the subject triangle's own
/// edges, j for the clip triangle's edge c_j → c_(j+1).
struct Polygon {
  std::array<Vec2, 9> p;
  std::array<int, 9> label;
  int n = 0;
  void push(const Vec2& q, int l) {
    p[std::size_t(n)] = q;
    label[std::size_t(n++)] = l;
  }
};

/// orient2d(a, b, p) with its floating-point filter inlined (Shewchuk's bound A, as in
/// core/predicates.cpp): the exact routine runs only when the filter cannot decide. `det`
/// receives the floating determinant (twice the signed area).
inline int orientation(const Vec2& a, const Vec2& b, const Vec2& p, double& det) {
  constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;
  constexpr double kErrBoundA = (3.0 + 16.0 * kEps) * kEps;
  const double l = (b.x() - a.x()) * (p.y() - a.y()), r = (b.y() - a.y()) * (p.x() - a.x());
  det = l - r;
  const double bound = kErrBoundA * (std::abs(l) + std::abs(r));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient2d(a, b, p);
}

/// Keeps the part of `in` on the left of (or on) the directed line a→b (label `line`). Each
/// vertex is classified once, exactly (orient2d); the crossing point uses the floating
/// determinants. Edges keep their labels; the new edge along a→b gets `line`.
void clipHalfPlane(const Polygon& in, const Vec2& a, const Vec2& b, int line, Polygon& out) {
  std::array<int, 9> side;
  std::array<double, 9> det;
  bool anyOut = false;
  for (int i = 0; i < in.n; ++i) {
    const std::size_t k = std::size_t(i);
    side[k] = orientation(a, b, in.p[k], det[k]);
    anyOut |= side[k] < 0;
  }
  if (!anyOut) {
    out = in;
    return;
  }
  out.n = 0;
  for (int i = 0; i < in.n; ++i) {
    const std::size_t k = std::size_t(i), l = std::size_t((i + 1) % in.n);
    const auto crossing = [&] {
      const double t = std::clamp(det[k] / (det[k] - det[l]), 0.0, 1.0);
      return Vec2(in.p[k] + t * (in.p[l] - in.p[k]));
    };
    if (side[k] > 0 && side[l] < 0) {
      out.push(in.p[k], in.label[k]);
      out.push(crossing(), line);  // exit: the next output (the entry) is along the line
    } else if (side[k] >= 0) {
      out.push(in.p[k], side[k] == 0 && side[l] < 0 ? line : in.label[k]);
    } else if (side[l] > 0) {
      out.push(crossing(), in.label[k]);  // entry
    }
  }
}

double polygonArea(const Polygon& poly) {
  double s = 0;
  for (int i = 1; i + 1 < poly.n; ++i) s += signedArea2(poly.p[0], poly.p[std::size_t(i)], poly.p[std::size_t(i + 1)]);
  return 0.5 * s;
}

/// subject ∩ clip (both CCW); n = 0 when the intersection has no area.
Polygon clip(const std::array<Vec2, 3>& subject, const std::array<Vec2, 3>& c) {
  Polygon a, b;
  for (int k = 0; k < 3; ++k) a.push(subject[std::size_t(k)], -1);
  clipHalfPlane(a, c[0], c[1], 0, b);
  if (b.n < 3) return {};
  clipHalfPlane(b, c[1], c[2], 1, a);
  if (a.n < 3) return {};
  clipHalfPlane(a, c[2], c[0], 2, b);
  if (b.n < 3 || !(polygonArea(b) > 0)) return {};
  return b;
}

std::array<Vec2, 3> corners(const Mesh2& mesh, int t) {
  const auto& tr = mesh.triangles[std::size_t(t)];
  return {mesh.vertices[tr[0]], mesh.vertices[tr[1]], mesh.vertices[tr[2]]};
}

bool boxesOverlap(const std::array<Vec2, 3>& a, const std::array<Vec2, 3>& b) {
  const Vec2 aLo = a[0].cwiseMin(a[1]).cwiseMin(a[2]), aHi = a[0].cwiseMax(a[1]).cwiseMax(a[2]);
  const Vec2 bLo = b[0].cwiseMin(b[1]).cwiseMin(b[2]), bHi = b[0].cwiseMax(b[1]).cwiseMax(b[2]);
  return aLo.x() <= bHi.x() && bLo.x() <= aHi.x() && aLo.y() <= bHi.y() && bLo.y() <= aHi.y();
}

/// The advancing front of one new triangle over the old mesh: calls piece(oldTriangle, polygon)
/// for every non-empty intersection, in a deterministic order (breadth first from the old
/// triangle holding the centroid). The front crosses an old edge only where the piece runs
/// along it (positive length, from the clip's edge labels): two old triangles whose pieces of
/// T are adjacent share such an edge, so every piece is reached, and empty neighbours are
/// rarely tested. Until a piece is found (a centroid outside the old mesh), the two rings
/// around the start are searched. `visited` is scratch space.
template <class Piece>
void frontOfTriangle(const Mesh2& oldMesh, const PointLocator& locator, const std::vector<std::array<int, 3>>& nb,
                     const std::array<Vec2, 3>& tri, std::vector<int>& visited, Piece&& piece) {
  const Vec2 centroid = (tri[0] + tri[1] + tri[2]) / 3.0;
  const int start = locator.locate(centroid).triangle;
  visited.assign(1, start);
  thread_local std::vector<int> depth;
  depth.assign(1, 0);
  bool found = false;
  for (std::size_t head = 0; head < visited.size(); ++head) {
    const int o = visited[head];
    const std::array<Vec2, 3> oc = corners(oldMesh, o);
    Polygon poly;
    if (boxesOverlap(tri, oc)) poly = clip(tri, oc);
    bool cross[3] = {false, false, false};  // by neighbour index (across the edge opposite vertex k)
    if (poly.n >= 3) {
      found = true;
      piece(o, poly);
      for (int i = 0; i < poly.n; ++i)
        if (poly.label[std::size_t(i)] >= 0) cross[(poly.label[std::size_t(i)] + 2) % 3] = true;
    } else if (found || depth[head] >= 2) {
      continue;
    } else {
      cross[0] = cross[1] = cross[2] = true;
    }
    for (int k = 0; k < 3; ++k) {
      const int n = nb[std::size_t(o)][std::size_t(k)];
      if (cross[k] && n >= 0 && std::find(visited.begin(), visited.end(), n) == visited.end()) {
        visited.push_back(n);
        depth.push_back(depth[head] + 1);
      }
    }
  }
}

void requireFields(const Mesh2& oldMesh, std::span<const Eigen::VectorXd> fields) {
  for (std::size_t f = 0; f < fields.size(); ++f) {
    ABLMG_REQUIRE(fields[f].size() == oldMesh.numVertices(),
                  "transfer: field " << f << " has " << fields[f].size() << " values for an old mesh of "
                                     << oldMesh.numVertices() << " vertices");
    ABLMG_REQUIRE(fields[f].allFinite(), "transfer: field " << f << " has a non-finite value");
  }
}

/// Closest point of the old boundary to p: the old edge and its parameter s ∈ [0, 1].
std::pair<const BoundaryEdge*, double> closestBoundaryPoint(const Mesh2& mesh, const Vec2& p) {
  const BoundaryEdge* best = nullptr;
  double bestD = std::numeric_limits<double>::infinity(), bestS = 0;
  for (const auto& e : mesh.boundaryEdges) {
    const Vec2 a = mesh.vertices[e.a], d = mesh.vertices[e.b] - a;
    const double s = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const double dist = (a + s * d - p).squaredNorm();
    if (dist < bestD) {
      bestD = dist;
      best = &e;
      bestS = s;
    }
  }
  return {best, bestS};
}

std::vector<Eigen::VectorXd> interpolateFields(const Mesh2& oldMesh, const Mesh2& newMesh,
                                               std::span<const Eigen::VectorXd> fields, TransferStats& stats) {
  const PointLocator locator(oldMesh);
  const int nv = newMesh.numVertices(), nf = int(fields.size());
  std::vector<Eigen::VectorXd> out(static_cast<std::size_t>(nf), Eigen::VectorXd(nv));
  std::vector<char> outside(std::size_t(nv), 0);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const auto loc = locator.locate(newMesh.vertices[std::size_t(v)]);
    outside[std::size_t(v)] = !loc.inside;
    const auto& tr = oldMesh.triangles[std::size_t(loc.triangle)];
    for (int f = 0; f < nf; ++f)
      out[std::size_t(f)][v] =
          loc.bary[0] * fields[f][tr[0]] + loc.bary[1] * fields[f][tr[1]] + loc.bary[2] * fields[f][tr[2]];
  }
  for (int v = 0; v < nv; ++v) {
    if (!outside[std::size_t(v)]) continue;
    ++stats.outsideVertices;
    const auto [e, s] = closestBoundaryPoint(oldMesh, newMesh.vertices[std::size_t(v)]);
    for (int f = 0; f < nf; ++f) out[std::size_t(f)][v] = (1 - s) * fields[f][e->a] + s * fields[f][e->b];
  }
  return out;
}

/// ∫_P 1, ∫_P x, ∫_P x xᵀ of a polygon, coordinates taken relative to `o` (Green's theorem
/// on the edges: exact for any simple polygon; the same sums as a fan triangulation).
struct Moments {
  double area = 0, x = 0, y = 0, xx = 0, xy = 0, yy = 0;
};
Moments polygonMoments(const Polygon& poly, const Vec2& o) {
  Moments m;
  for (int i = 0; i < poly.n; ++i) {
    const Vec2 p = poly.p[std::size_t(i)] - o, q = poly.p[std::size_t((i + 1) % poly.n)] - o;
    const double c = p.x() * q.y() - q.x() * p.y();
    m.area += c;
    m.x += (p.x() + q.x()) * c;
    m.y += (p.y() + q.y()) * c;
    m.xx += (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) * c;
    m.yy += (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) * c;
    m.xy += (p.x() * q.y() + 2 * p.x() * p.y() + 2 * q.x() * q.y() + q.x() * p.y()) * c;
  }
  m.area /= 2;
  m.x /= 6;
  m.y /= 6;
  m.xx /= 12;
  m.yy /= 12;
  m.xy /= 24;
  return m;
}

/// A linear function a + g·(x − o) on a triangle.
struct Affine {
  double a;
  Vec2 g;
};
/// The affine functions λ_k of triangle c, relative to origin o.
std::array<Affine, 3> hatFunctions(const std::array<Vec2, 3>& c, const Vec2& o) {
  const double area2 = signedArea2(c[0], c[1], c[2]);
  std::array<Affine, 3> h;
  for (int k = 0; k < 3; ++k) {
    const Vec2 e = c[std::size_t((k + 2) % 3)] - c[std::size_t((k + 1) % 3)];  // edge opposite k, CCW
    const Vec2 g(-e.y() / area2, e.x() / area2);
    h[std::size_t(k)] = {-g.dot(c[std::size_t((k + 1) % 3)] - o), g};  // λ_k = 0 on that edge
  }
  return h;
}

/// ∫_P f g for affine f, g, from the moments of P.
double integrateProduct(const Moments& m, const Affine& f, const Affine& g) {
  return f.a * g.a * m.area + (f.a * g.g.x() + g.a * f.g.x()) * m.x + (f.a * g.g.y() + g.a * f.g.y()) * m.y +
         f.g.x() * g.g.x() * m.xx + (f.g.x() * g.g.y() + f.g.y() * g.g.x()) * m.xy + f.g.y() * g.g.y() * m.yy;
}

/// Per new triangle t and local vertex k, field f: ∫_{T ∩ old} u_old,f φ_k at rhs[(t·3 + k)·nf + f].
std::vector<double> supermeshLoads(const Mesh2& oldMesh, const Mesh2& newMesh, std::span<const Eigen::VectorXd> fields,
                                   TransferStats& stats) {
  const PointLocator locator(oldMesh);
  const auto nb = oldMesh.triangleNeighbours();
  const int nt = newMesh.numTriangles(), nf = int(fields.size());
  std::vector<double> rhs(std::size_t(nt) * 3 * std::size_t(nf), 0.0);
  std::vector<double> areaOf(std::size_t(nt), 0.0);
  std::vector<int> piecesOf(std::size_t(nt), 0);
#pragma omp parallel
  {
    std::vector<int> visited;
#pragma omp for schedule(dynamic, 256)
    for (int t = 0; t < nt; ++t) {
      const std::array<Vec2, 3> tri = corners(newMesh, t);
      const Vec2 o = tri[0];
      const std::array<Affine, 3> phi = hatFunctions(tri, o);
      double* b = rhs.data() + std::size_t(t) * 3 * std::size_t(nf);
      double area = 0;
      int pieces = 0;
      frontOfTriangle(oldMesh, locator, nb, tri, visited, [&](int old, const Polygon& poly) {
        const Moments m = polygonMoments(poly, o);
        area += m.area;
        ++pieces;
        const std::array<Affine, 3> lam = hatFunctions(corners(oldMesh, old), o);
        const auto& otr = oldMesh.triangles[std::size_t(old)];
        for (int f = 0; f < nf; ++f) {
          const double u0 = fields[f][otr[0]], u1 = fields[f][otr[1]], u2 = fields[f][otr[2]];
          const Affine u{u0 * lam[0].a + u1 * lam[1].a + u2 * lam[2].a, u0 * lam[0].g + u1 * lam[1].g + u2 * lam[2].g};
          for (int k = 0; k < 3; ++k) b[std::size_t(k * nf + f)] += integrateProduct(m, u, phi[std::size_t(k)]);
        }
      });
      areaOf[std::size_t(t)] = area;
      piecesOf[std::size_t(t)] = pieces;
    }
  }
  for (int t = 0; t < nt; ++t) {
    stats.supermeshArea += areaOf[std::size_t(t)];
    stats.supermeshPieces += piecesOf[std::size_t(t)];
  }
  return rhs;
}

/// Σ_i f(i) over [0, n), in blocks of a fixed size summed in block order: the same bits for
/// any thread count (an OpenMP reduction would not be).
template <class F>
double blockSum(Eigen::Index n, F&& f) {
  constexpr Eigen::Index kBlock = 4096;
  const Eigen::Index blocks = (n + kBlock - 1) / kBlock;
  thread_local std::vector<double> partial;
  partial.assign(std::size_t(blocks), 0.0);
  double* out = partial.data();
#pragma omp parallel for schedule(static)
  for (Eigen::Index k = 0; k < blocks; ++k) {
    double s = 0;
    for (Eigen::Index i = k * kBlock; i < std::min(n, (k + 1) * kBlock); ++i) s += f(i);
    out[k] = s;
  }
  double s = 0;
  for (Eigen::Index k = 0; k < blocks; ++k) s += partial[std::size_t(k)];
  return s;
}

/// Jacobi-preconditioned CG on the mass matrix (see the header), from x (initial guess).
/// Plain loops over the compressed columns (M is symmetric, so a column is a row), in parallel
/// with block-ordered sums (deterministic).
int massSolve(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& diag, const Eigen::VectorXd& b,
              Eigen::VectorXd& x) {
  const double bn = b.norm();
  if (bn == 0) {
    x.setZero();
    return 0;
  }
  const Eigen::Index n = b.size();
  const int* outer = M.outerIndexPtr();
  const int* inner = M.innerIndexPtr();
  const double* val = M.valuePtr();
  Eigen::VectorXd r(n), z(n), p(n), q(n);
  const auto apply = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {  // out = M v; returns vᵀ M v
    return blockSum(n, [&](Eigen::Index i) {
      double s = 0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) s += val[k] * v[inner[k]];
      out[i] = s;
      return s * v[i];
    });
  };
  apply(x, q);
  r = b - q;
  z = r.cwiseQuotient(diag);
  p = z;
  double rz = r.dot(z), rr = r.squaredNorm();
  const double tol2 = 1e-28 * bn * bn;
  int it = 0;
  for (; it < 300 && rr > tol2; ++it) {
    const double alpha = rz / apply(p, q);
    rr = 0;
    const double rzNew = blockSum(n, [&](Eigen::Index i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      z[i] = r[i] / diag[i];
      return r[i] * z[i];
    });
    rr = blockSum(n, [&](Eigen::Index i) { return r[i] * r[i]; });
    const double beta = rzNew / rz;
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
    rz = rzNew;
  }
  return it;
}

/// Clip to [lo, hi] and give the clipped mass back where there is room (see the header).
void limitBounds(Eigen::VectorXd& u, const Eigen::VectorXd& m, double lo, double hi) {
  double defect = 0;  // mass to add back
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    const double c = std::clamp(u[i], lo, hi);
    defect += m[i] * (u[i] - c);
    u[i] = c;
  }
  if (defect == 0) return;
  double room = 0;
  for (Eigen::Index i = 0; i < u.size(); ++i) room += m[i] * (defect > 0 ? hi - u[i] : u[i] - lo);
  if (!(room > 0)) return;
  const double share = std::min(1.0, std::abs(defect) / room);
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] += (defect > 0 ? hi - u[i] : lo - u[i]) * share;
}

std::vector<Eigen::VectorXd> projectFields(const Mesh2& oldMesh, const Mesh2& newMesh,
                                           std::span<const Eigen::VectorXd> fields, const TransferOptions& options,
                                           TransferStats& stats) {
  const int nf = int(fields.size()), nv = newMesh.numVertices();
  const std::vector<double> local = supermeshLoads(oldMesh, newMesh, fields, stats);
  std::vector<Eigen::VectorXd> b(std::size_t(nf), Eigen::VectorXd::Zero(nv));
  for (int t = 0; t < newMesh.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k)
      for (int f = 0; f < nf; ++f)
        b[std::size_t(f)][newMesh.triangles[std::size_t(t)][std::size_t(k)]] +=
            local[(std::size_t(t) * 3 + std::size_t(k)) * std::size_t(nf) + std::size_t(f)];
  const Eigen::SparseMatrix<double> M = fem::massMatrix(newMesh);
  const Eigen::VectorXd diag = M.diagonal(), lumped = fem::lumpedMass(newMesh);
  std::vector<Eigen::VectorXd> out(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    Eigen::VectorXd x = b[std::size_t(f)].cwiseQuotient(lumped);  // lumped projection: a close start
    stats.solverIterations = std::max(stats.solverIterations, massSolve(M, diag, b[std::size_t(f)], x));
    if (options.boundPreserving) limitBounds(x, lumped, fields[f].minCoeff(), fields[f].maxCoeff());
    out[std::size_t(f)] = std::move(x);
  }
  return out;
}

}  // namespace

TransferMethod parseTransferMethod(const std::string& name) {
  if (name == "interpolation") return TransferMethod::Interpolation;
  if (name == "projection") return TransferMethod::L2Projection;
  ABLMG_REQUIRE(false, "unknown transfer method '" << name << "' (valid: interpolation, projection)");
  return TransferMethod::L2Projection;
}

std::string toString(TransferMethod method) {
  return method == TransferMethod::Interpolation ? "interpolation" : "projection";
}

double TransferStats::maxRelativeMassDefect() const {
  double worst = 0;
  for (std::size_t f = 0; f < massOld.size() && f < massNew.size(); ++f) {
    const double scale = f < absMassOld.size() ? std::max(absMassOld[f], 1e-300) : 1.0;
    worst = std::max(worst, std::abs(massNew[f] - massOld[f]) / scale);
  }
  return worst;
}

double integrate(const Mesh2& mesh, const Eigen::VectorXd& u) {
  ABLMG_REQUIRE(u.size() == mesh.numVertices(),
                "integrate: " << u.size() << " values for a mesh of " << mesh.numVertices() << " vertices");
  double s = 0;
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    const auto& tr = mesh.triangles[std::size_t(t)];
    s += mesh.triangleArea(t) / 3 * (u[tr[0]] + u[tr[1]] + u[tr[2]]);
  }
  return s;
}

std::vector<Eigen::VectorXd> transferFields(const Mesh2& oldMesh, const Mesh2& newMesh,
                                            std::span<const Eigen::VectorXd> fields, const TransferOptions& options,
                                            TransferStats* statsOut) {
  const Stopwatch watch;
  requireFields(oldMesh, fields);
  ABLMG_REQUIRE(oldMesh.numTriangles() > 0 && newMesh.numTriangles() > 0, "transfer: a mesh has no triangle");
  TransferStats stats;
  std::vector<Eigen::VectorXd> out = options.method == TransferMethod::Interpolation
                                         ? interpolateFields(oldMesh, newMesh, fields, stats)
                                         : projectFields(oldMesh, newMesh, fields, options, stats);
  for (std::size_t f = 0; f < fields.size(); ++f) {
    stats.massOld.push_back(integrate(oldMesh, fields[f]));
    stats.absMassOld.push_back(integrate(oldMesh, fields[f].cwiseAbs()));
    stats.massNew.push_back(integrate(newMesh, out[f]));
  }
  stats.seconds = watch.seconds();
  if (statsOut) *statsOut = std::move(stats);
  return out;
}

void forEachSupermeshPiece(const Mesh2& oldMesh, const Mesh2& newMesh,
                           const std::function<void(int, int, std::span<const Vec2>)>& visit) {
  const PointLocator locator(oldMesh);
  const auto nb = oldMesh.triangleNeighbours();
  std::vector<int> visited;
  for (int t = 0; t < newMesh.numTriangles(); ++t)
    frontOfTriangle(oldMesh, locator, nb, corners(newMesh, t), visited, [&](int o, const Polygon& poly) {
      visit(o, t, std::span<const Vec2>(poly.p.data(), std::size_t(poly.n)));
    });
}

std::vector<Vec2> clipTriangles(const std::array<Vec2, 3>& subject, const std::array<Vec2, 3>& clipper) {
  const Polygon p = clip(subject, clipper);
  return std::vector<Vec2>(p.p.begin(), p.p.begin() + p.n);
}

}  // namespace ablmg::adapt
