#include "ablmg/mesher/connect.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/core/predicates.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"
#include "ablmg/mesher/triangulation.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <string>

namespace ablmg::mesher {

bool swapCriterion(const Vec2& x, const Vec2& z, const Vec2& y, const Vec2& w, const Metric2& m) {
  // α at y (vectors a = x − y, b = z − y), β at w (c = z − w, d = x − w); the cross products
  // are taken unsigned since y, w lie on either side of x–z. sin(α+β) < 0 ⇔ α+β > π.
  const Vec2 a = x - y, b = z - y, c = z - w, d = x - w;
  const double sa = std::abs(cross(a, b)), sb = std::abs(cross(c, d));
  const double value = sa * m.dot(c, d) + sb * m.dot(a, b);  // eq. (12)
  const double scale =
      sa * std::sqrt(m.squaredLength(c) * m.squaredLength(d)) + sb * std::sqrt(m.squaredLength(a) * m.squaredLength(b));
  if (value < -1e-12 * scale) return true;
  if (value > 1e-12 * scale) return false;
  // Four nodes on one ellipse: the diagonal with the node of smallest abscissa goes.
  const auto less = [](const Vec2& p, const Vec2& q) { return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y()); };
  const Vec2& xzMin = less(x, z) ? x : z;
  const Vec2& ywMin = less(y, w) ? y : w;
  return less(xzMin, ywMin);
}

namespace {

bool properCross(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s) {
  return orient2d(p, q, r) * orient2d(p, q, s) < 0 && orient2d(r, s, p) * orient2d(r, s, q) < 0;
}

/// Boundary edges in a uniform grid, to test links against them, with an occupancy grid of
/// kBlock × kBlock cells above it: a link walks the blocks and enters the cells of occupied
/// ones only. The cells are about a boundary edge long, so where the boundary is finely cut (a
/// layer crossing it) the interior links of anisotropy 10⁴ span hundreds of cells, nearly all
/// empty: walked cell by cell they were too dear and were left to the scaffold (10 % of the
/// layer's triangles repaired, a third of its connection time).
class BoundaryGrid {
 public:
  BoundaryGrid(std::span<const Vec2> pos, std::span<const BoundaryEdge> edges) : pos_(pos), edges_(edges) {
    lo_ = hi_ = pos[edges[0].a];
    for (const auto& e : edges) {
      lo_ = lo_.cwiseMin(pos[e.a]).cwiseMin(pos[e.b]);
      hi_ = hi_.cwiseMax(pos[e.a]).cwiseMax(pos[e.b]);
    }
    const Vec2 ext = (hi_ - lo_).cwiseMax(Vec2(1e-300, 1e-300));
    double total = 0;
    for (const auto& e : edges) total += (pos[e.b] - pos[e.a]).norm();
    cell_ = std::max(total / double(edges.size()), std::sqrt(ext.x() * ext.y() / 4e6));
    margin_ = 1e-9 * std::max(ext.x(), ext.y());
    nx_ = std::min(2048, int(ext.x() / cell_) + 1);
    ny_ = std::min(2048, int(ext.y() / cell_) + 1);
    offsets_.assign(std::size_t(nx_) * ny_ + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<int> fill;
      if (pass == 1) {
        for (std::size_t c = 1; c < offsets_.size(); ++c) offsets_[c] += offsets_[c - 1];
        ids_.resize(offsets_.back());
        fill.assign(offsets_.begin(), offsets_.end() - 1);
      }
      for (int i = 0; i < int(edges.size()); ++i) {
        forCells(pos[edges[i].a], pos[edges[i].b], [&](std::size_t c) {
          if (pass == 0)
            ++offsets_[c + 1];
          else
            ids_[fill[c]++] = i;
          return false;
        });
      }
    }
    bx_ = (nx_ + kBlock - 1) / kBlock;
    by_ = (ny_ + kBlock - 1) / kBlock;
    occupied_.assign(std::size_t(bx_) * by_, 0);
    for (int y = 0; y < ny_; ++y)
      for (int x = 0; x < nx_; ++x) {
        const std::size_t c = std::size_t(y) * nx_ + x;
        if (offsets_[c + 1] > offsets_[c]) occupied_[std::size_t(y / kBlock) * bx_ + x / kBlock] = 1;
      }
  }

  /// Does segment p–q (link between nodes i and j) meet a boundary edge not incident to i or j?
  /// An edge whose bounding box lies strictly beside the link's cannot meet it (closed
  /// segments), and is skipped before the exact test: a wall cell crossed by a layer holds
  /// ~50 edges, of which a link from a wall node spans a few (the tanh layer's cycle at 10⁵
  /// vertices, a third of them on the walls: 4.6·10⁷ exact tests, 20 % of its instructions).
  bool crosses(int i, int j) const {
    const Vec2 &p = pos_[i], &q = pos_[j];
    const Vec2 lo = p.cwiseMin(q), hi = p.cwiseMax(q);
    return forOccupiedCells(p, q, [&](std::size_t c) {
      for (int k = offsets_[c]; k < offsets_[c + 1]; ++k) {
        const auto& e = edges_[ids_[k]];
        if (e.a == i || e.a == j || e.b == i || e.b == j) continue;
        const Vec2 &r = pos_[e.a], &s = pos_[e.b];
        if (std::max(r.x(), s.x()) < lo.x() || std::min(r.x(), s.x()) > hi.x() || std::max(r.y(), s.y()) < lo.y() ||
            std::min(r.y(), s.y()) > hi.y())
          continue;
        if (segmentsIntersect(p, q, r, s)) return true;
      }
      return false;
    });
  }

