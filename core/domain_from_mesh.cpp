#include "ablmg/core/domain_from_mesh.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>
#include <vector>

namespace ablmg {
namespace {

/// The boundary as a successor map: next[a] = b for each boundary edge a→b (−1 elsewhere),
/// nextRef[a] = its ref.
struct BoundaryChain {
  std::vector<int> next, nextRef;
};

/// The edges in exactly one triangle, oriented as in it, in triangle order, with the refs of
/// the file's Edges (a repeated edge takes its last ref; 1 where there is none). Undirected
/// edges are grouped by their smaller vertex (counting sort, O(n), no std::map).
BoundaryChain chainByCounting(const Mesh2& mesh, const std::string& name) {
  const int nv = mesh.numVertices();
  const auto sz = [](int i) { return static_cast<std::size_t>(i); };
  std::vector<int> rowStart(sz(nv) + 1, 0), his(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++rowStart[sz(std::min(t[k], t[(k + 1) % 3])) + 1];
  for (int v = 0; v < nv; ++v) rowStart[sz(v) + 1] += rowStart[sz(v)];
  {
    std::vector<int> fill(rowStart.begin(), rowStart.end() - 1);
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) his[sz(fill[sz(std::min(t[k], t[(k + 1) % 3]))]++)] = std::max(t[k], t[(k + 1) % 3]);
  }
  const auto trianglesOf = [&](int lo, int hi) {  // number of triangles with the edge {lo, hi}
    return std::count(his.begin() + rowStart[sz(lo)], his.begin() + rowStart[sz(lo) + 1], hi);
  };
  std::unordered_map<std::uint64_t, int> refs;
  refs.reserve(mesh.boundaryEdges.size());
  const auto key = [](int lo, int hi) { return std::uint64_t(std::uint32_t(lo)) << 32 | std::uint32_t(hi); };
  for (const auto& e : mesh.boundaryEdges) refs[key(std::min(e.a, e.b), std::max(e.a, e.b))] = e.ref;
  BoundaryChain c{std::vector<int>(sz(nv), -1), std::vector<int>(sz(nv), 1)};
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (trianglesOf(std::min(a, b), std::max(a, b)) != 1) continue;
      ABLMG_REQUIRE(c.next[sz(a)] < 0,
                    name << ": boundary vertex " << a + 1 << " starts two boundary edges (non-manifold boundary)");
      const auto it = refs.find(key(std::min(a, b), std::max(a, b)));
      c.next[sz(a)] = b;
      c.nextRef[sz(a)] = it == refs.end() ? 1 : it->second;
    }
  return c;
}

}  // namespace

// A valid mesh's one-triangle edges are exactly its boundaryEdges, listed once and oriented as
// in their triangle, so the chain comes straight from them. A vertex starting two of them
// (boundary loops that touch), or an empty list, goes through chainByCounting, which names the
// problem.
Domain domainFromMeshBoundary(const Mesh2& mesh, const std::string& name) {
  const int nv = mesh.numVertices();
  const auto sz = [](int i) { return static_cast<std::size_t>(i); };
  BoundaryChain chain{std::vector<int>(sz(nv), -1), std::vector<int>(sz(nv), 1)};
  bool any = false, pinched = false;
  for (const auto& e : mesh.boundaryEdges) {
    pinched = pinched || chain.next[sz(e.a)] >= 0;
    chain.next[sz(e.a)] = e.b;
    chain.nextRef[sz(e.a)] = e.ref;
    any = true;
  }
  if (pinched || !any) {
    chain = chainByCounting(mesh, name);
    any = std::any_of(chain.next.begin(), chain.next.end(), [](int b) { return b >= 0; });
  }
  const auto& next = chain.next;
  const auto& nextRef = chain.nextRef;
  ABLMG_REQUIRE(any, name << ": mesh has no boundary edges");
  std::vector<BoundaryLoop> loops;
  std::vector<double> areas;
  std::vector<char> used(sz(nv), 0);
  for (int start = 0; start < nv; ++start) {  // loops start at their smallest vertex, in that order
    if (next[sz(start)] < 0 || used[sz(start)]) continue;
    BoundaryLoop loop;
    loop.smooth = true;
    double area = 0;
    int v = start;
    do {
      used[sz(v)] = 1;
      ABLMG_REQUIRE(next[sz(v)] >= 0, name << ": boundary is not closed at vertex " << v + 1);
      loop.points.push_back(mesh.vertices[v]);
      loop.tags.push_back(nextRef[sz(v)]);
      // about the loop's first vertex: the sum about the origin cancels far from it (10⁹)
      area += 0.5 * cross(mesh.vertices[v] - mesh.vertices[start], mesh.vertices[next[sz(v)]] - mesh.vertices[start]);
      v = next[sz(v)];
      ABLMG_REQUIRE(v == start || !used[sz(v)], name << ": boundary loops touch at vertex " << v + 1);
    } while (v != start);
    loops.push_back(std::move(loop));
    areas.push_back(area);
  }
  const std::size_t outer = std::max_element(areas.begin(), areas.end()) - areas.begin();
  BoundaryLoop o = std::move(loops[outer]);
  loops.erase(loops.begin() + long(outer));
  try {
    return Domain(std::move(o), std::move(loops));
  } catch (const InputError& e) { throw InputError(name + ": boundary: " + e.what()); }
}

