#include "ablmg/core/mesh2.hpp"

#include "ablmg/core/counting_sort.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/core/predicates.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <sstream>

namespace ablmg {
namespace {

/// Directed half-edge keyed for sorting: (min, max, direction flag, triangle).
struct HalfEdge {
  int lo, hi;
  int forward;  ///< 1 if the triangle runs lo→hi, 0 if hi→lo
  int tri;
  bool operator<(const HalfEdge& o) const {
    if (lo != o.lo) return lo < o.lo;
    if (hi != o.hi) return hi < o.hi;
    if (forward != o.forward) return forward < o.forward;
    return tri < o.tri;
  }
};

/// Triangles per chunk of the parallel loops below: sums over chunks of a fixed size, added
/// in chunk order, are the same for any thread count.
constexpr int kChunk = 1 << 14;
/// Below this many triangles the loops run on one thread.
constexpr int kParallelTriangles = 1 << 15;

/// All half-edges in HalfEdge order, and start[v] = the first with lo = v (start[nv] = the
/// first whose lo is out of range, start[nv + 1] = the end): a counting sort on `lo`
/// (O(V + T)), then each bucket (a vertex's few edges) sorted on its own, so the result does
/// not depend on the threads. Vertex ids out of range go in one last bucket, sorted in full
/// (validate() reports them; no out-of-bounds access on the way). `h` views `store`, which is
/// left uninitialised until the fill: its pages are first touched by the threads that fill them.
struct HalfEdges {
  std::unique_ptr<HalfEdge[]> store;
  std::span<HalfEdge> h;
  std::vector<int> start;
};

/// One bucket's half-edges (all with the same lo, in range) in HalfEdge order. Within a
/// bucket that order is the one of (hi, forward, tri), which packs into one integer (hi and
/// tri are non-negative ints): insertion sort on it for the usual few (a vertex's 4–8),
/// std::sort on it for a crowded vertex. The same order as sorting on operator<.
void sortBucket(HalfEdge* first, HalfEdge* last) {
  const auto key = [](const HalfEdge& e) {
    return (std::uint64_t(std::uint32_t(e.hi)) << 32) | (std::uint64_t(e.forward) << 31) | std::uint64_t(e.tri);
  };
  if (last - first > 16) {
    std::sort(first, last, [&](const HalfEdge& a, const HalfEdge& b) { return key(a) < key(b); });
    return;
  }
  for (HalfEdge* i = first + (first != last); i < last; ++i) {
    const HalfEdge x = *i;
    const std::uint64_t kx = key(x);
    HalfEdge* j = i;
    for (; j > first && key(*(j - 1)) > kx; --j) *j = *(j - 1);
    *j = x;
  }
}

HalfEdges halfEdges(const Mesh2& m) {
  const int nv = m.numVertices(), nt = m.numTriangles();
  const std::size_t buckets = std::size_t(nv) + 1;
  HalfEdges r;
  auto& start = r.start;
  start.assign(buckets + 1, 0);
  r.store.reset(new HalfEdge[3 * std::size_t(nt)]);
  r.h = {r.store.get(), 3 * std::size_t(nt)};
  auto bucket = [nv](int lo) { return std::size_t(lo >= 0 && lo < nv ? lo : nv); };
  const auto lo = [&](int t, int k) {
    const auto& tr = m.triangles[std::size_t(t)];
    return std::min(tr[k], tr[(k + 1) % 3]);
  };
  const bool parallel = nt >= kParallelTriangles;
  const int threads = parallel ? omp_get_max_threads() : 1;
  // Per thread: its count per bucket, then its first slot in each bucket. Both loops over the
  // triangles are schedule(static) in one region, so a thread gets the same range in both.
  std::vector<int> slot(std::size_t(threads) * buckets, 0);
#pragma omp parallel num_threads(threads) if (parallel)
  {
    int* mine = slot.data() + std::size_t(omp_get_thread_num()) * buckets;
#pragma omp for schedule(static)
    for (int t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) ++mine[bucket(lo(t, k))];
    countsToSlots(slot, start);
#pragma omp for schedule(static)
    for (int t = 0; t < nt; ++t) {
      const auto& tr = m.triangles[std::size_t(t)];
      for (int k = 0; k < 3; ++k) {
        const int a = tr[k], b = tr[(k + 1) % 3];
        r.h[std::size_t(mine[bucket(std::min(a, b))]++)] = {std::min(a, b), std::max(a, b), a < b ? 1 : 0, t};
      }
    }
#pragma omp for schedule(static, 4096)
    for (int v = 0; v < nv; ++v) sortBucket(r.h.data() + start[std::size_t(v)], r.h.data() + start[std::size_t(v) + 1]);
  }
  std::sort(r.h.begin() + start[std::size_t(nv)], r.h.end());  // ids out of range: the whole key
  return r;
}

/// validate()'s fast path: true when every triangle's vertex ids are in range and it is
/// counter-clockwise (orient2d > 0), every vertex is used, and then `area` = the sum of the
/// triangle areas (chunk sums in chunk order). False: the serial checks find and name the
/// problem.
bool trianglesLookValid(const Mesh2& m, double& area) {
  const int nv = m.numVertices(), nt = m.numTriangles();
  const int chunks = (nt + kChunk - 1) / kChunk;
  std::vector<double> part(std::size_t(chunks), 0.0);
  std::vector<char> used(std::size_t(nv), 0);
  int bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad) if (nt >= kParallelTriangles)
  for (int c = 0; c < chunks; ++c) {
    double sum = 0;
    for (int t = c * kChunk; t < std::min(nt, (c + 1) * kChunk); ++t) {
      const auto& tr = m.triangles[std::size_t(t)];
      if (std::min({tr[0], tr[1], tr[2]}) < 0 || std::max({tr[0], tr[1], tr[2]}) >= nv) {
        ++bad;
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        char& u = used[std::size_t(tr[k])];
#pragma omp atomic write
        u = 1;
      }
      bad += orient2d(m.vertices[tr[0]], m.vertices[tr[1]], m.vertices[tr[2]]) <= 0;
      sum += m.triangleArea(t);
    }
    part[std::size_t(c)] = sum;
  }
  if (bad > 0 || std::find(used.begin(), used.end(), 0) != used.end()) return false;
  area = 0;
  for (const double a : part) area += a;
  return true;
}

}  // namespace

