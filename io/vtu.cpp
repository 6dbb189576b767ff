#include "ablmg/io/vtu.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

namespace ablmg::io {
namespace {

vtkNew<vtkDoubleArray> toArray(const Field& f, std::size_t entities, const char* kind, const std::string& path) {
  ABLMG_REQUIRE(f.components >= 1,
                path << ": " << kind << " field '" << f.name << "' has " << f.components << " components");
  ABLMG_REQUIRE(f.values.size() == entities * std::size_t(f.components),
                path << ": " << kind << " field '" << f.name << "' has " << f.values.size() << " values, expected "
                     << entities << " × " << f.components);
  vtkNew<vtkDoubleArray> a;
  a->SetName(f.name.c_str());
  a->SetNumberOfComponents(f.components);
  a->SetNumberOfTuples(vtkIdType(entities));
  for (std::size_t i = 0; i < f.values.size(); ++i) a->SetValue(vtkIdType(i), f.values[i]);
  return a;
}

void write(const std::string& path, vtkPoints* points, const std::vector<std::array<int, 3>>& triangles,
           const std::vector<Field>& pointData, const std::vector<Field>& cellData, const std::vector<int>* vertexRefs,
           const std::vector<int>* triangleRefs) {
  const vtkIdType np = points->GetNumberOfPoints();
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->Allocate(vtkIdType(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    vtkIdType ids[3];
    for (int k = 0; k < 3; ++k) {
      ABLMG_REQUIRE(triangles[t][k] >= 0 && triangles[t][k] < np, path << ": triangle " << t << " has vertex id "
                                                                       << triangles[t][k] << " out of range [0, " << np
                                                                       << ")");
      ids[k] = triangles[t][k];
    }
    grid->InsertNextCell(VTK_TRIANGLE, 3, ids);
  }
  for (const auto& f : pointData) grid->GetPointData()->AddArray(toArray(f, std::size_t(np), "point", path));
  for (const auto& f : cellData) grid->GetCellData()->AddArray(toArray(f, triangles.size(), "cell", path));
  if (vertexRefs && vertexRefs->size() == std::size_t(np)) {
    vtkNew<vtkIntArray> a;
    a->SetName("vertexRef");
    for (int r : *vertexRefs) a->InsertNextValue(r);
    grid->GetPointData()->AddArray(a);
  }
  if (triangleRefs && triangleRefs->size() == triangles.size()) {
    vtkNew<vtkIntArray> a;
    a->SetName("ref");
    for (int r : *triangleRefs) a->InsertNextValue(r);
    grid->GetCellData()->AddArray(a);
  }
  writePathAtomically(path, [&](const std::string& tmp) {
    vtkNew<vtkXMLUnstructuredGridWriter> w;
    w->SetFileName(tmp.c_str());
    w->SetInputData(grid);
    w->SetDataModeToAppended();
    w->SetCompressorTypeToZLib();
    if (w->Write() != 1) ABLMG_FAIL(path << ": VTK writer failed");
  });
}

}  // namespace

void writeVtu(const std::string& path, const Mesh2& mesh, const std::vector<Field>& pointData,
              const std::vector<Field>& cellData) {
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(mesh.numVertices());
  for (int i = 0; i < mesh.numVertices(); ++i) pts->SetPoint(i, mesh.vertices[i].x(), mesh.vertices[i].y(), 0.0);
  write(path, pts, mesh.triangles, pointData, cellData, &mesh.vertexRefs, &mesh.triangleRefs);
}

void writeVtu(const std::string& path, const std::vector<Eigen::Vector3d>& points,
              const std::vector<std::array<int, 3>>& triangles, const std::vector<Field>& pointData,
              const std::vector<Field>& cellData) {
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(vtkIdType(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    pts->SetPoint(vtkIdType(i), points[i].x(), points[i].y(), points[i].z());
  write(path, pts, triangles, pointData, cellData, nullptr, nullptr);
}

std::vector<Field> metricFields(std::span<const Metric2> metrics) {
  Field m{"metric", 3, {}}, h1{"h1", 1, {}}, h2{"h2", 1, {}}, angle{"angle", 1, {}};
  for (const auto& x : metrics) {
    m.values.insert(m.values.end(), {x.m11(), x.m12(), x.m22()});
    const auto e = x.eigen();
    h1.values.push_back(e.h1);
    h2.values.push_back(e.h2);
    angle.values.push_back(e.theta);
  }
  return {m, h1, h2, angle};
}

}  // namespace ablmg::io
