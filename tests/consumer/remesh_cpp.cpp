// A solver's loop on ablmg's C++ API, from an installed package: mesh [0,2]×[0,1] for a
// metric given by a function (a layer along x = 1 that sharpens each cycle), then remesh
// three times to that function sampled at the current mesh's vertices, as a solver hands over
// its recovered metric. Each mesh must be valid, cover the domain's area, keep the four
// boundary refs, and meet the quality figures; the vertex count must grow as the layer
// thins. Exit 0 and one line per cycle, or 1 and the failed check.
#include <ablmg/adapt/remesh.hpp>
#include <ablmg/mesher/mesher.hpp>
#include <ablmg/mesher/quality.hpp>

#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

namespace {

/// Sizes: h1 = 0.1 along x far from the layer, down to `width` at x = 1; h2 = 0.1 along y.
ablmg::Metric2 layerMetric(const ablmg::Vec2& p, double width) {
  const double d = std::abs(p.x() - 1);
  const double hx = std::min(0.1, width + 0.5 * d);
  return ablmg::Metric2::fromSizes(hx, 0.1, 0.0);
}

class LayerField final : public ablmg::MetricField {
 public:
  explicit LayerField(double width) : width_(width) {}
  ablmg::Metric2 at(const ablmg::Vec2& p) const override { return layerMetric(p, width_); }

 private:
  double width_;
};

bool check(bool ok, const char* what, int cycle) {
  if (!ok) std::fprintf(stderr, "remesh_cpp: cycle %d: %s\n", cycle, what);
  return ok;
}

}  // namespace

int main() {
  try {
    const ablmg::Domain domain = ablmg::Domain::rectangle(0, 0, 2, 1);
    ablmg::Mesh2 mesh = ablmg::mesher::meshDomain(domain, LayerField(0.05)).mesh;
    int previous = mesh.numVertices();
    for (int cycle = 1; cycle <= 3; ++cycle) {
      const double width = 0.05 / std::pow(2.0, cycle);
      std::vector<ablmg::Metric2> metric;
      for (const auto& p : mesh.vertices) metric.push_back(layerMetric(p, width));
      ablmg::adapt::RemeshOptions options;
      options.hmin = 1e-3;
      ablmg::adapt::RemeshResult r = ablmg::adapt::remesh(std::move(mesh), std::move(metric), options);
      mesh = std::move(r.mesh);
      const auto q = ablmg::mesher::meshQuality(mesh, r.metric);
      std::set<int> refs;
      for (const auto& e : mesh.boundaryEdges) refs.insert(e.ref);
      std::printf("cycle %d: %d vertices, %d triangles, q min %.3f mean %.3f, %.1f %% of edges in [1/sqrt2, sqrt2]\n",
                  cycle, mesh.numVertices(), mesh.numTriangles(), q.elements.min, q.elements.mean,
                  100 * q.edgeLengths.inSqrt2);
      if (!check(mesh.validate(2.0, 1e-9).ok, "invalid mesh or wrong area", cycle) ||
          !check(refs == std::set<int>{1, 2, 3, 4}, "boundary refs lost", cycle) ||
          !check(q.elements.min > 0.3 && q.elements.mean > 0.9, "quality below q min 0.3, mean 0.9", cycle) ||
          !check(q.edgeLengths.inSqrt2 > 0.95, "fewer than 95 % of edges in [1/sqrt2, sqrt2]", cycle) ||
          !check(mesh.numVertices() > previous, "the vertex count did not grow as the layer thinned", cycle))
        return 1;
      previous = mesh.numVertices();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "remesh_cpp: %s\n", e.what());
    return 1;
  }
  return 0;
}