double Mesh2::triangleArea(int t) const {
  const auto& tr = triangles[t];
  return 0.5 * signedArea2(vertices[tr[0]], vertices[tr[1]], vertices[tr[2]]);
}

double Mesh2::area() const {
  double a = 0;
  for (int t = 0; t < numTriangles(); ++t) a += triangleArea(t);
  return a;
}

namespace {

using EdgeKey = std::array<int, 2>;

/// The checks of Mesh2::validate, run in order. Each counts what it finds in `r` and keeps the
/// first problem's text; a check that returns false found input the later checks cannot read
/// (an id out of range, a non-finite coordinate).
class MeshChecks {
 public:
  MeshChecks(const Mesh2& m, int idBase) : m_(m), idBase_(idBase), nv_(m.numVertices()) {}
  MeshValidation r;

  /// Every coordinate is finite and there is at least one triangle.
  bool vertices() {
    for (int v = 0; v < nv_; ++v)
      if (!std::isfinite(m_.vertices[v].x()) || !std::isfinite(m_.vertices[v].y())) {
        problem("vertex " + id(v) + " has a non-finite coordinate");
        return false;
      }
    if (m_.triangles.empty()) {
      problem("the mesh has no triangles");
      return false;
    }
    return true;
  }

  /// Vertex ids in range, positive orientation (exact predicate), every vertex used; sums the area.
  bool triangles() {
    if (trianglesLookValid(m_, r.area)) return true;  // in parallel; the serial pass names a problem
    std::vector<char> used(nv_, 0);
    for (int t = 0; t < m_.numTriangles(); ++t) {
      const auto& tr = m_.triangles[t];
      for (int k = 0; k < 3; ++k)
        if (tr[k] < 0 || tr[k] >= nv_) {
          problem("triangle " + id(t) + " refers to vertex " + id(tr[k]) + " out of range");
          return false;
        }
      for (int k = 0; k < 3; ++k) used[tr[k]] = 1;
      if (orient2d(m_.vertices[tr[0]], m_.vertices[tr[1]], m_.vertices[tr[2]]) <= 0) {
        ++r.invertedTriangles;
        std::ostringstream os;
        os << "triangle " << id(t) << " (" << id(tr[0]) << ", " << id(tr[1]) << ", " << id(tr[2])
           << ") is inverted or degenerate";
        problem(os.str());
      }
      r.area += m_.triangleArea(t);
    }
    for (int v = 0; v < nv_; ++v)
      if (!used[v]) {
        ++r.unusedVertices;
        problem("vertex " + id(v) + " is used by no triangle");
      }
    return true;
  }