namespace {

std::uint64_t undirected(int a, int b) {
  return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
}

/// Triangles connected across non-interface edges: component id per triangle, in order of
/// their smallest triangle.
std::vector<int> components(const Mesh2& mesh, const std::vector<std::array<int, 3>>& nb,
                            const std::unordered_map<std::uint64_t, int>& interfaceRef) {
  std::vector<int> comp(mesh.triangles.size(), -1), stack;
  int nc = 0;
  for (int t0 = 0; t0 < mesh.numTriangles(); ++t0) {
    if (comp[std::size_t(t0)] >= 0) continue;
    comp[std::size_t(t0)] = nc;
    stack.push_back(t0);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      const auto& tr = mesh.triangles[std::size_t(t)];
      for (int k = 0; k < 3; ++k) {
        const int u = nb[std::size_t(t)][k];
        if (u < 0 || comp[std::size_t(u)] >= 0) continue;
        if (interfaceRef.count(undirected(tr[(k + 1) % 3], tr[(k + 2) % 3]))) continue;
        comp[std::size_t(u)] = nc;
        stack.push_back(u);
      }
    }
    ++nc;
  }
  return comp;
}

/// Junction flags (see MeshSubdomains::junction) from the boundary and interface edges.
std::vector<char> junctions(const Mesh2& mesh) {
  const std::size_t nv = mesh.vertices.size();
  std::vector<char> j(nv, 0), onBoundary(nv, 0), onInterface(nv, 0);
  std::vector<int> degree(nv, 0), firstRef(nv, 0);
  std::vector<std::array<int, 2>> ends(nv, {-1, -1});
  const auto visit = [&](const BoundaryEdge& e, std::vector<char>& on) {
    for (int k = 0; k < 2; ++k) {
      const int v = k == 0 ? e.a : e.b, w = k == 0 ? e.b : e.a;
      const std::size_t vs = std::size_t(v);
      if (degree[vs] == 0) firstRef[vs] = e.ref;
      if (degree[vs] < 2) ends[vs][std::size_t(degree[vs])] = w;
      if (firstRef[vs] != e.ref) j[vs] = 1;
      ++degree[vs];
      on[vs] = 1;
    }
  };
  for (const auto& e : mesh.boundaryEdges) visit(e, onBoundary);
  for (const auto& e : mesh.interfaceEdges) visit(e, onInterface);
  for (std::size_t v = 0; v < nv; ++v) {
    if (degree[v] == 0) continue;
    if (degree[v] != 2 || (onBoundary[v] && onInterface[v])) j[v] = 1;
    if (onInterface[v] && !onBoundary[v] && degree[v] == 2) {  // a turn of more than 30°
      const Vec2 din = mesh.vertices[v] - mesh.vertices[std::size_t(ends[v][0])];
      const Vec2 dout = mesh.vertices[std::size_t(ends[v][1])] - mesh.vertices[v];
      if (std::atan2(std::abs(cross(din, dout)), din.dot(dout)) > std::numbers::pi / 6) j[v] = 1;
    }
  }
  for (int v : mesh.corners) j[std::size_t(v)] = 1;
  for (int v : mesh.requiredVertices) j[std::size_t(v)] = 1;
  for (const auto* list : {&mesh.requiredEdges, &mesh.ridges})
    for (const auto& e : *list) j[std::size_t(e[0])] = j[std::size_t(e[1])] = 1;
  return j;
}

}  // namespace

