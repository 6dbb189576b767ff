#pragma once
/// ablmg's mesher API — the one header a solver calls in a loop (the libmmg2d.h of ablmg).
///
///   Domain + MetricField ─ placeNodes (§3) ─▶ PlacementResult ─ connect (§4) ─▶ Mesh2
///                                                        ─ improveQuality (improve.hpp) ─▶ Mesh2
///
/// meshDomain() runs the stages, validates the mesh (Mesh2::validate against the domain's
/// area) and returns it with statistics. It never returns an invalid mesh: it throws
/// ablmg::Error if repair fails, ablmg::InputError for bad input (non-SPD metric, a metric
/// asking for more than maxNodes nodes, ...). It does not print, open files or exit.
#include "ablmg/core/domain.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/core/progress.hpp"
#include "ablmg/mesher/connect.hpp"
#include "ablmg/mesher/improve.hpp"
#include "ablmg/mesher/place_nodes.hpp"

#include <string>

namespace ablmg::mesher {

struct MeshOptions {
  PlacementOptions placement;
  ConnectOptions connect;
  ImproveOptions improve;  ///< the post-pass on triangles with q < improve.qThreshold (enabled: on)
  /// Called at each stage and every progressEvery placement steps (core/progress.hpp); empty:
  /// no reports. The mesh does not depend on it.
  ProgressCallback progress;
  int progressEvery = 10;  ///< placement steps between two reports (values < 1 count as 1)
};

struct MeshStats {
  PlacementStats placement;
  ConnectStats connect;
  ImproveStats improve;  ///< all zero when the post-pass is disabled
  double secondsValidate = 0;
};

/// Adds the statistics of one part of a domain meshed in pieces (slit cuts, subdomains) into
/// the whole's: counts and times add up; step and pass counts, residuals and stop flags are the
/// worst part's; the nearest-neighbour share is weighted by the parts' node counts.
void addPartStats(MeshStats& whole, const MeshStats& part);

struct MeshResult {
  Mesh2 mesh;                   ///< valid; boundary edges carry the domain's segment tags
  std::vector<Metric2> metric;  ///< the prescribed metric at each mesh vertex
  MeshStats stats;
};

/// The mesher's three configurations, one per use; every entry point starts from one of them
/// (`ablmg mesh|remesh|adapt --print-options` shows the options in effect). They differ in four
/// fields of PlacementOptions, all else being MeshOptions{}'s:
///
///   field                        Mesh (meshDomain)  Remesh (adapt::remesh)  Adapt (adaptive loop)
///   plateauSteps / plateauGain   0 (off)            10 / 0.01               10 / 0.01
///   finalRelaxSteps              10                 0                       10
///   defectPasses                 6                  6                       0
///   lattice.orientation          Auto               Auto                    ShortAxis
///
/// - Mesh (`ablmg mesh`, the paper's cases): runs to the residual target; the packing is the
///   product, so defect annealing and a final relaxation are worth their steps.
/// - Remesh (`ablmg remesh`, the C API, Python's remesh): a metric from a solver rarely lets the
///   residual settle, so placement stops on the quality plateau; the final relaxation's 10
///   steps cost 12 % of a remesh for +0.4 point of edges within ±10 % and are skipped.
/// - Adapt (`ablmg adapt`): plateau stop as Remesh; the lattice starts with one row along each
///   node's short-size direction (the Hessian's steep eigenvector), since the P1 gradient error
///   of a metric-equilateral triangle depends on its orientation and the dynamics keep the
///   orientation they start from; no defect annealing, which does not lower the FE error.
/// Measurements: docs/method.md.
enum class MeshPreset { Mesh, Remesh, Adapt };
MeshOptions meshPreset(MeshPreset preset);
/// "mesh", "remesh", "adapt"; InputError naming the valid ones otherwise.
MeshPreset parseMeshPreset(const std::string& name);
const char* meshPresetName(MeshPreset preset);

/// Meshes `domain` so that edges have unit length in `metric` (paper §3–4). A domain with slits
/// (Domain::hasSlits) is cut and meshed piece by piece (mesher/slit_domain.hpp): the lips get
/// distinct vertices.
MeshResult meshDomain(const Domain& domain, const MetricField& metric, const MeshOptions& options = {});

}  // namespace ablmg::mesher