  /// `list` as sorted keys (directed (a, b), or undirected (min, max)), each in range, not
  /// degenerate, listed once; `what` names the list in the messages.
  bool edgeKeys(const std::vector<BoundaryEdge>& list, const char* what, bool directed, std::vector<EdgeKey>& keys) {
    keys.reserve(list.size());
    for (const auto& e : list) {
      if (e.a < 0 || e.a >= nv_ || e.b < 0 || e.b >= nv_ || e.a == e.b) {
        problem(std::string(what) + " (" + id(e.a) + ", " + id(e.b) + ") is out of range or degenerate");
        return false;
      }
      keys.push_back(directed ? EdgeKey{e.a, e.b} : EdgeKey{std::min(e.a, e.b), std::max(e.a, e.b)});
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 1; i < keys.size(); ++i)
      if (keys[i] == keys[i - 1])
        problem(std::string(what) + " (" + id(keys[i][0]) + ", " + id(keys[i][1]) + ") is listed twice");
    return true;
  }

  /// Each mesh edge lies in two triangles of opposite orientation (an interface edge where the
  /// subdomain changes) or in one, then it is a boundary edge with the triangle on its left.
  /// Every listed boundary edge and interface edge is met that way.
  void edgeIncidence(const std::vector<EdgeKey>& bnd, const std::vector<EdgeKey>& itf) {
    std::vector<char> bndUsed(bnd.size(), 0), itfUsed(itf.size(), 0);
    const auto refOf = [&](int t) {
      return std::size_t(t) < m_.triangleRefs.size() ? m_.triangleRefs[std::size_t(t)] : 0;
    };
    const HalfEdges he = halfEdges(m_);  // named members, not a structured binding: the
    const auto& h = he.h;                // lambdas below capture them (clang 14)
    // One run of half-edges with the same end points, h[i, j): an interior edge in two
    // triangles of opposite orientation, or a boundary edge in one. `report`: name the problem
    // (serial) or only return false. Each run writes its own bndUsed / itfUsed entries.
    const auto run = [&](std::size_t i, std::size_t j, bool report) {
      const std::size_t count = j - i;
      const auto name = [&] { return "edge (" + id(h[i].lo) + ", " + id(h[i].hi) + ")"; };
      const auto inItf = std::lower_bound(itf.begin(), itf.end(), EdgeKey{h[i].lo, h[i].hi});
      const bool isItf = inItf != itf.end() && *inItf == EdgeKey{h[i].lo, h[i].hi};
      if (isItf) itfUsed[std::size_t(inItf - itf.begin())] = 1;
      if (count == 2 && h[i].forward != h[i + 1].forward) {
        if (isItf || refOf(h[i].tri) == refOf(h[i + 1].tri)) return true;
        if (report)
          problem(name() + " separates subdomains " + std::to_string(refOf(h[i].tri)) + " and " +
                  std::to_string(refOf(h[i + 1].tri)) + " but is not an interface edge");
        return false;
      }
      if (count == 1) {
        if (isItf && !report) return false;
        if (isItf) problem("interface " + name() + " lies in one triangle (a boundary edge, not an interior one)");
        const EdgeKey dir = h[i].forward ? EdgeKey{h[i].lo, h[i].hi} : EdgeKey{h[i].hi, h[i].lo};
        const auto it = std::lower_bound(bnd.begin(), bnd.end(), dir);
        if (it != bnd.end() && *it == dir) {
          bndUsed[std::size_t(it - bnd.begin())] = 1;
          return !isItf;
        }
        if (!report) return false;
        ++r.openEdges;
        problem(name() + " lies in one triangle but is not a boundary edge (a gap or an overlap)");
        return false;
      }
      if (!report) return false;
      ++r.nonManifoldEdges;
      problem(name() + " lies in " + std::to_string(count) + " triangles" +
              (count == 2 ? " with the same orientation" : ""));
      return false;
    };
    const auto runsIn = [&](std::size_t first, std::size_t last, bool report) {
      bool ok = true;
      for (std::size_t i = first; i < last;) {
        std::size_t j = i;
        while (j < last && h[j].lo == h[i].lo && h[j].hi == h[i].hi) ++j;
        ok = run(i, j, report) && ok;
        i = j;
      }
      return ok;
    };
    // In parallel by vertex buckets (a run never crosses one); the serial pass names a problem.
    int bad = 0;
#pragma omp parallel for schedule(static, 4096) reduction(+ : bad) if (m_.numTriangles() >= kParallelTriangles)
    for (int v = 0; v <= nv_; ++v)
      bad += !runsIn(std::size_t(he.start[std::size_t(v)]), std::size_t(he.start[std::size_t(v) + 1]), false);
    if (bad > 0) {
      std::fill(bndUsed.begin(), bndUsed.end(), 0);
      std::fill(itfUsed.begin(), itfUsed.end(), 0);
      runsIn(0, h.size(), true);
    }
    for (std::size_t k = 0; k < bnd.size(); ++k)
      if (!bndUsed[k]) {
        ++r.openEdges;
        problem("boundary edge (" + id(bnd[k][0]) + ", " + id(bnd[k][1]) +
                ") is not the edge of exactly one triangle on its left");
      }
    for (std::size_t k = 0; k < itf.size(); ++k)
      if (!itfUsed[k])
        problem("interface edge (" + id(itf[k][0]) + ", " + id(itf[k][1]) + ") is not an edge of the mesh");
  }

