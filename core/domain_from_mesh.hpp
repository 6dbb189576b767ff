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

}  // namespace ablmg
