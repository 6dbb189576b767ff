#include "ablmg/cli/mesh_output.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/picture.hpp"
#include "ablmg/io/vtu.hpp"
#include "ablmg/mesher/quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <filesystem>
#include <span>

namespace ablmg::cli {

static std::string extensionOf(const std::string& path) { return std::filesystem::path(path).extension().string(); }

void checkOutputPath(const std::string& path, const std::string& what) {
  const std::string ext = extensionOf(path);
  ABLMG_REQUIRE(ext == ".mesh" || ext == ".vtu" || ext == ".png",
                what << ": output '" << path << "' must end in .mesh, .vtu or .png");
}

QualityFields qualityFields(const Mesh2& mesh, std::span<const Metric2> metric) {
  QualityFields f;
  if (mesh.triangles.empty()) return f;
  f.cell.push_back({"quality", 1, mesher::elementQualities(mesh, metric)});
  const auto edges = mesh.edges();
  const auto lengths = mesher::edgeMetricLengths(mesh, metric);
  io::Field lo{"edge_length_min", 1,
               std::vector<double>(mesh.vertices.size(), std::numeric_limits<double>::infinity())};
  io::Field hi{"edge_length_max", 1, std::vector<double>(mesh.vertices.size(), 0.0)};
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (int v : {edges[e][0], edges[e][1]}) {
      lo.values[std::size_t(v)] = std::min(lo.values[std::size_t(v)], lengths[e]);
      hi.values[std::size_t(v)] = std::max(hi.values[std::size_t(v)], lengths[e]);
    }
  for (double& x : lo.values)
    if (!std::isfinite(x)) x = 0;  // a vertex on no edge
  f.point.push_back(std::move(lo));
  f.point.push_back(std::move(hi));
  return f;
}

void writeMeshOutput(const std::string& path, const Domain& domain, const Mesh2& mesh,
                     const std::vector<Metric2>& metric) {
  checkOutputPath(path, path);
  const std::string ext = extensionOf(path);
  if (ext == ".mesh") {
    io::writeMesh(path, mesh);
    if (metric.size() == mesh.vertices.size())
      io::writeSol(std::filesystem::path(path).replace_extension(".sol").string(), metric);
  } else if (ext == ".vtu") {
    std::vector<io::Field> point, cell;
    if (metric.size() == mesh.vertices.size()) {
      point = io::metricFields(metric);
      auto q = qualityFields(mesh, metric);
      for (auto& f : q.point) point.push_back(std::move(f));
      cell = std::move(q.cell);
    }
    io::writeVtu(path, mesh, point, cell);
  } else {
    const bool hasMetric = metric.size() == mesh.vertices.size();
    io::drawBubbles(path, domain, hasMetric ? std::span<const Vec2>(mesh.vertices) : std::span<const Vec2>(),
                    hasMetric ? std::span<const Metric2>(metric) : std::span<const Metric2>(),
                    mesh.triangles.empty() ? nullptr : &mesh);
  }
}

}  // namespace ablmg::cli