  /// Corners and required vertices in range; required edges and ridges are mesh edges.
  bool features() {
    for (const auto* list : {&m_.corners, &m_.requiredVertices})
      for (int v : *list)
        if (v < 0 || v >= nv_) {
          problem((list == &m_.corners ? "corner " : "required vertex ") + id(v) + " is out of range");
          return false;
        }
    if (m_.requiredEdges.empty() && m_.ridges.empty()) return true;
    const auto all = m_.edges();
    for (const auto* list : {&m_.requiredEdges, &m_.ridges})
      for (const auto& e : *list) {
        const EdgeKey k{std::min(e[0], e[1]), std::max(e[0], e[1])};
        if (!std::binary_search(all.begin(), all.end(), k))
          problem(std::string(list == &m_.ridges ? "ridge" : "required edge") + " (" + id(e[0]) + ", " + id(e[1]) +
                  ") is not an edge of the mesh");
      }
    return true;
  }

  /// The summed area matches `expected` to the relative tolerance.
  void area(double expected, double tolerance) {
    const double rel = std::abs(r.area - expected) / std::abs(expected);
    if (!(rel <= tolerance)) {
      std::ostringstream os;
      os << "mesh area " << r.area << " differs from the domain's " << expected << " (relative " << rel << ")";
      problem(os.str());
    }
  }

 private:
  std::string id(int v) const { return std::to_string(v + idBase_); }
  void problem(const std::string& s) {
    if (r.ok) r.firstProblem = s;
    r.ok = false;
  }
  const Mesh2& m_;
  int idBase_;
  int nv_;
};

}  // namespace

