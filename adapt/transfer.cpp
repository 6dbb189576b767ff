#include "ablmg/adapt/transfer.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/core/point_locator.hpp"
#include "ablmg/core/predicates.hpp"
#include "ablmg/fem/p1_matrices.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>

namespace ablmg::adapt {
namespace {

/// A convex polygon of at most 9 vertices (a triangle clipped by three half-planes has ≤ 6).
/// label[i] names the subject triangle's edge that the edge p[i] → p[i+1] lies on (k for the
/// edge s_k → s_(k+1)), −1 for a part of a clip line. corner[i] is k when p[i] is the subject's
/// corner s_k, −1 for a crossing point.
struct Polygon {
  std::array<Vec2, 9> p;
  std::array<int, 9> label, corner;
  int n = 0;
  void push(const Vec2& q, int l, int c) {
    p[std::size_t(n)] = q;
    label[std::size_t(n)] = l;
    corner[std::size_t(n++)] = c;
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

/// Where the subject's corners lie against the clip triangle's lines c_j → c_(j+1):
/// side[k][j] = orientation (exact), det[k][j] the floating determinant. A corner is shared by
/// the subject triangles around it, so the advancing front computes these once per corner.
struct Sides {
  std::array<int, 3> side;
  std::array<double, 3> det;
};
using CornerSides = std::array<const Sides*, 3>;

/// The part of `in` on the left of (or on) clip line `line` (a→b): `in` itself when no vertex
/// is outside, else written to `out`. A corner's side comes from `cs`; a crossing point is
/// classified here, exactly (orient2d). The crossing points use the floating determinants.
/// Edges keep their labels; the new edge along the line gets −1.
const Polygon& clipHalfPlane(const Polygon& in, const Vec2& a, const Vec2& b, int line, const CornerSides& cs,
                             Polygon& out) {
  std::array<int, 9> side;
  std::array<double, 9> det;
  const std::size_t n = std::size_t(in.n);  // locals, not the polygons' members: no reloads per push
  bool anyOut = false;
  for (std::size_t k = 0; k < n; ++k) {
    const int c = in.corner[k];
    if (c >= 0) {
      side[k] = cs[std::size_t(c)]->side[std::size_t(line)];
      det[k] = cs[std::size_t(c)]->det[std::size_t(line)];
    } else {
      side[k] = orientation(a, b, in.p[k], det[k]);
    }
    anyOut |= side[k] < 0;
  }
  if (!anyOut) return in;
  std::size_t m = 0;
  const auto push = [&](const Vec2& q, int label, int corner) {
    out.p[m] = q;
    out.label[m] = label;
    out.corner[m++] = corner;
  };
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t l = k + 1 == n ? 0 : k + 1;
    const auto crossing = [&] {
      const double t = std::clamp(det[k] / (det[k] - det[l]), 0.0, 1.0);
      return Vec2(in.p[k] + t * (in.p[l] - in.p[k]));
    };
    if (side[k] > 0 && side[l] < 0) {
      push(in.p[k], in.label[k], in.corner[k]);
      push(crossing(), -1, -1);  // exit: the next output (the entry) is along the line
    } else if (side[k] >= 0) {
      push(in.p[k], side[k] == 0 && side[l] < 0 ? -1 : in.label[k], in.corner[k]);
    } else if (side[l] > 0) {
      push(crossing(), in.label[k], -1);  // entry
    }
  }
  out.n = int(m);
  return out;
}

double polygonArea(const Polygon& poly) {
  double s = 0;
  for (int i = 1; i + 1 < poly.n; ++i) s += signedArea2(poly.p[0], poly.p[std::size_t(i)], poly.p[std::size_t(i + 1)]);
  return 0.5 * s;
}

/// ∫_P 1, ∫_P x, ∫_P x xᵀ of a polygon, coordinates taken relative to `o` (Green's theorem
/// on the edges, in one pass: exact for any simple polygon; the same sums as a fan triangulation).
struct Moments {
  double area = 0, x = 0, y = 0, xx = 0, xy = 0, yy = 0;
};
Moments polygonMoments(const Polygon& poly, const Vec2& o) {
  Moments m;
  const std::size_t n = std::size_t(poly.n);
  double px = poly.p[n - 1].x() - o.x(), py = poly.p[n - 1].y() - o.y();
  for (std::size_t i = 0; i < n; ++i) {
    const double qx = poly.p[i].x() - o.x(), qy = poly.p[i].y() - o.y();
    const double c = px * qy - qx * py;
    m.area += c;
    m.x += (px + qx) * c;
    m.y += (py + qy) * c;
    m.xx += (px * px + px * qx + qx * qx) * c;
    m.yy += (py * py + py * qy + qy * qy) * c;
    m.xy += (px * qy + 2 * px * py + 2 * qx * qy + qx * py) * c;
    px = qx;
    py = qy;
  }
  m.area /= 2;
  m.x /= 6;
  m.y /= 6;
  m.xx /= 12;
  m.yy /= 12;
  m.xy /= 24;
  return m;
}

/// subject ∩ clip (both CCW), the subject's corner sides given, in one of the two scratch
/// polygons; nullptr when it has fewer than 3 vertices. A subject with its three corners
/// outside one clip line is empty, one with every corner inside every line is itself (returned
/// as scratch[0]): neither is clipped. A clipped polygon may still have no area: the caller
/// tests that (with the area it computes anyway).
const Polygon* clipPolygon(const std::array<Vec2, 3>& s, const std::array<Vec2, 3>& c, const CornerSides& cs,
                           std::array<Polygon, 2>& scratch) {
  std::array<bool, 3> cuts;  // some corner outside line j: the triangle (convex) is inside the others
  for (std::size_t j = 0; j < 3; ++j) {
    const int s0 = cs[0]->side[j], s1 = cs[1]->side[j], s2 = cs[2]->side[j];
    if (s0 < 0 && s1 < 0 && s2 < 0) return nullptr;
    cuts[j] = s0 < 0 || s1 < 0 || s2 < 0;
  }
  Polygon& a = scratch[0];
  a.n = 0;
  for (int k = 0; k < 3; ++k) a.push(s[std::size_t(k)], k, k);
  const Polygon* p = &a;
  for (int j = 0; j < 3; ++j) {
    if (!cuts[std::size_t(j)]) continue;
    p = &clipHalfPlane(*p, c[std::size_t(j)], c[std::size_t((j + 1) % 3)], j, cs, scratch[p == &a ? 1 : 0]);
    if (p->n < 3) return nullptr;
  }
  return p;
}

/// clipPolygon, and nullptr when the intersection has no area.
const Polygon* clip(const std::array<Vec2, 3>& s, const std::array<Vec2, 3>& c, const CornerSides& cs,
                    std::array<Polygon, 2>& scratch) {
  const Polygon* p = clipPolygon(s, c, cs, scratch);
  return p && (p == &scratch[0] || polygonArea(*p) > 0) ? p : nullptr;
}

std::array<Vec2, 3> corners(const Mesh2& mesh, int t) {
  const auto& tr = mesh.triangles[std::size_t(t)];
  return {mesh.vertices[tr[0]], mesh.vertices[tr[1]], mesh.vertices[tr[2]]};
}

/// The sides of the old mesh's vertices against the clip lines of the current new triangle,
/// computed on first use (stamp = that triangle's id) and reused by every old triangle around
/// the vertex.
struct SideCache {
  struct Entry : Sides {
    int stamp = -1;
  };
  std::vector<Entry> entries;
  std::vector<int> seen;  // per old triangle: the stamp of the last front that queued it
  const Entry& get(const Mesh2& oldMesh, int v, int stamp, const std::array<Vec2, 3>& c) {
    Entry& e = entries[std::size_t(v)];
    if (e.stamp != stamp) {
      e.stamp = stamp;
      const Vec2& p = oldMesh.vertices[std::size_t(v)];
      for (std::size_t j = 0; j < 3; ++j) e.side[j] = orientation(c[j], c[(j + 1) % 3], p, e.det[j]);
    }
    return e;
  }
};

/// The advancing front of new triangle `t` (corners `tri`) over the old mesh: calls
/// piece(oldTriangle, polygon) for every non-empty intersection, in a deterministic order
/// (breadth first from the old triangle holding the centroid; the polygon is the old triangle
/// clipped by tri's lines). The front crosses an old edge only where the piece runs along it
/// (positive length, from the clip's edge labels): two old triangles whose pieces of T are
/// adjacent share such an edge, so every piece is reached, and empty neighbours are rarely
/// tested. Until a piece is found (a centroid outside the old mesh), the two rings around the
/// start are searched. `hint` (≥ 0: an old triangle nearby) starts a walk to the centroid; `visited`, `cache` are
/// scratch space. Returns the old triangle holding the centroid.
/// The old triangle holding p, by a visibility walk from `from` (filtered orientation tests):
/// −1 when the walk reaches the boundary or takes more than 64 steps (the caller then asks the
/// locator). A triangle is left across its first edge, in local order, that p lies strictly
/// beyond, so the answer is a function of (from, p) alone.
int walkTo(const Mesh2& mesh, const std::vector<std::array<int, 3>>& nb, int from, const Vec2& p) {
  int t = from;
  for (int step = 0; step < 64 && t >= 0; ++step) {
    const auto& tr = mesh.triangles[std::size_t(t)];
    int exit = -1;
    for (int k = 0; k < 3 && exit < 0; ++k) {
      double det;
      if (orientation(mesh.vertices[tr[std::size_t((k + 1) % 3)]], mesh.vertices[tr[std::size_t((k + 2) % 3)]], p,
                      det) < 0)
        exit = k;
    }
    if (exit < 0) return t;
    t = nb[std::size_t(t)][std::size_t(exit)];
  }
  return -1;
}

/// The old triangle holding a point, for the fronts' starts: a walk (walkTo) from the old
/// triangle of a coarse grid cell (about 8 old triangles per cell; the lowest id whose
/// centroid lies in the cell), and the PointLocator, built on first need only, when the cell
/// is empty or the walk fails (a point outside the old mesh, a walk through a notch or along
/// a stretched layer). Only the few starts that no previous front gives are located: the
/// grid is one pass over the old triangles, where the locator sorts and buckets them all.
/// The answer is a function of the point alone (not of the thread or the call order).
class StartFinder {
 public:
  StartFinder(const Mesh2& mesh, const std::vector<std::array<int, 3>>& nb) : mesh_(mesh), nb_(nb) {
    const int nt = mesh.numTriangles();
    Vec2 lo = mesh.vertices.at(0), hi = lo;
    for (const auto& v : mesh.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    const Vec2 ext = (hi - lo).cwiseMax(1e-300);
    const double side = std::sqrt(ext.x() * ext.y() / std::max(1.0, nt / 8.0));
    nx_ = int(std::clamp(std::floor(ext.x() / side), 0.0, 4095.0)) + 1;
    ny_ = int(std::clamp(std::floor(ext.y() / side), 0.0, 4095.0)) + 1;
    lo_ = lo;
    cellSize_ = Vec2(ext.x() / nx_, ext.y() / ny_);
    first_.assign(std::size_t(nx_) * std::size_t(ny_), -1);
    for (int t = 0; t < nt; ++t) {
      const auto& tr = mesh.triangles[std::size_t(t)];
      int& c = first_[cell((mesh.vertices[tr[0]] + mesh.vertices[tr[1]] + mesh.vertices[tr[2]]) / 3.0)];
      if (c < 0) c = t;
    }
  }
  int find(const Vec2& p) const {
    const int from = first_[cell(p)];
    const int t = from >= 0 ? walkTo(mesh_, nb_, from, p) : -1;
    return t >= 0 ? t : locator().locate(p).triangle;
  }
  /// The PointLocator of the old mesh (built once, thread-safe).
  const PointLocator& locator() const {
    std::call_once(built_, [&] { locator_.emplace(mesh_); });
    return *locator_;
  }

 private:
  std::size_t cell(const Vec2& p) const {
    const auto index = [](double r, int n) { return r >= 0 ? int(std::min(std::floor(r), double(n - 1))) : 0; };
    return std::size_t(index((p.y() - lo_.y()) / cellSize_.y(), ny_)) * std::size_t(nx_) +
           std::size_t(index((p.x() - lo_.x()) / cellSize_.x(), nx_));
  }
  const Mesh2& mesh_;
  const std::vector<std::array<int, 3>>& nb_;
  Vec2 lo_, cellSize_;
  int nx_ = 1, ny_ = 1;
  std::vector<int> first_;
  mutable std::once_flag built_;
  mutable std::optional<PointLocator> locator_;
};

template <class Piece>
int frontOfTriangle(const Mesh2& oldMesh, const StartFinder& starts, const std::vector<std::array<int, 3>>& nb, int t,
                    const std::array<Vec2, 3>& tri, int hint, std::vector<int>& visited, SideCache& cache,
                    Piece&& piece) {
  const Vec2 centroid = (tri[0] + tri[1] + tri[2]) / 3.0;
  int start = hint >= 0 ? walkTo(oldMesh, nb, hint, centroid) : -1;
  if (start < 0) start = starts.find(centroid);
  visited.assign(1, start);
  cache.seen[std::size_t(start)] = t;
  thread_local std::vector<int> depth;
  depth.assign(1, 0);
  bool found = false;
  std::array<Polygon, 2> scratch;
  for (std::size_t head = 0; head < visited.size(); ++head) {
    const int o = visited[head];
    const auto& otr = oldMesh.triangles[std::size_t(o)];
    const CornerSides cs = {&cache.get(oldMesh, otr[0], t, tri), &cache.get(oldMesh, otr[1], t, tri),
                            &cache.get(oldMesh, otr[2], t, tri)};
    const Polygon* poly = clipPolygon(corners(oldMesh, o), tri, cs, scratch);
    Moments m;
    if (poly) {
      m = polygonMoments(*poly, tri[0]);
      if (poly != &scratch[0] && !(m.area > 0)) poly = nullptr;
    }
    bool cross[3] = {false, false, false};  // by neighbour index (across the edge opposite vertex k)
    if (poly) {
      found = true;
      piece(o, *poly, m);
      for (int i = 0; i < poly->n; ++i)
        if (poly->label[std::size_t(i)] >= 0) cross[(poly->label[std::size_t(i)] + 2) % 3] = true;
    } else if (found || depth[head] >= 2) {
      continue;
    } else {
      cross[0] = cross[1] = cross[2] = true;
    }
    for (int k = 0; k < 3; ++k) {
      const int n = nb[std::size_t(o)][std::size_t(k)];
      if (cross[k] && n >= 0 && cache.seen[std::size_t(n)] != t) {
        cache.seen[std::size_t(n)] = t;
        visited.push_back(n);
        depth.push_back(depth[head] + 1);
      }
    }
  }
  return start;
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
  ParallelFailure failure;  // location allocates on its rescue path: rethrown after the region
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v)
    failure.run(v, [&] {
      const auto loc = locator.locate(newMesh.vertices[std::size_t(v)]);
      outside[std::size_t(v)] = !loc.inside;
      const auto& tr = oldMesh.triangles[std::size_t(loc.triangle)];
      for (int f = 0; f < nf; ++f)
        out[std::size_t(f)][v] =
            loc.bary[0] * fields[f][tr[0]] + loc.bary[1] * fields[f][tr[1]] + loc.bary[2] * fields[f][tr[2]];
    });
  failure.rethrow();
  for (int v = 0; v < nv; ++v) {
    if (!outside[std::size_t(v)]) continue;
    ++stats.outsideVertices;
    const auto [e, s] = closestBoundaryPoint(oldMesh, newMesh.vertices[std::size_t(v)]);
    for (int f = 0; f < nf; ++f) out[std::size_t(f)][v] = (1 - s) * fields[f][e->a] + s * fields[f][e->b];
  }
  return out;
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

/// Per old triangle and field: u_old = a + g·(x − c_0) (c_0 the triangle's first corner), at
/// coefficients[(t·nf + f)·3 + {0, 1, 2}] = a, g_x, g_y.
std::vector<double> oldAffineFields(const Mesh2& mesh, std::span<const Eigen::VectorXd> fields) {
  const int nt = mesh.numTriangles(), nf = int(fields.size());
  std::vector<double> coefficients(std::size_t(nt) * std::size_t(nf) * 3);
#pragma omp parallel for schedule(static)
  for (int t = 0; t < nt; ++t) {
    const auto& tr = mesh.triangles[std::size_t(t)];
    const std::array<Affine, 3> lam = hatFunctions(corners(mesh, t), mesh.vertices[tr[0]]);
    for (int f = 0; f < nf; ++f) {
      const double u0 = fields[f][tr[0]], u1 = fields[f][tr[1]], u2 = fields[f][tr[2]];
      const Vec2 g = u0 * lam[0].g + u1 * lam[1].g + u2 * lam[2].g;
      double* c = coefficients.data() + (std::size_t(t) * std::size_t(nf) + std::size_t(f)) * 3;
      c[0] = u0;
      c[1] = g.x();
      c[2] = g.y();
    }
  }
  return coefficients;
}

/// Per new triangle t and local vertex k, field f: ∫_{T ∩ old} u_old,f φ_k at rhs[(t·3 + k)·nf + f].
/// On each piece P the moments of u_old (∫_P u, ∫_P u x, ∫_P u y, exact from P's polygon
/// moments: u_old is affine there) are summed over T's pieces; φ_k being affine on the whole
/// of T, ∫ u_old φ_k follows from the three sums.
std::vector<double> supermeshLoads(const Mesh2& oldMesh, const Mesh2& newMesh, std::span<const Eigen::VectorXd> fields,
                                   TransferStats& stats) {
  const std::vector<std::array<int, 3>> nb = neighboursOf(oldMesh);
  const StartFinder starts(oldMesh, nb);
  const std::vector<double> coefficients = oldAffineFields(oldMesh, fields);
  const int nt = newMesh.numTriangles(), nf = int(fields.size());
  constexpr int kChunk = 256;  // the front's start is located from the previous triangle's within a chunk
  std::vector<double> rhs(std::size_t(nt) * 3 * std::size_t(nf), 0.0);
  std::vector<double> areaOf(std::size_t(nt), 0.0);
  std::vector<int> piecesOf(std::size_t(nt), 0);
  ParallelFailure failure;  // the fronts allocate: rethrown after the region, the lowest triangle's
#pragma omp parallel
  {
    std::vector<int> visited;
    SideCache cache;
    cache.entries.resize(std::size_t(oldMesh.numVertices()));
    cache.seen.assign(std::size_t(oldMesh.numTriangles()), -1);
    std::vector<double> moments(3 * std::size_t(nf));
    int hint = -1;
#pragma omp for schedule(dynamic, kChunk)
    for (int t = 0; t < nt; ++t)
      failure.run(t, [&] {
        const std::array<Vec2, 3> tri = corners(newMesh, t);
        const Vec2 o = tri[0];
        std::fill(moments.begin(), moments.end(), 0.0);
        double area = 0;
        int pieces = 0;
        hint = frontOfTriangle(oldMesh, starts, nb, t, tri, t % kChunk == 0 ? -1 : hint, visited, cache,
                               [&](int old, const Polygon&, const Moments& m) {
                                 area += m.area;
                                 ++pieces;
                                 const Vec2 shift = o - oldMesh.vertices[oldMesh.triangles[std::size_t(old)][0]];
                                 const double* c = coefficients.data() + std::size_t(old) * std::size_t(nf) * 3;
                                 for (std::size_t f = 0; f < std::size_t(nf); ++f, c += 3) {
                                   const double a = c[0] + c[1] * shift.x() + c[2] * shift.y();
                                   moments[3 * f] += a * m.area + c[1] * m.x + c[2] * m.y;
                                   moments[3 * f + 1] += a * m.x + c[1] * m.xx + c[2] * m.xy;
                                   moments[3 * f + 2] += a * m.y + c[1] * m.xy + c[2] * m.yy;
                                 }
                               });
        const std::array<Affine, 3> phi = hatFunctions(tri, o);
        double* b = rhs.data() + std::size_t(t) * 3 * std::size_t(nf);
        for (std::size_t k = 0; k < 3; ++k)
          for (std::size_t f = 0; f < std::size_t(nf); ++f)
            b[k * std::size_t(nf) + f] =
                phi[k].a * moments[3 * f] + phi[k].g.x() * moments[3 * f + 1] + phi[k].g.y() * moments[3 * f + 2];
        areaOf[std::size_t(t)] = area;
        piecesOf[std::size_t(t)] = pieces;
      });
  }
  failure.rethrow();
  for (int t = 0; t < nt; ++t) {
    stats.supermeshArea += areaOf[std::size_t(t)];
    stats.supermeshPieces += piecesOf[std::size_t(t)];
  }
  return rhs;
}

/// The triangles around each vertex of a mesh: entries start[v] … start[v + 1] − 1 of `corner`
/// hold 3t + k for the triangles t (ascending) whose local vertex k is v, of `triangle` t. A sum over them in
/// that order adds the same terms in the same order as a scatter in triangle order.
struct VertexTriangles {
  std::vector<int> start, corner, triangle;
  explicit VertexTriangles(const Mesh2& mesh) : start(std::size_t(mesh.numVertices()) + 1, 0) {
    for (const auto& tr : mesh.triangles)
      for (int v : tr) ++start[std::size_t(v) + 1];
    for (std::size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
    corner.resize(std::size_t(start.back()));
    std::vector<int> fill(start.begin(), start.end() - 1);
    triangle.resize(corner.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t e = std::size_t(fill[std::size_t(mesh.triangles[t][k])]++);
        corner[e] = int(3 * t + k);
        triangle[e] = int(t);
      }
  }
};

/// The vector operations of the mass solve cut [0, n) into kBlocks fixed ranges, whatever the
/// thread count; a dot product is the sum of its blocks' partial sums, in block order, so the
/// bits do not depend on how OpenMP shares the blocks out.
constexpr int kBlocks = 64;
struct BlockRange {
  Eigen::Index lo, hi;
};
BlockRange blockRange(Eigen::Index n, int block) { return {n * block / kBlocks, n * (block + 1) / kBlocks}; }
double sumOfBlocks(const std::array<double, kBlocks>& partial) {
  double s = 0;
  for (double p : partial) s += p;
  return s;
}

/// The consistent P1 mass matrix of a mesh, applied without being assembled: per triangle
/// (M_T x)_i = |T|/12 (x_a + x_b + x_c + x_i), so (M x)_i = (m_i/4) x_i + Σ_{T ∋ i} |T|/12 (x_a + x_b + x_c),
/// m the lumped masses, the sum over i's triangles in triangle order.
struct MassOperator {
  const Mesh2& mesh;
  const VertexTriangles& around;
  Eigen::VectorXd areas12, quarterLumped, invDiag;  // M's diagonal is m/2
  /// `areas` the triangles' areas, `lumped` the lumped masses.
  MassOperator(const Mesh2& m, const VertexTriangles& a, const std::vector<double>& areas,
               const Eigen::VectorXd& lumped)
      : mesh(m), around(a), areas12(m.numTriangles()), quarterLumped(lumped / 4), invDiag((lumped / 2).cwiseInverse()) {
#pragma omp parallel for schedule(static)
    for (int t = 0; t < m.numTriangles(); ++t) areas12[t] = areas[std::size_t(t)] / 12;
  }
  /// First half of y = M x: s_T = |T|/12 (x_a + x_b + x_c) on the triangles of one block.
  void sumsBlock(const Eigen::VectorXd& x, Eigen::VectorXd& s, BlockRange range) const {
    const double *xs = x.data(), *a = areas12.data();
    double* ss = s.data();
    const std::array<int, 3>* tri = mesh.triangles.data();
    for (Eigen::Index t = range.lo; t < range.hi; ++t) ss[t] = a[t] * (xs[tri[t][0]] + xs[tri[t][1]] + xs[tri[t][2]]);
  }
  /// Second half, on the vertices of one block, from every triangle's s_T: y_i = (m_i/4) x_i +
  /// Σ_{T ∋ i} s_T. Returns that block's part of xᵀ M x.
  double gatherBlock(const Eigen::VectorXd& x, const Eigen::VectorXd& s, Eigen::VectorXd& y, BlockRange range) const {
    const int* start = around.start.data();
    const int* triangle = around.triangle.data();
    const double *xs = x.data(), *ss = s.data(), *q = quarterLumped.data();
    double* ys = y.data();
    double xy = 0;
    for (Eigen::Index i = range.lo; i < range.hi; ++i) {
      double v = q[i] * xs[i];
      for (int e = start[i]; e < start[i + 1]; ++e) v += ss[triangle[e]];
      ys[i] = v;
      xy += xs[i] * v;
    }
    return xy;
  }
};

/// Jacobi-preconditioned CG on the mass matrix (see the header), from x (initial guess), in
/// one parallel region: the blocks are shared out statically, every thread forms the same
/// dot products from the blocks' partial sums, so all take the same steps.
int massSolve(const MassOperator& mass, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const double bn = b.norm();
  if (bn == 0) {
    x.setZero();
    return 0;
  }
  const Eigen::Index n = b.size();
  const Eigen::Index nt = mass.areas12.size();
  Eigen::VectorXd r(n), z(n), p(n), q(n), sums(nt);
  std::array<double, kBlocks> partialPq{}, partialRz{}, partialRr{};
  const double tol2 = 1e-28 * bn * bn;
  int iterations = 0;
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (int k = 0; k < kBlocks; ++k) mass.sumsBlock(x, sums, blockRange(nt, k));
#pragma omp for schedule(static)
    for (int k = 0; k < kBlocks; ++k) {
      const BlockRange range = blockRange(n, k);
      mass.gatherBlock(x, sums, q, range);
      double rz = 0, rr = 0;
      for (Eigen::Index i = range.lo; i < range.hi; ++i) {
        r[i] = b[i] - q[i];
        z[i] = r[i] * mass.invDiag[i];
        p[i] = z[i];
        rz += r[i] * z[i];
        rr += r[i] * r[i];
      }
      partialRz[std::size_t(k)] = rz;
      partialRr[std::size_t(k)] = rr;
    }
    double rz = sumOfBlocks(partialRz), rr = sumOfBlocks(partialRr);
    int it = 0;
    for (; it < 300 && rr > tol2; ++it) {
#pragma omp for schedule(static)
      for (int k = 0; k < kBlocks; ++k) mass.sumsBlock(p, sums, blockRange(nt, k));
#pragma omp for schedule(static)
      for (int k = 0; k < kBlocks; ++k) partialPq[std::size_t(k)] = mass.gatherBlock(p, sums, q, blockRange(n, k));
      const double alpha = rz / sumOfBlocks(partialPq);
#pragma omp for schedule(static)
      for (int k = 0; k < kBlocks; ++k) {
        const BlockRange range = blockRange(n, k);
        double rzNew = 0, rrNew = 0;
        for (Eigen::Index i = range.lo; i < range.hi; ++i) {
          x[i] += alpha * p[i];
          r[i] -= alpha * q[i];
          z[i] = r[i] * mass.invDiag[i];
          rzNew += r[i] * z[i];
          rrNew += r[i] * r[i];
        }
        partialRz[std::size_t(k)] = rzNew;
        partialRr[std::size_t(k)] = rrNew;
      }
      const double rzNew = sumOfBlocks(partialRz);
      rr = sumOfBlocks(partialRr);
      const double beta = rzNew / rz;
      rz = rzNew;
#pragma omp for schedule(static)
      for (int k = 0; k < kBlocks; ++k) {
        const BlockRange range = blockRange(n, k);
        for (Eigen::Index i = range.lo; i < range.hi; ++i) p[i] = z[i] + beta * p[i];
      }
    }
#pragma omp single nowait
    iterations = it;
  }
  return iterations;
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
  const int nf = int(fields.size()), nv = newMesh.numVertices(), nt = newMesh.numTriangles();
  const std::vector<double> local = supermeshLoads(oldMesh, newMesh, fields, stats);
  const VertexTriangles around(newMesh);
  std::vector<double> areas(static_cast<std::size_t>(nt));
#pragma omp parallel for schedule(static)
  for (int t = 0; t < nt; ++t) areas[std::size_t(t)] = newMesh.triangleArea(t);
  // b_i = Σ over i's triangles of their local loads, and the lumped masses m_i = Σ |T|/3
  // (fem::lumpedMass), summed in triangle order: the bits of a serial scatter.
  std::vector<Eigen::VectorXd> b(static_cast<std::size_t>(nf), Eigen::VectorXd(nv));
  Eigen::VectorXd lumped(nv);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    double m = 0;
    for (int f = 0; f < nf; ++f) b[std::size_t(f)][v] = 0;
    for (int e = around.start[std::size_t(v)]; e < around.start[std::size_t(v) + 1]; ++e) {
      const std::size_t c = std::size_t(around.corner[std::size_t(e)]);
      m += areas[c / 3] / 3;
      for (int f = 0; f < nf; ++f) b[std::size_t(f)][v] += local[c * std::size_t(nf) + std::size_t(f)];
    }
    lumped[v] = m;
  }
  const MassOperator mass(newMesh, around, areas, lumped);
  std::vector<Eigen::VectorXd> out(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    Eigen::VectorXd x = b[std::size_t(f)].cwiseQuotient(lumped);  // lumped projection: a close start
    stats.solverIterations = std::max(stats.solverIterations, massSolve(mass, b[std::size_t(f)], x));
    if (options.boundPreserving) limitBounds(x, lumped, fields[f].minCoeff(), fields[f].maxCoeff());
    out[std::size_t(f)] = std::move(x);
  }
  return out;
}

/// ∫u and ∫|u| of a P1 field in one pass (the same sums as integrate(mesh, u) and
/// integrate(mesh, |u|)).
std::pair<double, double> integrateWithAbs(const Mesh2& mesh, const Eigen::VectorXd& u) {
  double s = 0, a = 0;
  for (const auto& tr : mesh.triangles) {
    const double w = 0.5 * signedArea2(mesh.vertices[tr[0]], mesh.vertices[tr[1]], mesh.vertices[tr[2]]) / 3;
    s += w * (u[tr[0]] + u[tr[1]] + u[tr[2]]);
    a += w * (std::abs(u[tr[0]]) + std::abs(u[tr[1]]) + std::abs(u[tr[2]]));
  }
  return {s, a};
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
    s += 0.5 * signedArea2(mesh.vertices[tr[0]], mesh.vertices[tr[1]], mesh.vertices[tr[2]]) / 3 *
         (u[tr[0]] + u[tr[1]] + u[tr[2]]);
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
    const auto [mass, absMass] = integrateWithAbs(oldMesh, fields[f]);
    stats.massOld.push_back(mass);
    stats.absMassOld.push_back(absMass);
    stats.massNew.push_back(integrate(newMesh, out[f]));
  }
  stats.seconds = watch.seconds();
  if (statsOut) *statsOut = std::move(stats);
  return out;
}

void forEachSupermeshPiece(const Mesh2& oldMesh, const Mesh2& newMesh,
                           const std::function<void(int, int, std::span<const Vec2>)>& visit) {
  const std::vector<std::array<int, 3>> nb = neighboursOf(oldMesh);
  const StartFinder starts(oldMesh, nb);
  std::vector<int> visited;
  SideCache cache;
  cache.entries.resize(std::size_t(oldMesh.numVertices()));
  cache.seen.assign(std::size_t(oldMesh.numTriangles()), -1);
  int hint = -1;
  for (int t = 0; t < newMesh.numTriangles(); ++t)
    hint = frontOfTriangle(oldMesh, starts, nb, t, corners(newMesh, t), hint, visited, cache,
                           [&](int o, const Polygon& poly, const Moments&) {
                             visit(o, t, std::span<const Vec2>(poly.p.data(), std::size_t(poly.n)));
                           });
}

std::vector<Vec2> clipTriangles(const std::array<Vec2, 3>& subject, const std::array<Vec2, 3>& clipper) {
  std::array<Sides, 3> sides;
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t j = 0; j < 3; ++j)
      sides[k].side[j] = orientation(clipper[j], clipper[(j + 1) % 3], subject[k], sides[k].det[j]);
  const CornerSides cs = {&sides[0], &sides[1], &sides[2]};
  std::array<Polygon, 2> scratch;
  const Polygon* p = clip(subject, clipper, cs, scratch);
  if (!p) return {};
  return std::vector<Vec2>(p->p.begin(), p->p.begin() + p->n);
}

}  // namespace ablmg::adapt