MeshSubdomains subdomainsFromMesh(const Mesh2& mesh, const std::string& name) {
  std::unordered_map<std::uint64_t, int> boundaryRef, interfaceRef;
  for (const auto& e : mesh.boundaryEdges) boundaryRef[undirected(e.a, e.b)] = e.ref;
  for (const auto& e : mesh.interfaceEdges) interfaceRef[undirected(e.a, e.b)] = e.ref;
  const auto nb = mesh.triangleNeighbours();
  const std::vector<int> comp = components(mesh, nb, interfaceRef);
  MeshSubdomains out;
  out.junction = junctions(mesh);
  const int nc = comp.empty() ? 0 : *std::max_element(comp.begin(), comp.end()) + 1;
  out.regions.resize(std::size_t(nc));
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    auto& r = out.regions[std::size_t(comp[std::size_t(t)])];
    if (r.triangles.empty()) r.ref = t < int(mesh.triangleRefs.size()) ? mesh.triangleRefs[std::size_t(t)] : 0;
    r.triangles.push_back(t);
  }
  std::vector<int> next(mesh.vertices.size(), -1), nextRef(mesh.vertices.size(), 0);
  std::vector<char> nextInterface(mesh.vertices.size(), 0), used(mesh.vertices.size(), 0);
  for (auto& r : out.regions) {
    std::vector<int> starts;
    for (int t : r.triangles) {
      const auto& tr = mesh.triangles[std::size_t(t)];
      for (int k = 0; k < 3; ++k) {
        const int a = tr[(k + 1) % 3], b = tr[(k + 2) % 3], u = nb[std::size_t(t)][k];
        const bool inside = u >= 0 && comp[std::size_t(u)] == comp[std::size_t(t)];
        if (inside) {
          ABLMG_REQUIRE(!interfaceRef.count(undirected(a, b)),
                        name << ": interface edge (" << a + 1 << ", " << b + 1
                             << ") has the same subdomain on both sides (a line that separates nothing)");
          continue;
        }
        ABLMG_REQUIRE(next[std::size_t(a)] < 0,
                      name << ": the boundary of subdomain " << r.ref << " touches itself at vertex " << a + 1);
        next[std::size_t(a)] = b;
        nextInterface[std::size_t(a)] = u >= 0;
        const auto& refs = u >= 0 ? interfaceRef : boundaryRef;
        const auto it = refs.find(undirected(a, b));
        nextRef[std::size_t(a)] = it == refs.end() ? 0 : it->second;
        starts.push_back(a);
      }
    }
    std::sort(starts.begin(), starts.end());
    std::vector<double> areas;
    for (int s : starts) {
      if (used[std::size_t(s)]) continue;
      std::vector<int> loop, refs;
      std::vector<char> itf;
      double area = 0;
      int v = s;
      do {
        used[std::size_t(v)] = 1;
        loop.push_back(v);
        refs.push_back(nextRef[std::size_t(v)]);
        itf.push_back(nextInterface[std::size_t(v)]);
        const int w = next[std::size_t(v)];
        ABLMG_REQUIRE(w >= 0, name << ": the boundary of subdomain " << r.ref << " is not closed at vertex " << v + 1);
        const Vec2& o = mesh.vertices[std::size_t(s)];  // as above: about the loop's first vertex
        area += 0.5 * cross(mesh.vertices[std::size_t(v)] - o, mesh.vertices[std::size_t(w)] - o);
        v = w;
      } while (v != s);
      r.loops.push_back(std::move(loop));
      r.segmentRefs.push_back(std::move(refs));
      r.segmentInterface.push_back(std::move(itf));
      areas.push_back(area);
    }
    const std::size_t outer = std::size_t(std::max_element(areas.begin(), areas.end()) - areas.begin());
    std::swap(r.loops[0], r.loops[outer]);
    std::swap(r.segmentRefs[0], r.segmentRefs[outer]);
    std::swap(r.segmentInterface[0], r.segmentInterface[outer]);
    for (int s : starts) next[std::size_t(s)] = -1, used[std::size_t(s)] = 0;
  }
  return out;
}

}  // namespace ablmg
