#include "ablmg/fem/material_problems.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"

namespace ablmg::fem {
namespace {

/// The battery's material at (x, y) (the centre of a cell of its grid).
int batteryMaterial(double x, double y) {
  if (x > 6.1 && x < 6.9 && y > 0.8 && y < 20.4) return 4;
  if (x < 6.9 && y > 20.4 && y < 23.2) return 5;
  if (x > 0.8 && x < 6.1 && y > 3.6 && y < 12) return 3;
  if (x > 0.8 && x < 6.1 && ((y > 1.6 && y < 3.6) || (y > 12 && y < 18.8))) return 2;
  return 1;
}

MaterialProblem battery() {
  MaterialProblem p;
  p.name = "battery";
  p.description = "-div(kappa grad u) = f, kappa/f by material 1: 25/0, 2: 7/1, 3: 5/1, 4: 0.2/0, 5: 0.05/0";
  p.domain = Domain::rectangle(0, 0, 8.4, 24);
  p.regions = gridRegionMesh({0, 0.8, 6.1, 6.9, 8.4}, {0, 0.8, 1.6, 3.6, 12, 18.8, 20.4, 23.2, 24}, batteryMaterial);
  const double kappa[] = {25, 7, 5, 0.2, 0.05}, f[] = {0, 1, 1, 0, 0};
  for (int m = 1; m <= 5; ++m) {
    p.pde.kappaBySubdomain[m] = kappa[m - 1];
    p.pde.fBySubdomain[m] = f[m - 1];
  }
  for (int tag : {1, 2, 3}) p.pde.dirichlet[tag] = 0.0;
  p.pde.neumann[4] = 0.0;
  p.pde.threadSafeFunctions = true;
  return p;
}

}  // namespace

std::vector<std::string> materialProblemNames() { return {"battery"}; }

MaterialProblem makeMaterialProblem(const std::string& name, const std::map<std::string, double>& params) {
  ABLMG_REQUIRE(name == "battery", "unknown material problem '" << name << "' (valid: battery)");
  ABLMG_REQUIRE(params.empty(),
                "problem '" << name << "': unknown parameter '" << params.begin()->first << "' (it has none)");
  return battery();
}

}  // namespace ablmg::fem