 private:
  std::span<const Vec2> pos_;
  std::span<const BoundaryEdge> edges_;
  Vec2 lo_, hi_;
  double cell_ = 1, margin_ = 0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> offsets_, ids_;
  static constexpr int kBlock = 16;
  int bx_ = 1, by_ = 1;
  std::vector<char> occupied_;  ///< per block of kBlock × kBlock cells: holds an edge

  /// forCells for the cells of occupied blocks only: the segment is cut into pieces no longer
  /// than a block, and the cells of a piece are visited if one of the ≤ 2×2 blocks of its box
  /// is occupied (every cell it touches lies in those blocks).
  template <class F>
  bool forOccupiedCells(const Vec2& p, const Vec2& q, F&& f) const {
    const double block = kBlock * cell_;
    const auto bx = [&](double x) { return std::clamp(int((x - lo_.x()) / block), 0, bx_ - 1); };
    const auto by = [&](double y) { return std::clamp(int((y - lo_.y()) / block), 0, by_ - 1); };
    const double len = (q - p).lpNorm<Eigen::Infinity>() / block;
    const int pieces = 1 + int(std::min(len, double(bx_ + by_)));
    for (int k = 0; k < pieces; ++k) {
      const Vec2 a = p + (q - p) * (double(k) / pieces),
                 b = k + 1 == pieces ? q : p + (q - p) * (double(k + 1) / pieces);
      const int x0 = bx(std::min(a.x(), b.x()) - margin_), x1 = bx(std::max(a.x(), b.x()) + margin_);
      const int y0 = by(std::min(a.y(), b.y()) - margin_), y1 = by(std::max(a.y(), b.y()) + margin_);
      bool any = false;
      for (int y = y0; y <= y1 && !any; ++y)
        for (int x = x0; x <= x1 && !any; ++x) any = occupied_[std::size_t(y) * bx_ + x] != 0;
      if (any && forCells(a, b, f)) return true;
    }
    return false;
  }

  /// Calls f on every cell the closed segment p–q touches (it is cut into pieces no longer
  /// than a cell, each visiting the ≤ 2×2 cells of its box), until f returns true; a cell may
  /// be visited twice.
  template <class F>
  bool forCells(const Vec2& p, const Vec2& q, F&& f) const {
    const auto cx = [&](double x) { return std::clamp(int((x - lo_.x()) / cell_), 0, nx_ - 1); };
    const auto cy = [&](double y) { return std::clamp(int((y - lo_.y()) / cell_), 0, ny_ - 1); };
    const int pieces = 1 + int((q - p).lpNorm<Eigen::Infinity>() / cell_);
    for (int k = 0; k < pieces; ++k) {
      const Vec2 a = p + (q - p) * (double(k) / pieces),
                 b = k + 1 == pieces ? q : p + (q - p) * (double(k + 1) / pieces);
      const int x0 = cx(std::min(a.x(), b.x()) - margin_), x1 = cx(std::max(a.x(), b.x()) + margin_);
      const int y0 = cy(std::min(a.y(), b.y()) - margin_), y1 = cy(std::max(a.y(), b.y()) + margin_);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
          if (f(std::size_t(y) * nx_ + x)) return true;
    }
    return false;
  }
};

/// The candidate links and their state during the deletions of step 2.
struct Links {
  std::vector<int> offsets{0}, ids;  ///< CSR rows sorted by id (symmetric)
  std::vector<int> ccw;              ///< per row: positions within the row in counter-clockwise order
  std::vector<std::uint8_t> alive;

