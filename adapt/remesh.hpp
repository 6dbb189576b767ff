#pragma once
/// Remeshing to a per-vertex metric: the call a solver makes between two solves (what
/// libmmg2d's MMG2D_mmg2dlib is to MMG). `ablmg remesh` is this call between reading and
/// writing files.
///
///   Mesh2 + one Metric2 per vertex ─ clamp sizes to [hmin, hmax] ─ limitGradation (hgrad)
///     ─ domainFromMeshBoundary ─ BackgroundMetricField ─ mesher::meshDomain ─▶ new Mesh2
///
/// Usage, in a solver's loop (Remesh.TheHeadersSolverLoopRuns in tests/adapt/test_remesh.cpp
/// runs it; examples/07_solver_in_the_loop.cpp is a loop with a real solver and a known domain):
///
///   #include "ablmg/adapt/remesh.hpp"
///   ablmg::Mesh2 mesh = myMesh();           // CCW triangles; boundaryEdges carry your refs
///   ablmg::adapt::RemeshOptions options;
///   options.hmin = 1e-4;                    // sizes in the mesh's length unit
///   options.hmax = 0.1;                     // hgrad stays 1.3 (MMG's default)
///   for (int cycle = 0; cycle < 5; ++cycle) {
///     const std::vector<double> u = mySolve(mesh);
///     std::vector<ablmg::Metric2> metric = myMetric(mesh, u);  // e.g. adapt::adaptMetric
///     ablmg::adapt::RemeshResult r = ablmg::adapt::remesh(std::move(mesh), std::move(metric), options);
///     mesh = std::move(r.mesh);             // valid; boundary refs kept
///   }
///
/// Errors are exceptions (ablmg::InputError for bad input, ablmg::Error if the mesher fails);
/// nothing is printed or written. Same input and options (seed) ⇒ bit-identical output.
#include "ablmg/adapt/boundary_mesh.hpp"
#include "ablmg/adapt/gradation.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/mesher/mesher.hpp"

#include <limits>
#include <string>
#include <vector>

