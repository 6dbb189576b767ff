// Reference solutions and the interface check of adaptive_loop.hpp, for problems without an
// exact solution (the material problems of fem/material_problems.hpp).
#include "ablmg/adapt/adaptive_loop.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/point_locator.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

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

double uncoveredInterfaceLength(const Mesh2& input, const Mesh2& output) {
  double uncovered = 0;
  for (const auto& e : input.interfaceEdges) {
    const Vec2 a = input.vertices[std::size_t(e.a)], b = input.vertices[std::size_t(e.b)];
    const double len = (b - a).norm();
    const auto onLine = [&](const Vec2& p) { return std::abs(cross(b - a, p - a)) <= 1e-12 * len * len; };
    const auto param = [&](const Vec2& p) { return (p - a).dot(b - a) / (len * len); };
    double covered = 0;
    for (const auto& f : output.interfaceEdges) {
      const Vec2 p = output.vertices[std::size_t(f.a)], q = output.vertices[std::size_t(f.b)];
      if (!onLine(p) || !onLine(q)) continue;
      const double lo = std::max(0.0, std::min(param(p), param(q))), hi = std::min(1.0, std::max(param(p), param(q)));
      if (hi > lo) covered += (hi - lo) * len;
    }
    uncovered += std::max(0.0, len - covered);
  }
  return uncovered;
}

}  // namespace ablmg::adapt
