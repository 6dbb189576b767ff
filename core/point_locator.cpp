#include "ablmg/core/point_locator.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace ablmg {

// Half-edges are grouped by their origin vertex (counting sort, O(n)); a row holds a vertex's
// few outgoing half-edges, and the neighbour across a→b holds b→a.
std::vector<std::array<int, 3>> neighboursOf(const Mesh2& mesh) {
  const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
  std::vector<int> rowStart(nv + 1, 0);
  for (const auto& tr : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++rowStart[std::size_t(tr[k]) + 1];
  for (std::size_t v = 0; v < nv; ++v) rowStart[v + 1] += rowStart[v];
  struct HalfEdge {
    int to, triangle;
  };
  std::vector<HalfEdge> out(3 * nt);
  {
    std::vector<int> fill(rowStart.begin(), rowStart.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k)
        out[std::size_t(fill[std::size_t(mesh.triangles[t][k])]++)] = {mesh.triangles[t][(k + 1) % 3], int(t)};
  }
  std::vector<std::array<int, 3>> nb(nt, {-1, -1, -1});
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles[t][(k + 1) % 3], b = mesh.triangles[t][(k + 2) % 3];  // edge a→b opposite k
      for (int i = rowStart[std::size_t(b)]; i < rowStart[std::size_t(b) + 1]; ++i)
        if (out[std::size_t(i)].to == a) {
          nb[t][std::size_t(k)] = out[std::size_t(i)].triangle;
          break;
        }
    }
  return nb;
}

namespace {

constexpr int kLeafTriangles = 8;

/// floor(r) clamped to [0, n − 1], clamped as a double first: a cell ratio beyond int's range
/// (a point far outside, a mesh of extreme aspect ratio, NaN) is undefined behaviour to
/// convert. NaN gives 0.
int clampedCell(double r, int n) { return r >= 0 ? int(std::min(std::floor(r), double(n - 1))) : 0; }

}  // namespace

PointLocator::PointLocator(const Mesh2& mesh) : mesh_(mesh), neighbours_(neighboursOf(mesh)) {
  const int nt = mesh.numTriangles();
  ABLMG_REQUIRE(nt > 0, "PointLocator: the mesh has no triangle");
  Vec2 lo = mesh.vertices.at(0), hi = lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec2 ext = (hi - lo).cwiseMax(1e-300);
  const double cells = std::max(1.0, nt / 2.0);
  const double side = std::sqrt(ext.x() * ext.y() / cells);
  nx_ = clampedCell(ext.x() / side, 4096) + 1;
  ny_ = clampedCell(ext.y() / side, 4096) + 1;
  lo_ = lo;
  cellSize_ = Vec2(ext.x() / nx_, ext.y() / ny_);
  // Triangles bucketed by the cell of their centroid (counting sort: ascending ids per cell).
  centroid_.resize(std::size_t(nt));
  std::vector<int> cellOf(static_cast<std::size_t>(nt));
  std::vector<int> start(std::size_t(nx_) * ny_ + 1, 0);
  for (int t = 0; t < nt; ++t) {
    const auto& tr = mesh.triangles[t];
    const Vec2 c = (mesh.vertices[tr[0]] + mesh.vertices[tr[1]] + mesh.vertices[tr[2]]) / 3.0;
    centroid_[std::size_t(t)] = c;
    const int i = clampedCell((c.x() - lo_.x()) / cellSize_.x(), nx_);
    const int j = clampedCell((c.y() - lo_.y()) / cellSize_.y(), ny_);
    cellOf[std::size_t(t)] = j * nx_ + i;
    ++start[std::size_t(cellOf[std::size_t(t)]) + 1];
  }
  for (std::size_t c = 0; c + 1 < start.size(); ++c) start[c + 1] += start[c];
  order_.resize(std::size_t(nt));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int t = 0; t < nt; ++t) order_[std::size_t(fill[std::size_t(cellOf[std::size_t(t)])]++)] = t;
  }
  cellNode_.assign(std::size_t(nx_) * ny_, -1);
  // A cell of a few triangles starts at its lowest triangle id; a crowded one (graded,
  // stretched meshes) gets a tree, encoded as −2 − root.
  cellStart_ = start;
  for (std::size_t c = 0; c + 1 < start.size(); ++c) {
    if (start[c + 1] - start[c] > kLeafTriangles)
      cellNode_[c] = -2 - build(start[c], start[c + 1]);
    else if (start[c + 1] > start[c])
      cellNode_[c] = order_[std::size_t(start[c])];
  }
}

