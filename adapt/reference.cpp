// Reference solutions and the interface check of adaptive_loop.hpp, for problems without an
// exact solution (the material problems of fem/material_problems.hpp).
#include "ablmg/adapt/adaptive_loop.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/point_locator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace ablmg::adapt {
namespace {

/// The reference mesh and u_h, and a locator on that mesh (built after the mesh is in place:
/// the locator keeps a reference to it, so this object never moves).
struct ReferenceField {
  Mesh2 mesh;
  Eigen::VectorXd u;
  PointLocator locator;
  ReferenceField(Mesh2 m, Eigen::VectorXd values) : mesh(std::move(m)), u(std::move(values)), locator(mesh) {}

  double value(double x, double y) const {
    const auto loc = locator.locate(Vec2(x, y));
    const auto& t = mesh.triangles[std::size_t(loc.triangle)];
    return loc.bary[0] * u[t[0]] + loc.bary[1] * u[t[1]] + loc.bary[2] * u[t[2]];
  }
  Vec2 gradient(double x, double y) const {
    const auto loc = locator.locate(Vec2(x, y));
    const auto& t = mesh.triangles[std::size_t(loc.triangle)];
    const Vec2 p0 = mesh.vertices[std::size_t(t[0])], p1 = mesh.vertices[std::size_t(t[1])],
               p2 = mesh.vertices[std::size_t(t[2])];
    const double twiceArea = cross(p1 - p0, p2 - p0);
    // ∇λ_k = perp(opposite edge) / 2|T|
    const Vec2 g0(p1.y() - p2.y(), p2.x() - p1.x()), g1(p2.y() - p0.y(), p0.x() - p2.x()),
        g2(p0.y() - p1.y(), p1.x() - p0.x());
    return (u[t[0]] * g0 + u[t[1]] * g1 + u[t[2]] * g2) / twiceArea;
  }
};

}  // namespace

ReferenceSolution referenceSolution(const AdaptProblem& problem, double vertices, const AdaptOptions& options) {
  AdaptOptions o = options;
  // Two passes per size (the schedule its figures were measured with; the default's third
  // pass would add a third of the cycles below 10⁴).
  o.targetVertices = geometricSchedule(vertices, {.passes = 2});
  o.cycles = 0;
  o.stopL2 = o.stopH1 = 0;
  AdaptProblem p = problem;
  p.exact.reset();
  std::shared_ptr<ReferenceField> field;
  runAdaptiveLoop(p, o, [&](const CycleData& c) {
    if (c.nextMetric.empty()) field = std::make_shared<ReferenceField>(c.mesh, c.u);
  });
  ABLMG_REQUIRE(field, "referenceSolution: the loop ended without a last cycle");
  ReferenceSolution r;
  r.vertices = field->mesh.numVertices();
  r.exact.u = [field](double x, double y) { return field->value(x, y); };
  r.exact.grad = [field](double x, double y) { return field->gradient(x, y); };
  r.exact.threadSafe = true;
  return r;
}

namespace {

/// Bucket grid of segments: a segment is listed in every cell that one of its sample points
/// (spaced by half a cell) falls in, so two segments sharing a piece of length > 0 are listed
/// in the same or in neighbouring cells.
class SegmentGrid {
 public:
  explicit SegmentGrid(double cell) : cell_(cell) {}

  void add(int id, const Vec2& p, const Vec2& q) {
    for (const auto key : cellsAlong(p, q)) cells_[key].push_back(id);
  }
  /// Ids of the segments listed in the cells around the samples of pq, sorted, unique.
  std::vector<int> near(const Vec2& p, const Vec2& q) const {
    std::vector<int> ids;
    for (const auto key : cellsAlong(p, q))
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy) {
          const auto it = cells_.find(key + pack(dx, dy));
          if (it != cells_.end()) ids.insert(ids.end(), it->second.begin(), it->second.end());
        }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
  }

 private:
  static std::int64_t pack(std::int64_t i, std::int64_t j) { return i * (std::int64_t(1) << 32) + j; }
  std::vector<std::int64_t> cellsAlong(const Vec2& p, const Vec2& q) const {
    const int samples = 1 + int(std::ceil(2 * (q - p).norm() / cell_));
    std::vector<std::int64_t> keys;
    for (int k = 0; k <= samples; ++k) {
      const Vec2 s = p + (q - p) * (double(k) / samples);
      keys.push_back(pack(std::int64_t(std::floor(s.x() / cell_)), std::int64_t(std::floor(s.y() / cell_))));
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
  }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

}  // namespace

std::vector<double> interfaceCoverage(const Mesh2& input, const Mesh2& output) {
  std::vector<double> covered(input.interfaceEdges.size(), 0.0);
  if (covered.empty()) return covered;
  const auto endpoints = [](const Mesh2& m, const BoundaryEdge& e) {
    return std::pair(m.vertices[std::size_t(e.a)], m.vertices[std::size_t(e.b)]);
  };
  double meanLength = 0;
  for (const auto& e : input.interfaceEdges) {
    const auto [a, b] = endpoints(input, e);
    meanLength += (b - a).norm() / double(input.interfaceEdges.size());
  }
  if (!(meanLength > 0)) return covered;
  SegmentGrid grid(meanLength);
  for (std::size_t k = 0; k < output.interfaceEdges.size(); ++k) {
    const auto [p, q] = endpoints(output, output.interfaceEdges[k]);
    grid.add(int(k), p, q);
  }
  for (std::size_t i = 0; i < covered.size(); ++i) {
    const auto ends = endpoints(input, input.interfaceEdges[i]);
    const Vec2 a = ends.first, b = ends.second;  // plain variables: lambdas below capture them
    const double len2 = (b - a).squaredNorm();
    const auto onLine = [&](const Vec2& p) { return std::abs(cross(b - a, p - a)) <= 1e-12 * len2; };
    const auto param = [&](const Vec2& p) { return (p - a).dot(b - a) / len2; };
    for (const int k : grid.near(a, b)) {
      const auto [p, q] = endpoints(output, output.interfaceEdges[std::size_t(k)]);
      if (!onLine(p) || !onLine(q)) continue;
      const double lo = std::max(0.0, std::min(param(p), param(q))), hi = std::min(1.0, std::max(param(p), param(q)));
      if (hi > lo) covered[i] += (hi - lo) * std::sqrt(len2);
    }
  }
  return covered;
}

double uncoveredInterfaceLength(const Mesh2& input, const Mesh2& output) {
  const std::vector<double> covered = interfaceCoverage(input, output);
  double uncovered = 0;
  for (std::size_t i = 0; i < covered.size(); ++i) {
    const auto& e = input.interfaceEdges[i];
    const double len = (input.vertices[std::size_t(e.b)] - input.vertices[std::size_t(e.a)]).norm();
    uncovered += std::max(0.0, len - covered[i]);
  }
  return uncovered;
}

}  // namespace ablmg::adapt
