#pragma once
/// Structured triangle meshes of rectilinear domains (rectangles, the L-shape, any Domain
/// whose segments are axis-parallel and whose points lie on the grid), for verification,
/// benchmarks and tests that must not depend on the bubble mesher.
///
/// The bounding box is split into nx × ny equal cells; a cell is kept when its centre is in
/// the domain; each cell is cut into two triangles along alternating diagonals (the
/// diagonal flips with the parity of i + j), so the mesh has no preferred direction.
/// Boundary edges carry the tag of the domain segment they lie on.
///
/// `perturbation` > 0 moves every non-boundary vertex by a uniform random offset in
/// [−p·h, p·h]² (h = min cell side; p ≤ 0.2 keeps every triangle valid), seeded by `seed`
/// (std::mt19937_64: same seed, same mesh): an "unstructured" mesh of the same density.
/// The result passes Mesh2::validate with the domain's area.
#include "ablmg/core/domain.hpp"
#include "ablmg/core/mesh2.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace ablmg::fem {

/// Throws InputError if nx, ny < 1, perturbation ∉ [0, 0.2], a segment is not axis-parallel,
/// a domain point is not a grid node, or the domain has slits.
Mesh2 structuredMesh(const Domain& domain, int nx, int ny, double perturbation = 0.0, std::uint64_t seed = 1);

/// A rectangle cut by the grid lines x = xs[i], y = ys[j] (each strictly increasing, ≥ 2
/// values; the rectangle is [xs.front(), xs.back()] × [ys.front(), ys.back()]) into cells,
/// each cell two triangles (alternating diagonals) whose triangleRefs is refOfCell(centre of
/// the cell). Boundary tags as Domain::rectangle; every edge between two triangles of
/// different refs a and b is an interface edge of ref 10·min(a, b) + max(a, b). A coarse,
/// valid mesh of rectilinear subdomains (materials), e.g. the regions of Mitchell's battery.
/// Throws InputError for breakpoints not increasing or non-finite.
Mesh2 gridRegionMesh(const std::vector<double>& xs, const std::vector<double>& ys,
                     const std::function<int(double x, double y)>& refOfCell);
/// The unit square [0,1]² with n × n cells (tags as Domain::rectangle).
Mesh2 unitSquareMesh(int n, double perturbation = 0.0, std::uint64_t seed = 1);

}  // namespace ablmg::fem
