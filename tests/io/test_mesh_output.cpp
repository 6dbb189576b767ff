// Tests of cli/mesh_output.hpp (compiled into test_io by tests/cli/io_cli.cmake): the .vtu of a
// mesh carries its quality in the metric, read back with VTK's own reader.
#include "ablmg/cli/mesh_output.hpp"

#include "ablmg/io/medit.hpp"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <filesystem>

using namespace ablmg;

TEST(MeshOutput, VtuCarriesQualityAndEdgeLengths) {
  // square.mesh: the unit square cut into four right isosceles triangles around its centre
  // (vertex 4). Identity metric: q = 4√3 (1/4) / (1/2 + 1/2 + 1) = √3/2; the centre's edges are
  // the half-diagonals (√2/2), a corner has two sides (1) and one half-diagonal.
  const Mesh2 m = io::readMesh(std::string(ABLMG_TEST_DATA) + "/square.mesh");
  const std::vector<Metric2> identity(5, Metric2::isotropic(1.0));
  const std::string p =
      (std::filesystem::temp_directory_path() / ("ablmg_mo_" + std::to_string(::getpid()) + ".vtu")).string();
  cli::writeMeshOutput(p, Domain::rectangle(0, 0, 1, 1), m, identity);
  vtkNew<vtkXMLUnstructuredGridReader> r;
  r->SetFileName(p.c_str());
  r->Update();
  vtkUnstructuredGrid* g = r->GetOutput();
  ASSERT_NE(g->GetCellData()->GetArray("quality"), nullptr);
  for (int t = 0; t < 4; ++t)
    EXPECT_NEAR(g->GetCellData()->GetArray("quality")->GetComponent(t, 0), std::sqrt(3.0) / 2, 1e-12);
  EXPECT_NEAR(g->GetPointData()->GetArray("edge_length_min")->GetComponent(4, 0), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(g->GetPointData()->GetArray("edge_length_max")->GetComponent(4, 0), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(g->GetPointData()->GetArray("edge_length_min")->GetComponent(0, 0), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(g->GetPointData()->GetArray("edge_length_max")->GetComponent(0, 0), 1.0, 1e-12);
  // In the metric of size 1/2 every length doubles; q does not change.
  const auto f = cli::qualityFields(m, std::vector<Metric2>(5, Metric2::isotropic(0.5)));
  EXPECT_NEAR(f.point[1].values[0], 2.0, 1e-12);
  EXPECT_NEAR(f.cell[0].values[3], std::sqrt(3.0) / 2, 1e-12);
  std::filesystem::remove(p);
}