MeshValidation Mesh2::validate(std::optional<double> expectedArea, double areaTolerance, int idBase) const {
  MeshChecks c(*this, idBase);
  std::vector<EdgeKey> bnd, itf;
  if (!c.vertices() || !c.triangles() || !c.edgeKeys(boundaryEdges, "boundary edge", true, bnd) ||
      !c.edgeKeys(interfaceEdges, "interface edge", false, itf))
    return c.r;
  c.edgeIncidence(bnd, itf);
  if (!c.features()) return c.r;
  if (expectedArea) c.area(*expectedArea, areaTolerance);
  return c.r;
}

void Mesh2::requireValid(const std::string& what, std::optional<double> expectedArea, double areaTolerance,
                         int idBase) const {
  const MeshValidation r = validate(expectedArea, areaTolerance, idBase);
  if (!r.ok)
    ABLMG_FAIL(what << ": invalid mesh" << (idBase == 1 ? " (ids from 1, as in the file)" : "") << ": "
                    << r.firstProblem);
}

std::vector<std::array<int, 2>> Mesh2::edges() const {
  std::vector<std::array<int, 2>> e;
  const int nv = numVertices();
  const bool inRange = std::all_of(triangles.begin(), triangles.end(), [nv](const std::array<int, 3>& tr) {
    return std::min({tr[0], tr[1], tr[2]}) >= 0 && std::max({tr[0], tr[1], tr[2]}) < nv;
  });
  if (inRange) {  // from the half-edges (counting sort, O(V + T)): the same order as sorting
    const HalfEdges he = halfEdges(*this);
    const auto& h = he.h;
    e.reserve(h.size() / 2 + 1);
    for (const auto& x : h)
      if (e.empty() || e.back()[0] != x.lo || e.back()[1] != x.hi) e.push_back({x.lo, x.hi});
    return e;
  }
  e.reserve(3 * triangles.size());
  for (const auto& tr : triangles)
    for (int k = 0; k < 3; ++k) e.push_back({std::min(tr[k], tr[(k + 1) % 3]), std::max(tr[k], tr[(k + 1) % 3])});
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  return e;
}

std::vector<std::array<int, 3>> Mesh2::triangleNeighbours() const {
  std::vector<std::array<int, 3>> nb(triangles.size(), {-1, -1, -1});
  const HalfEdges he = halfEdges(*this);
  const auto& h = he.h;
  auto localEdge = [&](int t, int lo, int hi) {
    const auto& tr = triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int a = tr[(k + 1) % 3], b = tr[(k + 2) % 3];  // edge opposite vertex k
      if (std::min(a, b) == lo && std::max(a, b) == hi) return k;
    }
    return -1;
  };
  // By vertex buckets: every write for an edge comes from its own bucket, in the serial order.
  const int nv = numVertices();
#pragma omp parallel for schedule(static, 4096) if (numTriangles() >= kParallelTriangles)
  for (int v = 0; v <= nv; ++v) {
    const std::size_t last = std::size_t(he.start[std::size_t(v) + 1]);
    for (std::size_t i = std::size_t(he.start[std::size_t(v)]); i + 1 < last; ++i)
      if (h[i].lo == h[i + 1].lo && h[i].hi == h[i + 1].hi) {
        nb[h[i].tri][localEdge(h[i].tri, h[i].lo, h[i].hi)] = h[i + 1].tri;
        nb[h[i + 1].tri][localEdge(h[i + 1].tri, h[i].lo, h[i].hi)] = h[i].tri;
      }
  }
  return nb;
}

Mesh2::VertexTriangles Mesh2::vertexTriangles() const {
  VertexTriangles vt;
  vt.offsets.assign(vertices.size() + 1, 0);
  for (const auto& tr : triangles)
    for (int k = 0; k < 3; ++k) ++vt.offsets[tr[k] + 1];
  for (std::size_t v = 0; v < vertices.size(); ++v) vt.offsets[v + 1] += vt.offsets[v];
  vt.ids.resize(vt.offsets.back());
  std::vector<int> fill(vt.offsets.begin(), vt.offsets.end() - 1);
  for (int t = 0; t < numTriangles(); ++t)
    for (int k = 0; k < 3; ++k) vt.ids[fill[triangles[t][k]]++] = t;
  return vt;
}

}  // namespace ablmg