  int find(int i, int j) const {
    const auto b = ids.begin() + offsets[i], e = ids.begin() + offsets[i + 1];
    const auto it = std::lower_bound(b, e, j);
    return (it != e && *it == j) ? int(it - ids.begin()) : -1;
  }
  bool linked(int i, int j) const {
    const int e = find(i, j);
    return e >= 0 && alive[e];
  }
  /// Live neighbours of i in counter-clockwise order.
  void liveRing(int i, std::vector<int>& out) const {
    out.clear();
    for (int k = offsets[i]; k < offsets[i + 1]; ++k) {
      const int e = offsets[i] + ccw[k];
      if (alive[e]) out.push_back(ids[e]);
    }
  }
};

/// Angle order of the vectors around a node: half-plane first, then cross product.
bool ccwLess(const Vec2& u, const Vec2& v) {
  const bool hu = u.y() > 0 || (u.y() == 0 && u.x() > 0), hv = v.y() > 0 || (v.y() == 0 && v.x() > 0);
  if (hu != hv) return hu;
  const double c = cross(u, v);
  if (c != 0) return c > 0;
  return u.squaredNorm() < v.squaredNorm();
}

/// Symmetric CSR rows of the links (i, j) (each listed once), each row sorted by id with its
/// counter-clockwise order.
Links linksFromPairs(std::span<const Vec2> pos, std::vector<std::pair<int, int>> pairs, int threads) {
  const int n = int(pos.size());
  const long np = long(pairs.size());
  Links links;
  links.offsets.assign(n + 1, 0);
  // Rows counted and filled in parallel (atomic slots): a row's ids arrive in any order, but
  // each row is sorted by id below, so the rows do not depend on the threads.
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long p = 0; p < np; ++p) {
    const auto [i, j] = pairs[std::size_t(p)];
    std::atomic_ref<int>(links.offsets[std::size_t(i) + 1]).fetch_add(1, std::memory_order_relaxed);
    std::atomic_ref<int>(links.offsets[std::size_t(j) + 1]).fetch_add(1, std::memory_order_relaxed);
  }
  for (int i = 0; i < n; ++i) links.offsets[i + 1] += links.offsets[i];
  links.ids.resize(links.offsets[n]);
  links.ccw.resize(links.offsets[n]);
  {
    std::vector<int> fill(links.offsets.begin(), links.offsets.end() - 1);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long p = 0; p < np; ++p) {
      const auto [i, j] = pairs[std::size_t(p)];
      links.ids[std::size_t(std::atomic_ref<int>(fill[std::size_t(i)]).fetch_add(1, std::memory_order_relaxed))] = j;
      links.ids[std::size_t(std::atomic_ref<int>(fill[std::size_t(j)]).fetch_add(1, std::memory_order_relaxed))] = i;
    }
  }
  pairs = {};
#pragma omp parallel for schedule(dynamic, 256) num_threads(threads)
  for (int i = 0; i < n; ++i) {
    const int b = links.offsets[i], m = links.offsets[i + 1] - b;
    std::sort(links.ids.begin() + b, links.ids.begin() + b + m);
    for (int k = 0; k < m; ++k) links.ccw[b + k] = k;
    std::sort(links.ccw.begin() + b, links.ccw.begin() + b + m,
              [&](int x, int y) { return ccwLess(pos[links.ids[b + x]] - pos[i], pos[links.ids[b + y]] - pos[i]); });
  }
  return links;
}

/// Step 1 (paper §4.1): the links, adjacency pairs of used nodes inside the domain (not
/// leaving a boundary node's angle, not crossing a boundary edge), plus every boundary edge;
/// rows sorted by id, with their counter-clockwise order.
Links buildLinks(const PlacementResult& placement, const std::vector<char>& used, int threads, ConnectStats& st) {
  const auto& pos = placement.nodes.positions;
  const int n = int(pos.size());
  std::vector<int> prevB(n, -1), nextB(n, -1);
  for (const auto& e : placement.boundaryEdges) {
    nextB[e.a] = e.b;
    prevB[e.b] = e.a;
  }
  const BoundaryGrid grid(pos, placement.boundaryEdges);
  const auto inSector = [&](int b, int q) {  // direction b→q inside the domain's angle at boundary node b
    if (q == nextB[b] || q == prevB[b]) return true;
    const Vec2 &P = pos[prevB[b]], &B = pos[b], &N = pos[nextB[b]];
    const bool left1 = orient2d(B, N, pos[q]) > 0, left2 = orient2d(P, B, pos[q]) > 0;
    const int turn = orient2d(P, B, N);
    return turn > 0 ? (left1 && left2) : turn < 0 ? (left1 || left2) : left1;
  };
  const auto& adj = placement.adjacency;
  // The links (i, j), j > i, decided in parallel in blocks of kBlockNodes consecutive i, each
  // block's list its own, so the lists concatenated run in i order for any thread count. The
  // blocks are dealt out dynamically: the boundary nodes come first and cost the most (their
  // links meet the boundary grid's crowded cells), a static split gave them all to one thread.
  constexpr int kBlockNodes = 1024;
  std::vector<std::vector<std::pair<int, int>>> perBlock(std::size_t((n + kBlockNodes - 1) / kBlockNodes));
  ParallelFailure failure;  // push_back may throw: rethrown after the region
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int block = 0; block < int(perBlock.size()); ++block) {
    auto& out = perBlock[std::size_t(block)];
    for (int i = block * kBlockNodes; i < std::min(n, (block + 1) * kBlockNodes); ++i)
      failure.run(i, [&] {
        if (!used[i]) return;
        for (int j : adj.neighbours(i)) {
          // Each pair is decided once, from its smaller node, and linked both ways below: the
          // tests (boundary-grid walk, sectors) need not give the same answer from both ends in
          // floating point, and links must be symmetric (markDead writes both directions).
          if (j <= i || !used[j]) continue;
          const bool boundaryLink = (nextB[i] == j || prevB[i] == j);
          if (!boundaryLink) {
            if (nextB[i] >= 0 && !inSector(i, j)) continue;
            if (nextB[j] >= 0 && !inSector(j, i)) continue;
            if (grid.crosses(i, j)) continue;
          }
          out.emplace_back(i, j);
        }
      });
  }
  failure.rethrow();
  std::vector<std::pair<int, int>> pairs;
  std::size_t total = 0;
  for (const auto& v : perBlock) total += v.size();
  pairs.reserve(total + placement.boundaryEdges.size());
  for (auto& v : perBlock) {
    pairs.insert(pairs.end(), v.begin(), v.end());
    v = {};
  }
  // Boundary edges are links even if the adjacency radius missed them.
  std::vector<int> upper(std::size_t(n) + 1, 0);  // pairs[upper[i] ..) start with i
  for (const auto& pr : pairs) ++upper[std::size_t(pr.first) + 1];
  for (int i = 0; i < n; ++i) upper[std::size_t(i) + 1] += upper[std::size_t(i)];
  const std::size_t found = pairs.size();
  for (const auto& e : placement.boundaryEdges) {
    const int lo = std::min(e.a, e.b), hi = std::max(e.a, e.b);
    const auto first = pairs.begin() + upper[std::size_t(lo)], last = pairs.begin() + upper[std::size_t(lo) + 1];
    const bool listed = std::any_of(first, last, [&](const std::pair<int, int>& pr) { return pr.second == hi; }) ||
                        std::find(pairs.begin() + std::ptrdiff_t(found), pairs.end(), std::pair{lo, hi}) != pairs.end();
    if (!listed) pairs.emplace_back(lo, hi);
  }
  Links links = linksFromPairs(pos, std::move(pairs), threads);
  links.alive.assign(links.ids.size(), 1);
  st.links = long(links.ids.size() / 2);
  return links;
}

