// Tests of io/vtu.hpp: the file reads back with VTK's own reader (counts and field values).
#include "ablmg/io/vtu.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <filesystem>

using namespace ablmg;

TEST(Vtu, WrittenFileReadsBackWithFields) {
  const Mesh2 m = io::readMesh(std::string(ABLMG_TEST_DATA) + "/square.mesh");
  std::vector<Metric2> metrics(5, Metric2::fromSizes(0.2, 0.05, 0.5));
  auto pointData = io::metricFields(metrics);
  pointData.push_back({"u", 1, {0, 1, 2, 3, 4}});
  const std::vector<io::Field> cellData = {{"quality", 1, {0.9, 0.8, 0.7, 0.6}}};
  const std::string p =
      (std::filesystem::temp_directory_path() / ("ablmg_vtu_" + std::to_string(::getpid()) + ".vtu")).string();
  io::writeVtu(p, m, pointData, cellData);

  vtkNew<vtkXMLUnstructuredGridReader> r;
  r->SetFileName(p.c_str());
  r->Update();
  vtkUnstructuredGrid* g = r->GetOutput();
  EXPECT_EQ(g->GetNumberOfPoints(), 5);
  EXPECT_EQ(g->GetNumberOfCells(), 4);
  EXPECT_DOUBLE_EQ(g->GetPointData()->GetArray("u")->GetComponent(3, 0), 3.0);
  EXPECT_EQ(g->GetPointData()->GetArray("metric")->GetNumberOfComponents(), 3);
  EXPECT_NEAR(g->GetPointData()->GetArray("h2")->GetComponent(2, 0), 0.05, 1e-15);
  EXPECT_NEAR(g->GetPointData()->GetArray("angle")->GetComponent(0, 0), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(g->GetCellData()->GetArray("quality")->GetComponent(2, 0), 0.7);
  EXPECT_EQ(g->GetCellData()->GetArray("ref")->GetComponent(0, 0), 0.0);
  double x[3];
  g->GetPoint(4, x);
  EXPECT_EQ(x[0], 0.5);
  std::filesystem::remove(p);
}

TEST(Vtu, WrongFieldSizeNamesTheField) {
  const Mesh2 m = io::readMesh(std::string(ABLMG_TEST_DATA) + "/square.mesh");
  try {
    io::writeVtu("/tmp/never_written_ablmg.vtu", m, {{"u", 1, {1, 2}}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'u' has 2 values, expected 5"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists("/tmp/never_written_ablmg.vtu"));
}

TEST(Vtu, SurfaceTrianglesIn3D) {
  const std::string p =
      (std::filesystem::temp_directory_path() / ("ablmg_vtu3_" + std::to_string(::getpid()) + ".vtu")).string();
  io::writeVtu(p, {{0, 0, 0}, {1, 0, 0}, {0, 1, 2}}, {{0, 1, 2}}, {}, {{"area", 1, {1.5}}});
  vtkNew<vtkXMLUnstructuredGridReader> r;
  r->SetFileName(p.c_str());
  r->Update();
  double x[3];
  r->GetOutput()->GetPoint(2, x);
  EXPECT_EQ(x[2], 2.0);
  EXPECT_DOUBLE_EQ(r->GetOutput()->GetCellData()->GetArray("area")->GetComponent(0, 0), 1.5);
  EXPECT_THROW(io::writeVtu(p, {{0, 0, 0}}, {{0, 1, 2}}), InputError);  // bad vertex id
  std::filesystem::remove(p);
}
