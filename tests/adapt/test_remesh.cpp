// Mirrors adapt/remesh.hpp: remesh(mesh, metric, options) on structured meshes of a polygon
// with a hole (the domain comes from the input's boundary): the output is valid, covers the
// same area, keeps the boundary refs on the right sides; hmin/hmax move the vertex count the
// right way; bad input is an InputError naming what is wrong; same input, same mesh; the
// result equals the composition of its steps run by hand.
#include "ablmg/adapt/remesh.hpp"

#include "ablmg/core/domain_from_mesh.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/fem/structured_mesh.hpp"
#include "ablmg/mesher/quality.hpp"

#include <gtest/gtest.h>

#include "square_with_hole.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

using namespace ablmg;
using namespace ablmg::adapt;

namespace {

using test::squareWithHole;

/// A perturbed structured mesh of squareWithHole() (cells 0.25 wide, 280 vertices).
Mesh2 inputMesh() { return fem::structuredMesh(squareWithHole(), 16, 16, 0.15, 7); }

/// Anisotropic, varying with x: h1 from 0.08 to 0.2 along x, h2 = 2 h1 along y.
std::vector<Metric2> inputMetric(const Mesh2& mesh) {
  std::vector<Metric2> m;
  for (const Vec2& p : mesh.vertices) m.push_back(Metric2::fromSizes(0.08 + 0.03 * p.x(), 0.16 + 0.06 * p.x(), 0.0));
  return m;
}

std::vector<Metric2> isotropic(const Mesh2& mesh, double h) {
  return std::vector<Metric2>(std::size_t(mesh.numVertices()), Metric2::isotropic(h));
}

/// Runs f and returns the InputError's message ("" if nothing or something else was thrown).
template <class F>
std::string inputErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) { return e.what(); } catch (...) {
    return "(not an InputError)";
  }
  return "";
}

}  // namespace

TEST(Remesh, OutputIsValidAndCoversTheInputArea) {
  const Mesh2 in = inputMesh();
  ASSERT_TRUE(in.validate().ok);
  const RemeshResult r = remesh(in, inputMetric(in), {});
  const MeshValidation v = r.mesh.validate(in.area(), 1e-9);  // 16 − 1, up to round-off
  EXPECT_TRUE(v.ok) << v.firstProblem;
  EXPECT_NEAR(r.mesh.area(), 15.0, 15.0 * 1e-9);
  EXPECT_EQ(long(r.metric.size()), long(r.mesh.numVertices()));
  EXPECT_GT(r.mesh.numVertices(), in.numVertices());  // the metric is finer than the input
  EXPECT_GT(r.stats.placement.steps, 0);
}

TEST(Remesh, BoundaryRefsStayOnTheirSides) {
  const Mesh2 in = inputMesh();
  const RemeshResult r = remesh(in, inputMetric(in), {});
  // The side of each ref: a point on it (up to round-off of the mesher's interpolation).
  const auto onSide = [](int ref, const Vec2& p) {
    const auto is = [](double a, double b) { return std::abs(a - b) <= 1e-12; };
    const auto in = [](double a, double lo, double hi) { return a >= lo - 1e-12 && a <= hi + 1e-12; };
    switch (ref) {
      case 1:
        return is(p.y(), 0) && in(p.x(), 0, 4);
      case 2:
        return is(p.x(), 4) && in(p.y(), 0, 4);
      case 3:
        return is(p.y(), 4) && in(p.x(), 0, 4);
      case 4:
        return is(p.x(), 0) && in(p.y(), 0, 4);
      case 5:
        return (is(p.x(), 1) || is(p.x(), 2) || is(p.y(), 1) || is(p.y(), 2)) && in(p.x(), 1, 2) && in(p.y(), 1, 2);
      default:
        return false;
    }
  };
  std::set<int> refs;
  double length[6] = {0, 0, 0, 0, 0, 0};
  for (const auto& e : r.mesh.boundaryEdges) {
    refs.insert(e.ref);
    const Vec2 a = r.mesh.vertices[std::size_t(e.a)], b = r.mesh.vertices[std::size_t(e.b)];
    EXPECT_TRUE(onSide(e.ref, a) && onSide(e.ref, b))
        << "edge (" << a.transpose() << ")-(" << b.transpose() << ") has ref " << e.ref;
    if (e.ref >= 1 && e.ref <= 5) length[e.ref] += (b - a).norm();
  }
  EXPECT_EQ(refs, (std::set<int>{1, 2, 3, 4, 5}));
  for (int ref = 1; ref <= 5; ++ref) EXPECT_NEAR(length[ref], 4.0, 1e-12) << "ref " << ref;  // each side once
}

