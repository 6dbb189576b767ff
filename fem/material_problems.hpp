#pragma once
/// Library problems with several materials: −∇·(κ ∇u) = f with κ and f constant on each
/// subdomain and jumping across the interfaces between them, and no exact solution (errors are
/// measured against a reference solution computed on a much finer mesh; adapt/reference.hpp).
///
///  name      domain            materials (triangle ref: κ, f)                   boundary
///  battery   (0, 8.4) × (0, 24)  1: 25, 0 (the rest)   2: 7, 1 ([0.8, 6.1] × ([1.6, 3.6] ∪ [12, 18.8]))
///                              3: 5, 1 ([0.8, 6.1] × [3.6, 12])   4: 0.2, 0 ([6.1, 6.9] × [0.8, 20.4])
///                              5: 0.05, 0 ([0, 6.9] × [20.4, 23.2])      u = 0 on tags 1–3, κ∂u/∂n = 0 on 4
///
/// battery is a Poisson variant of Mitchell's battery problem (W. F. Mitchell, "A collection of 2D
/// elliptic problems for testing adaptive grid refinement algorithms", Appl. Math. Comput. 220
/// (2013), §2.10): his five materials' values of κ (the x coefficient p; his y coefficient q
/// differs in two of them and is not modelled) and loads on the same outer rectangle, the
/// regions laid out as nested rectangles with T and cross junctions, where u has singularities
/// of the kind his has, and Dirichlet/Neumann instead of his Robin conditions. Tags as
/// Domain::rectangle (1 bottom, 2 right, 3 top, 4 left); interface refs 10·a + b between
/// materials a < b (fem/structured_mesh.hpp, gridRegionMesh).
#include "ablmg/core/domain.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/fem/poisson_problem.hpp"

#include <map>
#include <string>
#include <vector>

namespace ablmg::fem {

struct MaterialProblem {
  std::string name;
  std::map<std::string, double> params;  ///< every parameter in effect (none for battery)
  std::string description;               ///< for reports
  Domain domain;                         ///< the outer boundary
  /// A coarse valid mesh of the domain whose triangleRefs are the materials and whose
  /// interfaceEdges are the interfaces between them (the loop's first mesh is remeshed from it).
  Mesh2 regions;
  PoissonProblem pde;  ///< with kappaBySubdomain / fBySubdomain keyed by material ref
};

/// Builds problem `name`. Throws InputError naming the valid names (unknown name) or naming
/// the key (a parameter the problem does not have).
MaterialProblem makeMaterialProblem(const std::string& name, const std::map<std::string, double>& params = {});

/// Names accepted by makeMaterialProblem.
std::vector<std::string> materialProblemNames();

}  // namespace ablmg::fem
