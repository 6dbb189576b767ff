#pragma once
/// The domain a triangle mesh covers, rebuilt from its boundary: what remeshing needs when
/// the caller has a mesh but no Domain (a solver's mesh, a .mesh file).
#include "ablmg/core/domain.hpp"
#include "ablmg/core/mesh2.hpp"

#include <string>

namespace ablmg {

/// The boundary of `mesh` (its edges in exactly one triangle, oriented with the mesh on their
/// left) chained into closed loops. The loop of largest area is the outer loop, the others are
/// holes. Each segment keeps the ref of its boundary edge (`mesh.boundaryEdges`; 1 where a
/// boundary edge is missing from that list). Loops are `smooth` (BoundaryLoop::smooth), so the
/// mesher places its own boundary nodes and keeps only the corners: ref changes and turns of
/// more than 30°. Loops start at their smallest vertex, in that order (deterministic).
///
/// `mesh` must be valid (Mesh2::validate; not checked here): then its one-triangle edges are
/// exactly `boundaryEdges` and are read straight from it (O(edges)). Boundary loops that
/// touch at a vertex are refused.
///
/// Throws InputError "<name>: ..." (vertex numbers 1-based, as in a medit file) if the mesh
/// has no boundary edge, a boundary vertex starts two boundary edges (non-manifold boundary),
/// a loop is not closed or two loops touch, or the loops do not form a valid Domain.
Domain domainFromMeshBoundary(const Mesh2& mesh, const std::string& name = "mesh");

/// One subdomain of a mesh: a connected set of triangles of one ref, bounded by the mesh's
/// boundary edges and its interface edges (Mesh2::interfaceEdges).
struct MeshSubdomain {
  int ref = 0;                                      ///< the triangles' ref
  std::vector<int> triangles;                       ///< its triangles, ascending
  std::vector<std::vector<int>> loops;              ///< vertex ids; [0] the outer loop (CCW), then holes (CW);
                                                    ///< segment k joins loops[i][k] → loops[i][k + 1 mod n]
  std::vector<std::vector<int>> segmentRefs;        ///< per segment: the edge's ref
  std::vector<std::vector<char>> segmentInterface;  ///< per segment: an interface edge (shared)
};

/// The subdomains of `mesh` and the vertices every subdomain must keep where it is.
struct MeshSubdomains {
  std::vector<MeshSubdomain> regions;  ///< in order of their smallest triangle
  /// Per vertex: a junction, fixed in every remesh: where interfaces meet each other or the
  /// boundary, where the ref of the boundary or interface changes, where an interface turns by
  /// more than 30°, the mesh's corners, required vertices and the ends of required edges and
  /// ridges. Closed interface curves with none get one at their smallest vertex.
  std::vector<char> junction;
};

/// Splits a valid `mesh` (Mesh2::validate) into subdomains: triangles connected across edges
/// that are not interface edges. Each subdomain's boundary is chained into loops (starting at
/// their smallest vertex; the loop of largest area is the outer one). Throws InputError
/// "<name>: ..." (vertices 1-based) if an interface edge has the same subdomain on both sides
/// (a line that separates nothing), or a subdomain's boundary touches itself at a vertex.
MeshSubdomains subdomainsFromMesh(const Mesh2& mesh, const std::string& name = "mesh");

}  // namespace ablmg