TEST(Remesh, HmaxRefinesACoarseMetricAndHminCoarsensAFineOne) {
  const Mesh2 in = inputMesh();
  RemeshOptions o;
  o.hgrad = -1;  // sizes of the output metric then stay within [hmin, hmax] exactly
  // Coarse metric (h = 0.5): hmax = 0.2 clamps every size, so many more vertices.
  const RemeshResult coarse = remesh(in, isotropic(in, 0.5), o);
  o.hmax = 0.2;
  const RemeshResult capped = remesh(in, isotropic(in, 0.5), o);
  EXPECT_EQ(coarse.clampedMetrics, 0);
  EXPECT_EQ(capped.clampedMetrics, in.numVertices());
  EXPECT_GT(capped.mesh.numVertices(), 3 * coarse.mesh.numVertices());
  for (const Metric2& m : capped.metric) EXPECT_LE(m.eigen().h1, 0.2 * (1 + 1e-9));
  // Fine metric (h = 0.05): hmin = 0.1 caps the vertex count at about a quarter.
  o.hmax = std::numeric_limits<double>::infinity();
  const RemeshResult fine = remesh(in, isotropic(in, 0.05), o);
  o.hmin = 0.1;
  const RemeshResult floored = remesh(in, isotropic(in, 0.05), o);
  EXPECT_EQ(floored.clampedMetrics, in.numVertices());
  EXPECT_LT(floored.mesh.numVertices(), fine.mesh.numVertices() / 3);
  for (const Metric2& m : floored.metric) EXPECT_GE(m.eigen().h2, 0.1 * (1 - 1e-9));
  EXPECT_TRUE(floored.mesh.validate(15.0, 1e-9).ok);
}

TEST(Remesh, GradationSpreadsAFineSpot) {
  const Mesh2 in = inputMesh();
  // One fine vertex in a coarse field: gradation spreads it, so more vertices than without.
  std::vector<Metric2> m = isotropic(in, 0.5);
  m[std::size_t(in.numVertices() / 2)] = Metric2::isotropic(0.02);
  RemeshOptions o;
  o.hgrad = -1;
  const RemeshResult off = remesh(in, m, o);
  o.hgrad = 1.3;
  const RemeshResult on = remesh(in, m, o);
  EXPECT_EQ(off.gradation.corrections, 0);
  EXPECT_GT(on.gradation.corrections, 0);
  EXPECT_TRUE(on.gradation.converged);
  EXPECT_GT(on.mesh.numVertices(), off.mesh.numVertices());
}

TEST(Remesh, MetricCountMismatchIsAnInputErrorNamingBothCounts) {
  const Mesh2 in = inputMesh();
  std::vector<Metric2> m = isotropic(in, 0.2);
  m.resize(3);
  const std::string what = inputErrorOf([&] { remesh(in, m); });
  EXPECT_NE(what.find("3 metrics"), std::string::npos) << what;
  EXPECT_NE(what.find(std::to_string(in.numVertices()) + " vertices"), std::string::npos) << what;
}

TEST(Remesh, OptionsOutOfRangeAreInputErrorsNamingTheField) {
  const Mesh2 in = inputMesh();
  const auto message = [&](auto set) {
    RemeshOptions o;
    set(o);
    return inputErrorOf([&] { remesh(in, isotropic(in, 0.2), o); });
  };
  EXPECT_NE(message([](RemeshOptions& o) { o.hmin = -1; }).find("hmin"), std::string::npos);
  EXPECT_NE(message([](RemeshOptions& o) { o.hmin = NAN; }).find("hmin"), std::string::npos);
  EXPECT_NE(message([](RemeshOptions& o) { o.hmax = 0; }).find("hmax"), std::string::npos);
  EXPECT_NE(message([](RemeshOptions& o) {
              o.hmin = 0.3;
              o.hmax = 0.3;
            }).find("hmax"),
            std::string::npos);
  EXPECT_NE(message([](RemeshOptions& o) { o.hgrad = 1; }).find("hgrad"), std::string::npos);
  EXPECT_NE(message([](RemeshOptions& o) { o.hgrad = 0.5; }).find("hgrad"), std::string::npos);
  EXPECT_NE(message([](RemeshOptions& o) { o.hgrad = NAN; }).find("hgrad"), std::string::npos);
  EXPECT_EQ(message([](RemeshOptions& o) { o.hgrad = 0; }), "");  // ≤ 0: no gradation
}