int PointLocator::build(int lo, int hi) {
  const int id = int(nodes_.size());
  nodes_.push_back(Node{0, -1, -1, -1, lo, hi});
  if (hi - lo <= kLeafTriangles) return id;
  Vec2 a = centroid_[std::size_t(order_[std::size_t(lo)])], b = a;
  for (int k = lo; k < hi; ++k) {
    a = a.cwiseMin(centroid_[std::size_t(order_[std::size_t(k)])]);
    b = b.cwiseMax(centroid_[std::size_t(order_[std::size_t(k)])]);
  }
  const int axis = (b.x() - a.x()) >= (b.y() - a.y()) ? 0 : 1;
  const int mid = lo + (hi - lo) / 2;
  const auto less = [&](int s, int t) {
    const double cs = centroid_[std::size_t(s)][axis], ct = centroid_[std::size_t(t)][axis];
    return cs < ct || (cs == ct && s < t);
  };
  std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi, less);
  const double split = centroid_[std::size_t(order_[std::size_t(mid)])][axis];
  const int left = build(lo, mid), right = build(mid, hi);
  Node& n = nodes_[std::size_t(id)];
  n.axis = axis;
  n.split = split;
  n.left = left;
  n.right = right;
  return id;
}

int PointLocator::nearestInTree(int id, const Vec2& p) const {
  while (nodes_[std::size_t(id)].axis >= 0) {
    const Node& n = nodes_[std::size_t(id)];
    id = p[n.axis] < n.split ? n.left : n.right;
  }
  const Node& leaf = nodes_[std::size_t(id)];
  int best = order_[std::size_t(leaf.lo)];
  double bestD = (centroid_[std::size_t(best)] - p).squaredNorm();
  for (int k = leaf.lo + 1; k < leaf.hi; ++k) {
    const int t = order_[std::size_t(k)];
    const double d = (centroid_[std::size_t(t)] - p).squaredNorm();
    if (d < bestD) {
      bestD = d;
      best = t;
    }
  }
  return best;
}

int PointLocator::startTriangle(const Vec2& p) const {
  const int i0 = clampedCell((p.x() - lo_.x()) / cellSize_.x(), nx_);
  const int j0 = clampedCell((p.y() - lo_.y()) / cellSize_.y(), ny_);
  // Rings of cells around (i0, j0), each in row-major order (j, then i ascending): the first
  // and last rows of a ring whole, the rows between only at i0 ± ring. Only cells of the ring
  // that lie in the grid are visited, so a search costs O(cells), not O(ring³) (a 4096 × 1 grid
  // of a mesh with an extreme aspect ratio took seconds per point).
  const auto at = [&](int i, int j) { return cellNode_[std::size_t(j) * nx_ + i] != -1 ? 0 : -1; };
  const auto from = [&](int i, int j) {
    const int c = cellNode_[std::size_t(j) * nx_ + i];
    return c >= 0 ? c : nearestInTree(-2 - c, p);
  };
  for (int ring = 0; ring < std::max(nx_, ny_); ++ring) {
    const int iLo = std::max(i0 - ring, 0), iHi = std::min(i0 + ring, nx_ - 1);
    for (int j = std::max(j0 - ring, 0); j <= std::min(j0 + ring, ny_ - 1); ++j) {
      if (j == j0 - ring || j == j0 + ring) {
        for (int i = iLo; i <= iHi; ++i)
          if (at(i, j) >= 0) return from(i, j);
      } else {
        if (i0 - ring >= 0 && at(i0 - ring, j) >= 0) return from(i0 - ring, j);
        if (i0 + ring < nx_ && at(i0 + ring, j) >= 0) return from(i0 + ring, j);
      }
    }
  }
  return 0;
}