/// Step 2: deletes the links to non-satellite nodes (eq. 12), in rounds until nothing changes.
void deleteNonSatellites(const PlacementResult& placement, Links& links, int threads, ConnectStats& st) {
  const auto& pos = placement.nodes.positions;
  const auto& met = placement.metrics;
  const int n = int(pos.size());
  std::vector<std::uint8_t> kill(links.ids.size(), 0);
  const auto markDead = [&](int i, int j) {
    for (const int e : {links.find(i, j), links.find(j, i)})
      if (e >= 0) std::atomic_ref<std::uint8_t>(kill[std::size_t(e)]).store(1, std::memory_order_relaxed);
  };
  for (int round = 0; round < 50; ++round) {
    long tests = 0, crossings = 0;
    ParallelFailure failure;  // liveRing allocates: rethrown after the region
#pragma omp parallel num_threads(threads) reduction(+ : tests, crossings)
    {
      std::vector<int> ring;
#pragma omp for schedule(dynamic, 256)
      for (int p = 0; p < n; ++p)
        failure.run(p, [&] {
          links.liveRing(p, ring);
          const int m = int(ring.size());
          if (m < 3) return;
          for (int j = 0; j < m; ++j) {
            const int y = ring[(j + m - 1) % m], z = ring[j], w = ring[(j + 1) % m];
            if (y == w || !links.linked(y, w)) continue;
            ++tests;
            if (!properCross(pos[p], pos[z], pos[y], pos[w])) continue;
            ++crossings;
            const Metric2 mAvg = 0.25 * (met[p] + met[z] + met[y] + met[w]);
            if (swapCriterion(pos[p], pos[z], pos[y], pos[w], mAvg))
              markDead(p, z);
            else
              markDead(y, w);
          }
        });
    }
    failure.rethrow();
    st.intersectionTests += tests;
    st.crossingsFound += crossings;
    long deleted = 0;
    const long nl = long(kill.size());
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : deleted)
    for (long e = 0; e < nl; ++e)
      if (kill[std::size_t(e)] && links.alive[std::size_t(e)]) {
        links.alive[std::size_t(e)] = 0;
        ++deleted;
      }
    st.deletedEdges += deleted / 2;
    st.deletionRounds = round + 1;
    if (deleted == 0) break;
  }
}

/// Step 3: the consistent triangles, (p, s, t) with s, t consecutive in p's ring, listed once
/// (p the smallest id), present in the rings of s and t as well; sorted.
std::vector<std::array<int, 3>> consistentTriangles(std::span<const Vec2> pos, const Links& links, int threads) {
  const int n = int(pos.size());
  std::vector<std::vector<std::array<int, 3>>> perThread(threads);
  ParallelFailure failure;  // liveRing and push_back allocate: rethrown after the region
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> ring, other;
    auto& out = perThread[omp_get_thread_num()];
    const auto follows = [&](int c, int a, int b) {  // in c's ring, b comes right after a
      links.liveRing(c, other);
      const int m = int(other.size());
      for (int k = 0; k < m; ++k)
        if (other[k] == a) return other[(k + 1) % m] == b;
      return false;
    };
#pragma omp for schedule(static)
    for (int p = 0; p < n; ++p)
      failure.run(p, [&] {
        links.liveRing(p, ring);
        const int m = int(ring.size());
        if (m < 2) return;
        const std::size_t first = out.size();
        for (int k = 0; k < m; ++k) {
          const int s = ring[k], t = ring[(k + 1) % m];
          if (s < p || t < p || s == t || !links.linked(s, t)) continue;
          if (orient2d(pos[p], pos[s], pos[t]) <= 0) continue;
          if (follows(s, t, p) && follows(t, p, s)) out.push_back({p, s, t});
        }
        std::sort(out.begin() + std::ptrdiff_t(first), out.end());  // p's few, in order
      });
  }
  failure.rethrow();
  // schedule(static) hands the threads consecutive ranges of p in thread order: the
  // concatenation is sorted already (checked; sorted in full otherwise).
  std::vector<std::array<int, 3>> consistent;
  std::size_t total = 0;
  for (const auto& v : perThread) total += v.size();
  consistent.reserve(total);
  for (auto& v : perThread) {
    consistent.insert(consistent.end(), v.begin(), v.end());
    v = {};
  }
  if (!std::is_sorted(consistent.begin(), consistent.end())) std::sort(consistent.begin(), consistent.end());
  return consistent;
}