TEST(Remesh, InvalidInputsAreInputErrors) {
  Mesh2 in = inputMesh();
  // A non-SPD metric (Metric2::raw skips the checks of fromTensor).
  std::vector<Metric2> m = isotropic(in, 0.2);
  m[5] = Metric2::raw(1, 2, 1);
  EXPECT_NE(inputErrorOf([&] { remesh(in, m); }).find("metric[5] (1, 2, 1) is not positive definite"),
            std::string::npos);
  // A triangle turned clockwise: named as an invalid mesh, under the options' name.
  std::swap(in.triangles[10][1], in.triangles[10][2]);
  RemeshOptions o;
  o.name = "solver mesh";
  const std::string what = inputErrorOf([&] { remesh(in, isotropic(in, 0.2), o); });
  EXPECT_EQ(what.rfind("solver mesh: invalid mesh: ", 0), 0u) << what;
}

TEST(Remesh, SameInputSameMesh) {
  const Mesh2 in = inputMesh();
  const RemeshResult a = remesh(in, inputMetric(in), {});
  RemeshOptions skip;
  skip.inputCheck = BackgroundMetricField::MeshCheck::AlreadyValidated;  // the check changes nothing
  const RemeshResult b = remesh(in, inputMetric(in), skip);
  ASSERT_EQ(a.mesh.numVertices(), b.mesh.numVertices());
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  ASSERT_EQ(a.metric.size(), b.metric.size());
  for (std::size_t v = 0; v < a.metric.size(); ++v)
    EXPECT_TRUE(a.metric[v].m11() == b.metric[v].m11() && a.metric[v].m12() == b.metric[v].m12() &&
                a.metric[v].m22() == b.metric[v].m22())
        << "vertex " << v;
}

TEST(Remesh, EqualsTheCompositionTheCommandLineRan) {
  // The steps of remesh() run by hand: clamp, gradation, domain from the boundary,
  // background field, meshDomain with the plateau stop.
  const Mesh2 in = inputMesh();
  const double hmin = 0.09, hmax = 0.15;
  std::vector<Metric2> metric = inputMetric(in);
  for (auto& m : metric) {
    const auto e = m.eigen();
    const double h1 = std::clamp(e.h1, hmin, hmax), h2 = std::clamp(e.h2, hmin, hmax);
    if (h1 != e.h1 || h2 != e.h2) m = Metric2::fromSizes(h1, h2, e.theta);
  }
  limitGradation(in, metric, {.hgrad = 1.3});
  const Domain domain = domainFromMeshBoundary(in, "in");
  mesher::MeshOptions meshOptions;
  meshOptions.placement.plateauSteps = 10;
  meshOptions.placement.plateauGain = 0.01;
  meshOptions.placement.finalRelaxSteps = 0;
  const mesher::MeshResult expected = mesher::meshDomain(domain, BackgroundMetricField(in, metric), meshOptions);

  RemeshOptions o;
  o.hmin = hmin;
  o.hmax = hmax;
  const RemeshResult r = remesh(in, inputMetric(in), o);
  EXPECT_GT(r.clampedMetrics, 0);
  EXPECT_EQ(r.mesh.vertices, expected.mesh.vertices);
  EXPECT_EQ(r.mesh.triangles, expected.mesh.triangles);
  ASSERT_EQ(r.mesh.boundaryEdges.size(), expected.mesh.boundaryEdges.size());
  for (std::size_t i = 0; i < r.mesh.boundaryEdges.size(); ++i)
    EXPECT_EQ(r.mesh.boundaryEdges[i].ref, expected.mesh.boundaryEdges[i].ref);
}

