#pragma once
/// A first mesh of the domain a boundary discretization encloses: what `ablmg remesh` (and
/// remesh()) do with a mesh that has edges and no triangles, MMG's way of asking for a mesh of
/// the enclosed domain.
///
///   edges ─ closed loops (every vertex on exactly two edges) ─ no two edges cross ─ nesting
///   ─ constrained Delaunay triangulation of the loop vertices (mesher::Triangulation, every
///   edge recovered) ─ triangles kept by region ─▶ a valid Mesh2 (no vertex added)
///
/// Regions by nesting: a loop inside no other is an outer boundary; InteriorLoops::Holes (the
/// default, Triangle's and the .poly convention) makes a loop inside an odd number of loops a
/// hole and one inside an even number an island (a domain of its own); Subdomains keeps every
/// loop's inside: the interior loops become interfaces (Mesh2::interfaceEdges with the edges'
/// refs) between subdomains. Each region's triangles get ref 1 + the index of the loop that
/// bounds it from outside (loops in order of their smallest vertex). Boundary edges keep the
/// file's refs. Vertices on no edge are dropped (the mesh has one vertex per loop vertex);
/// corners, required vertices and edges, ridges are renumbered with them.
#include "ablmg/core/mesh2.hpp"

#include <string>
#include <vector>

namespace ablmg::adapt {

enum class InteriorLoops { Holes, Subdomains };

struct BoundaryTriangulation {
  Mesh2 mesh;                    ///< valid (Mesh2::validate)
  std::vector<int> inputVertex;  ///< per vertex of `mesh`: its id in the input
};

/// Throws InputError "<name>: ..." (vertices 1-based, as in a medit file) if there are no
/// edges, an edge is degenerate, a chain of edges is open (a vertex on one edge), a vertex is
/// on more than two edges (loops that branch or touch), two edges cross or overlap, a loop
/// has zero area, an edge cannot be recovered (a vertex lies on it), or a corner / required
/// entity is on no edge.
BoundaryTriangulation triangulateBoundary(const Mesh2& boundary, const std::string& name = "mesh",
                                          InteriorLoops mode = InteriorLoops::Holes);

}  // namespace ablmg::adapt
