#include "ablmg/core/domain_from_mesh.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cstdint>
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
      area += 0.5 * cross(mesh.vertices[v], mesh.vertices[next[sz(v)]]);
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

}  // namespace ablmg