TEST(Remesh, KnownDomainOverloadKeepsTheGivenDomain) {
  // remesh(domain, mesh, metric): the domain is the caller's, not the input's boundary.
  const Mesh2 in = fem::unitSquareMesh(8);
  const mesher::MeshResult r = remesh(Domain::rectangle(0, 0, 1, 1), in, isotropic(in, 0.1));
  EXPECT_TRUE(r.mesh.validate(1.0, 1e-9).ok);
  EXPECT_EQ(long(r.metric.size()), long(r.mesh.numVertices()));
}

TEST(Remesh, TheHeadersSolverLoopRuns) {
  // The usage sample of adapt/remesh.hpp, with a stand-in solver (u = x) and a metric that
  // halves the size every cycle.
  int cycle = 0;
  const auto myMesh = [] { return inputMesh(); };
  const auto mySolve = [](const Mesh2& m) {
    std::vector<double> u;
    for (const Vec2& p : m.vertices) u.push_back(p.x());
    return u;
  };
  const auto myMetric = [&cycle](const Mesh2& m, const std::vector<double>& u) {
    EXPECT_EQ(long(u.size()), long(m.numVertices()));
    return isotropic(m, 0.4 / std::pow(2.0, cycle));
  };
  ablmg::Mesh2 mesh = myMesh();
  ablmg::adapt::RemeshOptions options;
  options.hmin = 1e-4;
  options.hmax = 0.1;
  std::vector<long> vertices;
  for (cycle = 0; cycle < 5; ++cycle) {
    const std::vector<double> u = mySolve(mesh);
    std::vector<ablmg::Metric2> metric = myMetric(mesh, u);
    ablmg::adapt::RemeshResult r = ablmg::adapt::remesh(std::move(mesh), std::move(metric), options);
    mesh = std::move(r.mesh);
    EXPECT_TRUE(mesh.validate(15.0, 1e-9).ok) << "cycle " << cycle;
    vertices.push_back(mesh.numVertices());
  }
  // Sizes 0.4, 0.2, 0.1 are 0.1 after the clamp (cycles 0–2), then 0.05, 0.025: ×4 vertices per halving.
  EXPECT_NEAR(double(vertices[1]) / vertices[0], 1.0, 0.05);
  EXPECT_NEAR(double(vertices[2]) / vertices[1], 1.0, 0.05);
  EXPECT_NEAR(double(vertices[3]) / vertices[2], 4.0, 0.6);
  EXPECT_NEAR(double(vertices[4]) / vertices[3], 4.0, 0.6);
}

// A mesh remeshed to its own metric (as a solver hands over a converged pair) starts from its
// own vertices and keeps their fit; a hand-over to a new metric (half the sizes) starts from
// the lattice. The warm start must not lose edges within ±10 % against the cold start.
TEST(Remesh, WarmStartsOnlyWhenTheInputFitsItsMetric) {
  const Mesh2 in = inputMesh();
  RemeshOptions o;
  o.hgrad = -1;
  const RemeshResult first = remesh(in, isotropic(in, 0.12), o);  // a mesh made for h = 0.12
  EXPECT_FALSE(first.warmStarted);
  EXPECT_LT(first.inputWithin10, 0.5);
  const std::vector<Metric2> own(std::size_t(first.mesh.numVertices()), Metric2::isotropic(0.12));
  const RemeshResult warm = remesh(first.mesh, own, o);
  EXPECT_TRUE(warm.warmStarted);
  EXPECT_GE(warm.inputWithin10, 0.5);
  o.warmStart = RemeshOptions::WarmStart::Off;
  const RemeshResult cold = remesh(first.mesh, own, o);
  EXPECT_FALSE(cold.warmStarted);
  EXPECT_TRUE(warm.mesh.validate().ok);
  const auto within = [](const RemeshResult& r) {
    return mesher::edgeLengthStats(mesher::edgeMetricLengths(r.mesh, r.metric)).within10;
  };
  EXPECT_GE(within(warm), within(cold) - 0.01);
  o.warmStart = RemeshOptions::WarmStart::IfFits;
  const std::vector<Metric2> finer(std::size_t(first.mesh.numVertices()), Metric2::isotropic(0.06));
  EXPECT_FALSE(remesh(first.mesh, finer, o).warmStarted);
}