double PointLocator::outside(int t, const Vec2& p) const {
  const auto& tr = mesh_.triangles[std::size_t(t)];
  const Vec2& a = mesh_.vertices[std::size_t(tr[0])];
  const Vec2& b = mesh_.vertices[std::size_t(tr[1])];
  const Vec2& c = mesh_.vertices[std::size_t(tr[2])];
  const double area2 = signedArea2(a, b, c);
  return -std::min({signedArea2(p, b, c), signedArea2(a, p, c), signedArea2(a, b, p)}) / area2;
}

int PointLocator::startNear(const Vec2& p, int previous) const {
  const bool given = previous >= 0 && previous < mesh_.numTriangles();
  const double fromPrevious = given ? outside(previous, p) : 0;
  if (given && fromPrevious <= 0) return previous;  // p is in it
  const int grid = startTriangle(p);
  return given && previous != grid && fromPrevious < outside(grid, p) ? previous : grid;
}

int PointLocator::walk(int t, const Vec2& p, int cap, bool& atBoundary) const {
  int came = -1;
  atBoundary = false;
  for (int step = 0; step <= cap; ++step) {
    const auto& tr = mesh_.triangles[t];
    int exit = -1;
    for (int k = 0; k < 3; ++k) {
      const int e = (k + step) % 3;  // rotate the first edge tested: avoids systematic cycles
      if (neighbours_[t][e] == came && came >= 0) continue;
      if (orient2d(mesh_.vertices[tr[(e + 1) % 3]], mesh_.vertices[tr[(e + 2) % 3]], p) < 0) {
        exit = e;
        break;
      }
    }
    if (exit < 0) return t;  // p is inside (or on) triangle t
    if (neighbours_[t][exit] < 0) {
      atBoundary = true;
      return t;
    }
    came = t;
    t = neighbours_[t][exit];
  }
  return -1;  // cycling (possible on non-Delaunay meshes)
}

bool PointLocator::contains(int t, const Vec2& p) const {
  const auto& tr = mesh_.triangles[t];
  for (int k = 0; k < 3; ++k)
    if (orient2d(mesh_.vertices[tr[(k + 1) % 3]], mesh_.vertices[tr[(k + 2) % 3]], p) < 0) return false;
  return true;
}

PointLocator::Location PointLocator::clamped(int t, const Vec2& p) const {
  Location loc;
  loc.triangle = t;
  const auto& tr = mesh_.triangles[t];
  const Vec2& a = mesh_.vertices[tr[0]];
  const Vec2& b = mesh_.vertices[tr[1]];
  const Vec2& c = mesh_.vertices[tr[2]];
  const double area2 = signedArea2(a, b, c);
  double w[3] = {signedArea2(p, b, c) / area2, signedArea2(a, p, c) / area2, signedArea2(a, b, p) / area2};
  loc.inside = w[0] >= -1e-12 && w[1] >= -1e-12 && w[2] >= -1e-12;
  double s = 0;
  for (double& x : w) s += (x = std::max(0.0, x));
  for (int k = 0; k < 3; ++k) loc.bary[k] = s > 0 ? w[k] / s : 1.0 / 3.0;
  return loc;
}

