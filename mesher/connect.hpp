#pragma once
/// ABLMG connection (paper §4.1): every node's local mesh from its adjacency list, with the
/// non-satellite nodes removed by the anisotropic swap criterion eq. (12); the global mesh is
/// the union of the local meshes, repaired deterministically where they disagree.
#include "core/domain.hpp"
#include "core/mesh2.hpp"
#include "mesher/place_nodes.hpp"

namespace ablmg::mesher {

struct ConnectOptions {
  int threads = 0;  ///< 0 = OpenMP default; the result does not depend on it
};

struct ConnectStats {
  long intersectionTests = 0;   ///< segment crossing tests (paper §4.3 reports 157317)
  long crossingsFound = 0;
  long deletedEdges = 0;        ///< non-satellite links removed by eq. (12)
  long consistentTriangles = 0; ///< triangles present in the local meshes of all three nodes
  long repairedTriangles = 0;   ///< triangles created or changed by the repair step
  double secondsLocalMeshes = 0, secondsRepair = 0;
};

struct ConnectResult {
  Mesh2 mesh;                   ///< valid (Mesh2::validate); vertex i = node i
  ConnectStats stats;
};

ConnectResult connect(const PlacementResult& placement, const Domain& domain, const ConnectOptions& options = {});

} // namespace ablmg::mesher
