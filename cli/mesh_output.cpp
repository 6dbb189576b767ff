#include "cli/mesh_output.hpp"

#include "core/error.hpp"
#include "io/medit.hpp"
#include "io/picture.hpp"
#include "io/vtu.hpp"

#include <filesystem>
#include <span>

namespace ablmg::cli {

static std::string extensionOf(const std::string& path) { return std::filesystem::path(path).extension().string(); }

void checkOutputPath(const std::string& path, const std::string& what) {
  const std::string ext = extensionOf(path);
  ABLMG_REQUIRE(ext == ".mesh" || ext == ".vtu" || ext == ".png",
                what << ": output '" << path << "' must end in .mesh, .vtu or .png");
}

void writeMeshOutput(const std::string& path, const Domain& domain, const Mesh2& mesh, const std::vector<Metric2>& metric) {
  checkOutputPath(path, path);
  const std::string ext = extensionOf(path);
  if (ext == ".mesh") {
    io::writeMesh(path, mesh);
    if (metric.size() == mesh.vertices.size()) io::writeSol(std::filesystem::path(path).replace_extension(".sol").string(), metric);
  } else if (ext == ".vtu") {
    io::writeVtu(path, mesh, metric.size() == mesh.vertices.size() ? io::metricFields(metric) : std::vector<io::Field>{});
  } else {
    const bool hasMetric = metric.size() == mesh.vertices.size();
    io::drawBubbles(path, domain, hasMetric ? std::span<const Vec2>(mesh.vertices) : std::span<const Vec2>(), hasMetric ? std::span<const Metric2>(metric) : std::span<const Metric2>(),
                    mesh.triangles.empty() ? nullptr : &mesh);
  }
}

} // namespace ablmg::cli