int PointLocator::acrossTheBoundary(const Vec2& p, int stopped) const {
  // The walks stopped at a boundary edge. Either p is outside, or the straight walks left a
  // non-convex mesh (a re-entrant corner) on their way to it. Candidates: the triangles bucketed
  // in the 3 × 3 cells around p's cell (around the nearest non-empty cell if they are empty),
  // at most kRescue of them spread over their list. One containing p wins; else a walk from
  // each of a few; else p is outside and the stop whose clamped point is nearest p wins (the
  // nearest boundary edge among them, not the one a far start happened to cross).
  constexpr int kRescue = 64, kWalks = 8;
  int i0 = clampedCell((p.x() - lo_.x()) / cellSize_.x(), nx_);
  int j0 = clampedCell((p.y() - lo_.y()) / cellSize_.y(), ny_);
  // At most ⌈total / stride⌉ ≤ kRescue candidates: on the stack (this runs per query).
  std::array<int, kRescue> candStore;
  int nCand = 0;
  for (int pass = 0; pass < 2 && nCand == 0; ++pass) {
    if (pass == 1) {  // around the start triangle's cell
      const Vec2& c = centroid_[std::size_t(stopped)];
      i0 = clampedCell((c.x() - lo_.x()) / cellSize_.x(), nx_);
      j0 = clampedCell((c.y() - lo_.y()) / cellSize_.y(), ny_);
    }
    int total = 0;
    for (int j = std::max(j0 - 1, 0); j <= std::min(j0 + 1, ny_ - 1); ++j)
      for (int i = std::max(i0 - 1, 0); i <= std::min(i0 + 1, nx_ - 1); ++i)
        total += cellStart_[std::size_t(j) * nx_ + i + 1] - cellStart_[std::size_t(j) * nx_ + i];
    const int stride = std::max(1, (total + kRescue - 1) / kRescue);
    // Every stride-th triangle of the cells' lists taken in turn (k: the position in them),
    // stepping over the others instead of visiting each: crowded cells hold thousands.
    int k = 0;
    for (int j = std::max(j0 - 1, 0); j <= std::min(j0 + 1, ny_ - 1); ++j)
      for (int i = std::max(i0 - 1, 0); i <= std::min(i0 + 1, nx_ - 1); ++i) {
        const int b = cellStart_[std::size_t(j) * nx_ + i], e = cellStart_[std::size_t(j) * nx_ + i + 1];
        for (int q = b + (stride - k % stride) % stride; q < e; q += stride) {
          ABLMG_ASSERT(nCand < kRescue, "");
          candStore[std::size_t(nCand++)] = order_[std::size_t(q)];
        }
        k += e - b;
      }
  }
  const std::span<const int> cand(candStore.data(), std::size_t(nCand));
  for (const int t : cand)
    if (contains(t, p)) return t;
  const int cap = 4 * int(std::sqrt(double(mesh_.numTriangles()))) + 64;
  int best = stopped;
  double bestD = (clampedPoint(clamped(stopped, p)) - p).squaredNorm();
  const int stride = std::max(1, int(cand.size()) / kWalks);
  for (std::size_t k = 0; k < cand.size(); k += std::size_t(stride)) {
    bool atBoundary = false;
    const int t = walk(cand[k], p, cap, atBoundary);
    if (t < 0) continue;
    if (!atBoundary) return t;
    const double d = (clampedPoint(clamped(t, p)) - p).squaredNorm();
    if (d < bestD) {
      bestD = d;
      best = t;
    }
  }
  return best;
}

Vec2 PointLocator::clampedPoint(const Location& loc) const {
  Vec2 q = Vec2::Zero();
  for (int k = 0; k < 3; ++k) q += loc.bary[k] * mesh_.vertices[mesh_.triangles[loc.triangle][k]];
  return q;
}

PointLocator::Location PointLocator::locate(const Vec2& p, int hint) const {
  const bool fromHint = hint >= 0 && hint < mesh_.numTriangles();
  // A walk from a hint stops after a few times √n steps (a far hint: the grid's start is
  // nearer). A walk from the grid's start may take up to n steps, which cost about what the
  // scan below costs: on a stretched layer mesh it can be thousands of thin triangles long
  // (2·10³–2·10⁴ steps for 0.2 % of the tanh-layer cycle's queries at 10⁵ triangles, whose
  // scans took 18 % of its remesh's instructions with a √n cap), and only a cycle, rare on
  // any mesh, goes on to the scan.
  const int cap = 4 * int(std::sqrt(double(mesh_.numTriangles()))) + 64;
  const int gridCap = std::max(cap, mesh_.numTriangles());
  bool atBoundary = false;
  int t = fromHint ? walk(hint, p, cap, atBoundary) : walk(startTriangle(p), p, gridCap, atBoundary);
  // From a far hint the straight walk may have left a non-convex mesh although p is inside, or
  // cycled: walk again from the grid's start triangle, which is near p.
  if (fromHint && (t < 0 || atBoundary)) t = walk(startTriangle(p), p, gridCap, atBoundary);
  if (t < 0) {  // cycling from the grid too: scan
    for (int s = 0; s < mesh_.numTriangles() && t < 0; ++s)
      if (contains(s, p)) t = s;
    if (t < 0) t = startTriangle(p);
    atBoundary = !contains(t, p);
  }
  if (atBoundary) t = acrossTheBoundary(p, t);
  return clamped(t, p);
}

}  // namespace ablmg