namespace ablmg::adapt {

struct RemeshOptions {
  double hmin = 0;                                        ///< [0, hmax): smallest size h1, h2
  double hmax = std::numeric_limits<double>::infinity();  ///< (hmin, ∞]: largest size h1, h2
  /// β > 1: size gradation on the input mesh after the clamp (gradation.hpp, MMG's -hgrad);
  /// ≤ 0 (e.g. MMG's −1): none. Values in (0, 1] are refused.
  double hgrad = 1.3;
  /// Validate (default): remesh() runs Mesh2::validate on the input. AlreadyValidated: the
  /// caller has just validated this very mesh (as `ablmg remesh` does when reading it).
  BackgroundMetricField::MeshCheck inputCheck = BackgroundMetricField::MeshCheck::Validate;
  std::string name = "mesh";  ///< names the input in error messages (the CLI gives the file)
  /// Warm start: the input mesh's interior vertices seed the bubble placement
  /// (PlacementOptions::warmStart: those that fit the metric's spacing replace lattice points).
  /// IfFits (default): only when the input already fits the metric, i.e. at least half of its
  /// edges are within ±10 % of unit length in it (after clamp and gradation). A mesh remeshed
  /// to its own metric then keeps its packing and placement only relaxes it: the paper's disks
  /// as mesh + metric pairs reach 90.8 % (ring), 92.2 % (line), 96.8 % (constant), 91.3 %
  /// (eq. 4) of edges within ±10 %, in fewer steps, where a fresh lattice stopped on the
  /// plateau at 85.7 % for the ring. A solver's hand-over (a new metric: the wave-front and
  /// layer cycles have 0.5 % and 4 % of their input edges within ±10 %) starts from the
  /// lattice, which is better there (wave front 93.8 % against 83.7 % warm, in half the time).
  /// Ignored when mesh.placement.warmStart is already given. The adaptive loop has its own
  /// switch (AdaptOptions::warmStart, off).
  enum class WarmStart { Off, IfFits, On };
  WarmStart warmStart = WarmStart::IfFits;
  /// > 0: the input metric is first snapped to a grid of this step (metric_snap.hpp), so that
  /// metrics differing by round-off (a distributed solver's) give the same mesh; 0: used as
  /// given (default; the meshes of `ablmg remesh`).
  double metricQuantum = 0;
  /// A mesh with edges and no triangles (a boundary discretization, boundary_mesh.hpp): how
  /// loops inside other loops are read, as holes (default) or as interfaces between subdomains.
  InteriorLoops interiorLoops = InteriorLoops::Holes;
  /// The mesher's options: the Remesh preset (mesher/mesher.hpp: plateau stop, no final
  /// relaxation). The seed is mesh.placement.seed, the lattice orientation
  /// mesh.placement.lattice.orientation.
  mesher::MeshOptions mesh = mesher::meshPreset(mesher::MeshPreset::Remesh);
};

/// Throws InputError "remesh options: <field> ..." naming the field and value.
void validate(const RemeshOptions& options);

/// The fields of mesher::MeshResult (so code written for meshDomain's result reads this one)
/// and what remesh() did before meshing. Times are wall seconds (steady clock).
struct RemeshResult {
  Mesh2 mesh;                   ///< valid; boundary edges carry the input's boundary refs
  std::vector<Metric2> metric;  ///< the metric (clamped, graded, interpolated) at each new vertex
  mesher::MeshStats stats;      ///< placement, connection, quality post-pass, validation
  long clampedMetrics = 0;      ///< input metrics changed by the [hmin, hmax] clamp
  GradationStats gradation;     ///< all zero when hgrad ≤ 0
  double secondsValidate = 0;   ///< the input check (0 with AlreadyValidated)
  double secondsClamp = 0, secondsGradation = 0, secondsDomain = 0, secondsBackgroundField = 0;
  double secondsMeshing = 0;  ///< mesher::meshDomain (placement + connection + post-pass)
  double inputWithin10 = 0;   ///< share of input edges within ±10 % of unit length (IfFits only)
  bool warmStarted = false;   ///< the placement was seeded with the input's interior vertices
};

/// Remeshes the domain covered by `mesh` so that edges have unit length in `metric`.
/// A mesh with no triangles and closed loops of boundary edges is first triangulated on its
/// loop vertices (triangulateBoundary, boundary_mesh.hpp; options.interiorLoops), the metric
/// of each kept vertex carried over: the size is then interpolated along and into the domain.
///  mesh    valid (Mesh2::validate; see RemeshOptions::inputCheck); its boundary loops and
///          their refs become the domain (domainFromMeshBoundary: one outer loop, holes,
///          corners kept, boundary nodes placed anew). Taken by value and kept as the
///          background mesh: pass std::move(mesh) to save a copy.
///  metric  one SPD Metric2 per vertex of `mesh` (coordinates' length unit); interpolated
///          log-Euclidean between vertices. Sizes are first clamped to [hmin, hmax] (the
///          directions kept), then graded if hgrad > 1.
/// Returns a valid mesh whose boundary nodes lie on the input's boundary polyline, with its
/// corners (ref changes, turns > 30°) kept and its other vertices not necessarily: the area is
/// the input's up to round-off where the boundary is straight between corners (a polygon),
/// slightly less where it samples a curve (chords).
/// Throws InputError for options out of range (validate), metric.size() ≠ the vertex count
/// (naming both), an invalid mesh ("<name>: invalid mesh: ..."), a boundary that is not
/// closed loops ("<name>: ..."), a non-SPD metric; ablmg::Error if the mesher fails.
RemeshResult remesh(Mesh2 mesh, std::vector<Metric2> metric, const RemeshOptions& options = {});

/// Subdomains and interfaces. A mesh with several triangle refs, interface edges or features
/// (Mesh2::corners, requiredVertices, requiredEdges, ridges) is remeshed subdomain by
/// subdomain (MeshSubdomains, core/domain_from_mesh.hpp): the connection (paper §4) works on
/// one domain, so each subdomain is meshed alone and no link can cross an interface. Each
/// interface curve (interface edges between junctions) is cut once into round(metric length)
/// pieces of equal metric length, and those points, fixed, with every piece kept as one edge,
/// are the loop of both subdomains beside it; the meshes are glued at those points. The
/// output has each subdomain's ref on its triangles, the interfaces as interfaceEdges (their
/// refs kept), and the corners and required vertices/edges (all on boundaries or interfaces)
/// at their exact coordinates, renumbered. A subdomain's area is kept to round-off where its
/// boundary is straight between junctions and corners.
/// Slits: a mesh whose boundary has distinct vertices at the same point (a zero-width gap, the
/// two lips of a crack) is cut, for meshing only, from each tip (the boundary vertex between
/// two lips) along the shortest path of mesh edges to the boundary or an interface; the lips
/// then lie in different pieces and keep distinct vertices, the tip stays a vertex, and the
/// cut is glued and dropped (no interface edge remains on it).
bool needsSubdomains(const Mesh2& mesh);
/// MMG's -nosurf: adds every boundary and interface edge of `mesh` to mesh.requiredEdges
/// (each pair listed once), so that remesh() keeps the boundary and the interfaces as they are
/// (their vertices at their coordinates, their edges unsplit, their refs) and meshes only the
/// inside. On an edges-only mesh it makes every loop edge required.
void requireBoundaryEdges(Mesh2& mesh);
/// The subdomain path of remesh(): `mesh` valid, `field` its background field; fills out.mesh,
/// out.metric, out.stats (counts summed over the subdomains). Throws InputError naming `name`
/// for a required vertex inside a subdomain or a subdomain that is no valid Domain.
void remeshSubdomains(const Mesh2& mesh, const MetricField& field, const mesher::MeshOptions& options,
                      const std::string& name, RemeshResult& out);

/// A region of a domain with its own triangle ref: a closed polygon (≥ 3 points, either
/// orientation) strictly inside the domain, touching neither its boundary nor another region
/// (regions may nest).
struct TaggedRegion {
  std::vector<Vec2> points;
  int tag = 1;  ///< ≥ 1: the triangle ref inside it (and the ref of its boundary, an interface)
};
/// meshDomain for a domain with regions: the domain's loops and the region polygons are
/// triangulated on their points (triangulateBoundary, interior loops as interfaces, the
/// domain's holes dropped), then meshed subdomain by subdomain to `field` (remeshSubdomains:
/// no ABLMG link crosses a region boundary). Triangles outside every region get ref 0, those
/// in a region its tag (the innermost region's when they nest). Throws InputError naming
/// `name` and the region for a tag < 1, a point outside the domain or regions that cross or
/// touch; the domain may not have slits.
mesher::MeshResult meshDomainWithRegions(const Domain& domain, const std::vector<TaggedRegion>& regions,
                                         const MetricField& field, const mesher::MeshOptions& options,
                                         const std::string& name = "domain");

/// meshDomain(domain, BackgroundMetricField(mesh, metric), options): remeshing a domain the
/// caller knows exactly (e.g. a curved boundary, which the input mesh only approximates).
/// No clamp and no gradation; `mesh` is validated. Used by the adaptive loop. A mesh with
/// subdomains (several triangle refs, or interface edges) is remeshed subdomain by subdomain
/// (remeshSubdomains): refs, interfaces and slits kept, the boundary then taken from `mesh`
/// (its polyline), not from `domain`. `rows`: per-vertex lattice rows (BackgroundMetricField).
mesher::MeshResult remesh(const Domain& domain, const Mesh2& mesh, std::vector<Metric2> metric,
                          const mesher::MeshOptions& options = {}, std::vector<Vec2> rows = {});

}  // namespace ablmg::adapt