/// Steps 1–3 (paper §4.1) over the nodes with used[i] set: links, eq. (12) deletions, and the
/// consistent triangles (sorted, smallest id first). Fills the local-mesh statistics.
std::vector<std::array<int, 3>> localMeshes(const PlacementResult& placement, const std::vector<char>& used,
                                            int threads, ConnectStats& st) {
  st.links = st.intersectionTests = st.crossingsFound = st.deletedEdges = 0;
  st.deletionRounds = 0;
  const Stopwatch watch;
  Links links = buildLinks(placement, used, threads, st);
  deleteNonSatellites(placement, links, threads, st);
  std::vector<std::array<int, 3>> consistent = consistentTriangles(placement.nodes.positions, links, threads);
  st.consistentTriangles = long(consistent.size());
  st.secondsLocalMeshes = watch.seconds();
  return consistent;
}

/// A directed half-edge a→x of triangle t, keyed by its undirected edge (lo, hi).
struct Half {
  int lo, hi, a, t;
  bool operator<(const Half& o) const {
    return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : a != o.a ? a < o.a : t < o.t;
  }
};

/// The half-edges of the triangles not skipped, in Half order: counting sort on lo, then each
/// vertex's few sorted on their own.
std::vector<Half> halfEdges(int n, const std::vector<std::array<int, 3>>& tris, const std::vector<char>* skip) {
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (int t = 0; t < int(tris.size()); ++t)
    if (!skip || !(*skip)[std::size_t(t)])
      for (int k = 0; k < 3; ++k)
        ++start[std::size_t(std::min(tris[std::size_t(t)][k], tris[std::size_t(t)][(k + 1) % 3])) + 1];
  for (int v = 0; v < n; ++v) start[std::size_t(v) + 1] += start[std::size_t(v)];
  std::vector<Half> h(static_cast<std::size_t>(start[std::size_t(n)]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int t = 0; t < int(tris.size()); ++t) {
    if (skip && (*skip)[std::size_t(t)]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = tris[std::size_t(t)][k], b = tris[std::size_t(t)][(k + 1) % 3];
      h[std::size_t(fill[std::size_t(std::min(a, b))]++)] = {std::min(a, b), std::max(a, b), a, t};
    }
  }
  for (int v = 0; v < n; ++v) std::sort(h.begin() + start[std::size_t(v)], h.begin() + start[std::size_t(v) + 1]);
  return h;
}

/// The boundary edges a→b (domain on the left), sorted, for lookups.
struct BoundaryIndex {
  std::vector<std::array<int, 2>> edges;
  explicit BoundaryIndex(std::span<const BoundaryEdge> boundary) {
    for (const auto& e : boundary) edges.push_back({e.a, e.b});
    std::sort(edges.begin(), edges.end());
  }
  /// Index of the boundary edge a→b, or −1.
  int find(int a, int b) const {
    const auto it = std::lower_bound(edges.begin(), edges.end(), std::array<int, 2>{a, b});
    return it != edges.end() && *it == std::array<int, 2>{a, b} ? int(it - edges.begin()) : -1;
  }
};

/// Repair step 1: the vertices of the union's defects, an edge in one triangle that is not a
/// boundary edge on its inner side, in three or more, or in two with the same orientation; a
/// boundary edge in none. Empty when there is none.
std::vector<char> defectVertices(int n, const std::vector<std::array<int, 3>>& consistent, const BoundaryIndex& bnd) {
  std::vector<char> mark(static_cast<std::size_t>(n), 0);
  bool any = false;
  auto markEdge = [&](int a, int b) {
    mark[std::size_t(a)] = mark[std::size_t(b)] = 1;
    any = true;
  };
  std::vector<char> covered(bnd.edges.size(), 0);
  const auto h = halfEdges(n, consistent, nullptr);
  for (std::size_t i = 0; i < h.size();) {
    std::size_t j = i;
    while (j < h.size() && h[j].lo == h[i].lo && h[j].hi == h[i].hi) ++j;
    const std::size_t count = j - i;
    const int a = h[i].a, b = a == h[i].lo ? h[i].hi : h[i].lo;  // the first half-edge runs a→b
    if (count == 1) {
      const int e = bnd.find(a, b);
      if (e >= 0)
        covered[std::size_t(e)] = 1;
      else
        markEdge(a, b);
    } else if (count > 2 || h[i].a == h[i + 1].a || bnd.find(h[i].lo, h[i].hi) >= 0 ||
               bnd.find(h[i].hi, h[i].lo) >= 0) {
      markEdge(h[i].lo, h[i].hi);
    }
    i = j;
  }
  for (std::size_t k = 0; k < bnd.edges.size(); ++k)
    if (!covered[k]) markEdge(bnd.edges[k][0], bnd.edges[k][1]);
  if (!any) mark.clear();
  return mark;
}

/// Repair step 2: the triangles touching marked vertices, grown by three rings in all.
std::vector<char> removedAround(const std::vector<std::array<int, 3>>& consistent, std::vector<char> mark) {
  const int nt = int(consistent.size());
  std::vector<char> removed(static_cast<std::size_t>(nt), 0);
  for (int ring = 0; ring < 3; ++ring) {
    for (int t = 0; t < nt; ++t)
      for (int v : consistent[std::size_t(t)]) removed[std::size_t(t)] |= mark[std::size_t(v)];
    for (int t = 0; t < nt; ++t)
      if (removed[std::size_t(t)])
        for (int v : consistent[std::size_t(t)]) mark[std::size_t(v)] = 1;
  }
  return removed;
}

/// The open region left by the removed triangles: its boundary (open side on the left), in
/// global ids, and its points, numbered locally (globalOf: local → global).
struct OpenRegion {
  std::vector<std::array<int, 2>> edges;
  std::vector<int> localOf, globalOf;
};

/// Repair step 3; false when the kept triangles overlap.
bool openRegion(int n, const std::vector<std::array<int, 3>>& consistent, const std::vector<char>& removed,
                const BoundaryIndex& bnd, OpenRegion& region) {
  const int nt = int(consistent.size());
  std::vector<char> inKept(static_cast<std::size_t>(n), 0);
  for (int t = 0; t < nt; ++t)
    if (!removed[std::size_t(t)])
      for (int v : consistent[std::size_t(t)]) inKept[std::size_t(v)] = 1;
  std::vector<char> covered(bnd.edges.size(), 0);
  const auto h = halfEdges(n, consistent, &removed);
  for (std::size_t i = 0; i < h.size();) {
    std::size_t j = i;
    while (j < h.size() && h[j].lo == h[i].lo && h[j].hi == h[i].hi) ++j;
    if (j - i > 2 || (j - i == 2 && h[i].a == h[i + 1].a)) return false;  // kept triangles overlap
    if (j - i == 1) {
      const int a = h[i].a, b = a == h[i].lo ? h[i].hi : h[i].lo;
      const int e = bnd.find(a, b);
      if (e >= 0)
        covered[std::size_t(e)] = 1;
      else
        region.edges.push_back({b, a});
    }
    i = j;
  }
  for (std::size_t k = 0; k < bnd.edges.size(); ++k)
    if (!covered[k]) region.edges.push_back(bnd.edges[k]);
  region.localOf.assign(static_cast<std::size_t>(n), -1);
  auto take = [&](int v) {
    if (region.localOf[std::size_t(v)] < 0) {
      region.localOf[std::size_t(v)] = int(region.globalOf.size());
      region.globalOf.push_back(v);
    }
  };
  for (int v = 0; v < n; ++v)
    if (!inKept[std::size_t(v)]) take(v);
  for (const auto& e : region.edges) {
    take(e[0]);
    take(e[1]);
  }
  return true;
}

/// Repair step 4: triangulates the open region from its own points (Delaunay, its boundary
/// locked, inside by orientation, eq. (12) swaps); global ids. False when its boundary cannot
/// be recovered or is not a closed polygon.
bool triangulateOpen(const PlacementResult& placement, const OpenRegion& region, std::vector<std::array<int, 3>>& fresh,
                     long& swaps) {
  const auto& pos = placement.nodes.positions;
  const auto& met = placement.metrics;
  const auto& globalOf = region.globalOf;
  std::vector<Vec2> sub(globalOf.size());
  for (std::size_t k = 0; k < globalOf.size(); ++k) sub[k] = pos[std::size_t(globalOf[k])];
  try {
    Triangulation tri(sub);
    std::vector<std::array<int, 2>> local;
    for (const auto& e : region.edges) {
      local.push_back({region.localOf[std::size_t(e[0])], region.localOf[std::size_t(e[1])]});
      if (!tri.recoverEdge(local.back()[0], local.back()[1])) return false;
    }
    tri.classify(local);
    const auto criterion = [&](int x, int z, int y, int w) {
      const int X = globalOf[std::size_t(x)], Z = globalOf[std::size_t(z)], Y = globalOf[std::size_t(y)],
                W = globalOf[std::size_t(w)];
      return swapCriterion(pos[X], pos[Z], pos[Y], pos[W], 0.25 * (met[X] + met[Z] + met[Y] + met[W]));
    };
    bool capHit = false;
    swaps = tri.flipWhile(criterion, 20L * 3 * long(sub.size()) + 1000, capHit);
    for (int t = 0; t < tri.numTriangleSlots(); ++t) {
      if (!tri.inside(t)) continue;
      auto v = tri.triangle(t);
      for (int& x : v) x = globalOf[std::size_t(x)];
      fresh.push_back(v);
    }
  } catch (const Error&) {
    return false;  // an open region that is not a closed polygon: leave it to the scaffold
  }
  return true;
}

/// Repair step 5: the mesh of the given triangles, nodes in none dropped; false when a
/// boundary node is dropped or the mesh does not validate against `area`.
bool meshOfTriangles(const PlacementResult& placement, const std::vector<std::array<int, 3>>& tris, double area,
                     Mesh2& mesh, std::vector<int>& nodeOfVertex) {
  const auto& pos = placement.nodes.positions;
  const int n = int(pos.size());
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  for (const auto& t : tris)
    for (int v : t) used[std::size_t(v)] = 1;
  std::vector<int> vertexOf(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    if (!used[std::size_t(i)]) continue;
    vertexOf[std::size_t(i)] = int(nodeOfVertex.size());
    nodeOfVertex.push_back(i);
    mesh.vertices.push_back(pos[std::size_t(i)]);
  }
  for (auto t : tris) {
    for (int& x : t) x = vertexOf[std::size_t(x)];
    mesh.triangles.push_back(t);
  }
  for (const auto& e : placement.boundaryEdges) {
    if (vertexOf[std::size_t(e.a)] < 0 || vertexOf[std::size_t(e.b)] < 0) return false;
    mesh.boundaryEdges.push_back({vertexOf[std::size_t(e.a)], vertexOf[std::size_t(e.b)], e.ref});
  }
  return mesh.validate(area, 1e-9).ok;
}

/// Local repair (the usual case: a few near-cocircular spots in a valid union). The triangles
/// touching a defect's vertices (step 1) are removed with two more rings around them (step 2),
/// and what is open (those holes and any gap, step 3) is triangulated again from its own
/// points only (step 4). Fills `result` and returns true when the union of kept and new
/// triangles validates against `area` (step 5); false (nothing to trust) else.
bool repairLocally(const PlacementResult& placement, const std::vector<std::array<int, 3>>& consistent, double area,
                   ConnectResult& result) {
  const int n = int(placement.nodes.positions.size());
  const BoundaryIndex bnd(placement.boundaryEdges);
  std::vector<char> mark = defectVertices(n, consistent, bnd);
  if (mark.empty()) return false;  // combinatorially sound: the failure was the area; leave it to the scaffold
  const std::vector<char> removed = removedAround(consistent, std::move(mark));
  OpenRegion region;
  if (!openRegion(n, consistent, removed, bnd, region) || region.globalOf.size() < 3) return false;
  std::vector<std::array<int, 3>> fresh;
  long swaps = 0;
  if (!triangulateOpen(placement, region, fresh, swaps)) return false;
  std::vector<std::array<int, 3>> tris;
  tris.reserve(consistent.size() + fresh.size());
  for (std::size_t t = 0; t < consistent.size(); ++t)
    if (!removed[t]) tris.push_back(consistent[t]);
  tris.insert(tris.end(), fresh.begin(), fresh.end());
  Mesh2 mesh;
  std::vector<int> nodeOfVertex;
  if (!meshOfTriangles(placement, tris, area, mesh, nodeOfVertex)) return false;
  result.mesh = std::move(mesh);
  result.nodeOfVertex = std::move(nodeOfVertex);
  result.stats.droppedNodes = n - int(result.nodeOfVertex.size());
  result.stats.repairedTriangles = 0;  // fresh triangles that are not consistent ones (min vertex first, sorted)
  for (auto key : fresh) {
    std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    result.stats.repairedTriangles += !std::binary_search(consistent.begin(), consistent.end(), key);
  }
  result.stats.swaps += swaps;
  result.validated = true;
  return true;
}

/// The area the mesh must cover (as meshDomain checks it): the polygon through the boundary
/// nodes when a loop is smooth (curved), the domain's area else.
double areaToCover(const PlacementResult& placement, const Domain& domain) {
  bool smooth = false;
  for (const auto& loop : domain.loops()) smooth = smooth || loop.smooth;
  if (!smooth) return domain.area();
  double area = 0;
  const auto& pos = placement.nodes.positions;
  const Vec2 o = placement.boundaryEdges.empty() ? Vec2(0, 0) : pos[placement.boundaryEdges[0].a];
  for (const auto& e : placement.boundaryEdges) area += 0.5 * cross(pos[e.a] - o, pos[e.b] - o);  // exact far away
  return area;
}

/// Fallback: a constrained Delaunay scaffold of all nodes (inside/outside by the boundary
/// edges); the local meshes again without the nodes outside; eq. (12) swaps, every consistent
/// edge recovered, swaps again; the inside triangles are the mesh.
void scaffoldMesh(const PlacementResult& placement, std::vector<std::array<int, 3>> consistent, int threads,
                  ConnectResult& result) {
  const auto& pos = placement.nodes.positions;
  const auto& met = placement.metrics;
  const int n = int(pos.size());
  ConnectStats& st = result.stats;
  Stopwatch watch;
  Triangulation tri(pos);
  std::vector<std::array<int, 2>> boundary;
  boundary.reserve(placement.boundaryEdges.size());
  for (const auto& e : placement.boundaryEdges) {
    if (!tri.recoverEdge(e.a, e.b)) {
      throw Error("connect: boundary edge between nodes " + std::to_string(e.a) + " and " + std::to_string(e.b) +
                  " cannot be made a mesh edge (another node lies on it)");
    }
    boundary.push_back({e.a, e.b});
  }
  tri.classify(boundary);
  std::vector<char> used(n, 0);
  for (int t = 0; t < tri.numTriangleSlots(); ++t)
    if (tri.inside(t))
      for (int v : tri.triangle(t)) used[v] = 1;
  st.secondsRepair += watch.seconds();

  // Nodes outside the boundary polygon: redo the local meshes without them.
  if (std::count(used.begin(), used.end(), 0) > 0) consistent = localMeshes(placement, used, threads, st);

  // 4. Repair on the scaffold: eq. (12) swaps, keep every consistent edge, swaps again.
  watch.restart();
  const auto criterion = [&](int x, int z, int y, int w) {
    return swapCriterion(pos[x], pos[z], pos[y], pos[w], 0.25 * (met[x] + met[z] + met[y] + met[w]));
  };
  const long maxSwaps = 20L * 3 * n + 1000;
  bool capHit = false;
  st.swaps += tri.flipWhile(criterion, maxSwaps, capHit);
  st.swapCapHit = capHit;
  std::vector<std::array<int, 2>> keep;
  keep.reserve(3 * consistent.size());
  for (const auto& t : consistent)
    for (int k = 0; k < 3; ++k) keep.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  std::sort(keep.begin(), keep.end());
  keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
  for (const auto& [a, b] : keep)
    if (!tri.recoverEdge(a, b)) ++st.failedRecoveries;
  st.swaps += tri.flipWhile(criterion, maxSwaps, capHit);
  st.swapCapHit = st.swapCapHit || capHit;

  // Output: inside triangles, nodes outside the boundary polygon dropped.
  std::vector<int> vertexOf(n, -1);
  for (int i = 0; i < n; ++i) {
    if (!used[i]) {
      ++st.droppedNodes;
      continue;
    }
    vertexOf[i] = int(result.nodeOfVertex.size());
    result.nodeOfVertex.push_back(i);
    result.mesh.vertices.push_back(pos[i]);
  }
  for (int t = 0; t < tri.numTriangleSlots(); ++t) {
    if (!tri.inside(t)) continue;
    auto v = tri.triangle(t);
    std::array<int, 3> key = v;
    std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    if (!std::binary_search(consistent.begin(), consistent.end(), key)) ++st.repairedTriangles;
    for (int& x : v) x = vertexOf[x];
    result.mesh.triangles.push_back(v);
  }
  for (const auto& e : placement.boundaryEdges)
    result.mesh.boundaryEdges.push_back({vertexOf[e.a], vertexOf[e.b], e.ref});
  st.secondsRepair += watch.seconds();
}

}  // namespace

ConnectResult connect(const PlacementResult& placement, const Domain& domain, const ConnectOptions& options) {
  const auto& pos = placement.nodes.positions;
  const int n = int(pos.size());
  ABLMG_REQUIRE(int(placement.metrics.size()) == n && placement.adjacency.size() == n,
                "connect: placement has inconsistent sizes");
  ABLMG_REQUIRE(!placement.boundaryEdges.empty(), "connect: no boundary edges");
  // Small node sets run on the calling thread (parallel_threshold.hpp); same result either way.
  const int threads = n < kMinParallelItems ? 1 : options.threads > 0 ? options.threads : omp_get_max_threads();
  ConnectResult result;
  ConnectStats& st = result.stats;

  // Steps 1–3 over all nodes. When the union of the local meshes is already a valid mesh of
  // the polygon through the boundary nodes (the usual case), it is the mesh, as in the paper.
  std::vector<std::array<int, 3>> consistent = localMeshes(placement, std::vector<char>(n, 1), threads, st);
  const Stopwatch validateWatch;
  Mesh2 un;
  un.vertices = pos;
  un.triangles = std::move(consistent);  // given back below when the union needs repair
  un.boundaryEdges = placement.boundaryEdges;
  const double area = areaToCover(placement, domain);
  const bool ok = un.validate(area, 1e-9).ok;
  result.secondsValidate = validateWatch.seconds();
  if (ok) {
    result.validated = true;
    result.mesh = std::move(un);
    result.nodeOfVertex.resize(n);
    std::iota(result.nodeOfVertex.begin(), result.nodeOfVertex.end(), 0);
    return result;
  }
  consistent = std::move(un.triangles);
  const Stopwatch repairWatch;
  const bool repaired = options.localRepair && repairLocally(placement, consistent, area, result);
  st.secondsRepair += repairWatch.seconds();
  if (repaired) {
    st.localRepair = true;
    return result;
  }
  scaffoldMesh(placement, std::move(consistent), threads, result);
  return result;
}

}  // namespace ablmg::mesher
