// Mirrors capi/ablmg.h: the C interface remeshes a medit pair read into arrays to the same
// mesh and metric as adapt::remesh with `ablmg remesh`'s options (the files' bytes are
// compared in tests/capi/capi.cmake); 0- and 1-based indices and either orientation give the
// same result; every hostile input of docs/hostile_inputs.md that arrays can carry gets its
// own status code and a message naming the array, index or value, and leaves the handle usable;
// getters refuse wrong counts; the seed and threads options keep the result deterministic;
// ablmg_transfer reproduces linear fields, keeps integrals and refuses bad calls.
#include "ablmg/capi/ablmg.h"

#include "ablmg/adapt/remesh.hpp"
#include "ablmg/adapt/transfer.hpp"
#include "ablmg/io/medit.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace ablmg;

namespace {

struct HandleDeleter {
  void operator()(ablmg_t* h) const { ablmg_free(h); }
};
using Handle = std::unique_ptr<ablmg_t, HandleDeleter>;

/// A medit pair as the arrays of ablmg.h (1-based, as a caller reading the file would have).
struct Arrays {
  std::vector<double> xy, metric;
  std::vector<int> vrefs, tri, trefs, edges, erefs;
  int n = 0, m = 0, k = 0;
};

Arrays arraysOf(const Mesh2& mesh, const std::vector<Metric2>& metric) {
  Arrays a;
  a.n = mesh.numVertices();
  a.m = mesh.numTriangles();
  a.k = int(mesh.boundaryEdges.size());
  for (int i = 0; i < a.n; ++i) {
    a.xy.push_back(mesh.vertices[std::size_t(i)].x());
    a.xy.push_back(mesh.vertices[std::size_t(i)].y());
    a.vrefs.push_back(mesh.vertexRefs.empty() ? 0 : mesh.vertexRefs[std::size_t(i)]);
  }
  for (int t = 0; t < a.m; ++t) {
    for (int v : mesh.triangles[std::size_t(t)]) a.tri.push_back(v + 1);
    a.trefs.push_back(mesh.triangleRefs.empty() ? 0 : mesh.triangleRefs[std::size_t(t)]);
  }
  for (const auto& e : mesh.boundaryEdges) {
    a.edges.push_back(e.a + 1);
    a.edges.push_back(e.b + 1);
    a.erefs.push_back(e.ref);
  }
  for (const auto& t : metric) {
    a.metric.push_back(t.m11());
    a.metric.push_back(t.m12());
    a.metric.push_back(t.m22());
  }
  return a;
}

Arrays fileArrays(const std::string& base) {
  const std::string dir = ABLMG_TEST_DATA;
  const Mesh2 mesh = io::readMesh(dir + "/" + base + ".mesh");
  return arraysOf(mesh, io::readSol(dir + "/" + base + ".sol", mesh.numVertices()));
}

/// Sets every array of `a` on h (1-based); returns the first failing status.
int setAll(ablmg_t* h, const Arrays& a) {
  int rc = ablmg_set_vertices(h, a.xy.data(), a.vrefs.data(), a.n);
  if (rc == ABLMG_OK) rc = ablmg_set_triangles(h, a.tri.data(), a.trefs.data(), a.m, 1);
  if (rc == ABLMG_OK) rc = ablmg_set_edges(h, a.edges.data(), a.erefs.data(), a.k, 1);
  if (rc == ABLMG_OK) rc = ablmg_set_metric(h, a.metric.data(), int(a.metric.size() / 3));
  return rc;
}

/// The result of h as a Mesh2 and its metric, through the getters (0-based).
std::pair<Mesh2, std::vector<Metric2>> resultOf(ablmg_t* h) {
  int nv = 0, nt = 0, ne = 0;
  EXPECT_EQ(ablmg_get_sizes(h, &nv, &nt, &ne), ABLMG_OK);
  std::vector<double> xy(2 * std::size_t(nv)), m(3 * std::size_t(nv));
  std::vector<int> vrefs(static_cast<std::size_t>(nv)), tri(3 * std::size_t(nt)), trefs(static_cast<std::size_t>(nt)),
      edges(2 * std::size_t(ne)), erefs(static_cast<std::size_t>(ne));
  EXPECT_EQ(ablmg_get_vertices(h, xy.data(), vrefs.data(), nv), ABLMG_OK);
  EXPECT_EQ(ablmg_get_triangles(h, tri.data(), trefs.data(), nt, 0), ABLMG_OK);
  EXPECT_EQ(ablmg_get_edges(h, edges.data(), erefs.data(), ne, 0), ABLMG_OK);
  EXPECT_EQ(ablmg_get_metric(h, m.data(), nv), ABLMG_OK);
  Mesh2 mesh;
  std::vector<Metric2> metric;
  for (int i = 0; i < nv; ++i) {
    mesh.vertices.emplace_back(xy[2 * std::size_t(i)], xy[2 * std::size_t(i) + 1]);
    mesh.vertexRefs.push_back(vrefs[std::size_t(i)]);
    metric.push_back(Metric2::raw(m[3 * std::size_t(i)], m[3 * std::size_t(i) + 1], m[3 * std::size_t(i) + 2]));
  }
  for (int t = 0; t < nt; ++t) {
    mesh.triangles.push_back({tri[3 * std::size_t(t)], tri[3 * std::size_t(t) + 1], tri[3 * std::size_t(t) + 2]});
    mesh.triangleRefs.push_back(trefs[std::size_t(t)]);
  }
  for (int e = 0; e < ne; ++e)
    mesh.boundaryEdges.push_back({edges[2 * std::size_t(e)], edges[2 * std::size_t(e) + 1], erefs[std::size_t(e)]});
  return {std::move(mesh), std::move(metric)};
}

/// What `ablmg remesh -in base.mesh -sol base.sol` computes (cli/cmd_remesh.cpp's options).
adapt::RemeshResult cliRemesh(const std::string& base) {
  const std::string dir = ABLMG_TEST_DATA;
  Mesh2 mesh = io::readMesh(dir + "/" + base + ".mesh");
  auto metric = io::readSol(dir + "/" + base + ".sol", mesh.numVertices());
  adapt::RemeshOptions options;
  options.name = base;
  options.mesh.placement.seed = 0;  // ablmg remesh's default
  return adapt::remesh(std::move(mesh), std::move(metric), options);
}

void expectSameMesh(const Mesh2& a, const Mesh2& b) {
  ASSERT_EQ(a.numVertices(), b.numVertices());
  ASSERT_EQ(a.numTriangles(), b.numTriangles());
  ASSERT_EQ(a.boundaryEdges.size(), b.boundaryEdges.size());
  for (int i = 0; i < a.numVertices(); ++i) {
    EXPECT_EQ(a.vertices[std::size_t(i)].x(), b.vertices[std::size_t(i)].x());
    EXPECT_EQ(a.vertices[std::size_t(i)].y(), b.vertices[std::size_t(i)].y());
  }
  for (int t = 0; t < a.numTriangles(); ++t) EXPECT_EQ(a.triangles[std::size_t(t)], b.triangles[std::size_t(t)]);
  for (std::size_t e = 0; e < a.boundaryEdges.size(); ++e) {
    EXPECT_EQ(a.boundaryEdges[e].a, b.boundaryEdges[e].a);
    EXPECT_EQ(a.boundaryEdges[e].b, b.boundaryEdges[e].b);
    EXPECT_EQ(a.boundaryEdges[e].ref, b.boundaryEdges[e].ref);
  }
}

/// A 3×3-vertex square [0,2]² (8 triangles, refs 1..4 on the sides), metric h = 0.25.
Arrays smallSquare() {
  Mesh2 mesh;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) mesh.vertices.emplace_back(i, j);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int v = 3 * j + i;
      mesh.triangles.push_back({v, v + 1, v + 4});
      mesh.triangles.push_back({v, v + 4, v + 3});
    }
  mesh.boundaryEdges = {{0, 1, 1}, {1, 2, 1}, {2, 5, 2}, {5, 8, 2}, {8, 7, 3}, {7, 6, 3}, {6, 3, 4}, {3, 0, 4}};
  return arraysOf(mesh, std::vector<Metric2>(9, Metric2::isotropic(0.25)));
}

/// The status of remeshing `a` after `edit` changed it, and the message.
template <class Edit>
std::pair<int, std::string> remeshEdited(Edit edit) {
  Arrays a = smallSquare();
  edit(a);
  Handle h(ablmg_create());
  int rc = setAll(h.get(), a);
  if (rc == ABLMG_OK) rc = ablmg_remesh(h.get());
  return {rc, ablmg_last_error(h.get())};
}

}  // namespace

TEST(CApi, RemeshesAMeditPairAsTheRemeshCommand) {
  for (const std::string base : {"square", "freefem"}) {
    SCOPED_TRACE(base);
    Handle h(ablmg_create());
    ASSERT_TRUE(h);
    ASSERT_EQ(setAll(h.get(), fileArrays(base)), ABLMG_OK) << ablmg_last_error(h.get());
    ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK) << ablmg_last_error(h.get());
    EXPECT_STREQ(ablmg_last_error(h.get()), "");
    const auto [mesh, metric] = resultOf(h.get());
    const auto expected = cliRemesh(base);
    expectSameMesh(mesh, expected.mesh);
    ASSERT_EQ(metric.size(), expected.metric.size());
    for (std::size_t i = 0; i < metric.size(); ++i) {
      EXPECT_EQ(metric[i].m11(), expected.metric[i].m11());
      EXPECT_EQ(metric[i].m12(), expected.metric[i].m12());
      EXPECT_EQ(metric[i].m22(), expected.metric[i].m22());
    }
    EXPECT_TRUE(mesh.validate().ok);
    ablmg_quality q;
    ASSERT_EQ(ablmg_get_quality(h.get(), &q), ABLMG_OK);
    EXPECT_EQ(q.valid, 1);
    EXPECT_EQ(q.vertices, mesh.numVertices());
    EXPECT_EQ(q.triangles, mesh.numTriangles());
    EXPECT_GT(q.quality_min, 0.3);
    EXPECT_GT(q.quality_mean, 0.85);
    EXPECT_GT(q.edge_in_sqrt2, 0.75);  // square.mesh gives a few dozen edges
    double binSum = 0;
    for (double b : q.quality_bins) binSum += b;
    EXPECT_NEAR(binSum, 1.0, 1e-12);
  }
}

TEST(CApi, ZeroBasedAndClockwiseInputGiveTheSameMesh) {
  const Arrays a = fileArrays("freefem");
  Handle ref(ablmg_create());
  ASSERT_EQ(setAll(ref.get(), a), ABLMG_OK);
  ASSERT_EQ(ablmg_remesh(ref.get()), ABLMG_OK);
  // 0-based, every triangle clockwise, every boundary edge reversed, sizes as tensors.
  std::vector<int> tri0(a.tri.size()), edges0(a.edges.size());
  for (int t = 0; t < a.m; ++t) {
    tri0[3 * std::size_t(t)] = a.tri[3 * std::size_t(t)] - 1;
    tri0[3 * std::size_t(t) + 1] = a.tri[3 * std::size_t(t) + 2] - 1;
    tri0[3 * std::size_t(t) + 2] = a.tri[3 * std::size_t(t) + 1] - 1;
  }
  for (int e = 0; e < a.k; ++e) {
    edges0[2 * std::size_t(e)] = a.edges[2 * std::size_t(e) + 1] - 1;
    edges0[2 * std::size_t(e) + 1] = a.edges[2 * std::size_t(e)] - 1;
  }
  Handle h(ablmg_create());
  ASSERT_EQ(ablmg_set_vertices(h.get(), a.xy.data(), a.vrefs.data(), a.n), ABLMG_OK);
  ASSERT_EQ(ablmg_set_triangles(h.get(), tri0.data(), a.trefs.data(), a.m, 0), ABLMG_OK);
  ASSERT_EQ(ablmg_set_edges(h.get(), edges0.data(), a.erefs.data(), a.k, 0), ABLMG_OK);
  ASSERT_EQ(ablmg_set_metric(h.get(), a.metric.data(), a.n), ABLMG_OK);
  ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK) << ablmg_last_error(h.get());
  expectSameMesh(resultOf(h.get()).first, resultOf(ref.get()).first);
}

TEST(CApi, SizesAreIsotropicTensorsAndTheLoopRunsOnTheResult) {
  // Three remeshes in a row on the same handle, each fed the previous result: valid each time,
  // and a finer size gives more vertices.
  Arrays a = smallSquare();
  Handle h(ablmg_create());
  ASSERT_EQ(setAll(h.get(), a), ABLMG_OK);
  int previous = 0;
  for (double size : {0.3, 0.2, 0.12}) {
    SCOPED_TRACE(size);
    ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK) << ablmg_last_error(h.get());
    auto [mesh, metric] = resultOf(h.get());
    EXPECT_TRUE(mesh.validate().ok);
    EXPECT_NEAR(mesh.area(), 4.0, 1e-12);
    EXPECT_GT(mesh.numVertices(), previous);
    previous = mesh.numVertices();
    a = arraysOf(mesh, metric);
    std::vector<double> sizes(std::size_t(a.n), size * 0.7);
    ASSERT_EQ(setAll(h.get(), a), ABLMG_OK);
    ASSERT_EQ(ablmg_set_sizes(h.get(), sizes.data(), a.n), ABLMG_OK);
  }
}

TEST(CApi, SeedAndThreadsKeepTheResultDeterministic) {
  const Arrays a = fileArrays("freefem");
  std::vector<Mesh2> results;
  for (int threads : {1, 2, 1}) {
    Handle h(ablmg_create());
    ASSERT_EQ(setAll(h.get(), a), ABLMG_OK);
    ASSERT_EQ(ablmg_set_int(h.get(), ABLMG_SEED, 7), ABLMG_OK);
    ASSERT_EQ(ablmg_set_int(h.get(), ABLMG_THREADS, threads), ABLMG_OK);
    const int before = omp_get_max_threads();
    ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK) << ablmg_last_error(h.get());
    EXPECT_EQ(omp_get_max_threads(), before);  // the caller's setting is restored
    results.push_back(resultOf(h.get()).first);
  }
  expectSameMesh(results[0], results[1]);
  expectSameMesh(results[0], results[2]);
}

TEST(CApi, NullArgumentsAreRefused) {
  EXPECT_EQ(ablmg_set_vertices(nullptr, nullptr, nullptr, 3), ABLMG_ERR_NULL);
  EXPECT_EQ(ablmg_remesh(nullptr), ABLMG_ERR_NULL);
  EXPECT_STREQ(ablmg_last_error(nullptr), "null ablmg handle");
  ablmg_free(nullptr);
  Handle h(ablmg_create());
  const int tri[3] = {0, 1, 2};
  EXPECT_EQ(ablmg_set_vertices(h.get(), nullptr, nullptr, 3), ABLMG_ERR_NULL);
  EXPECT_NE(std::string(ablmg_last_error(h.get())).find("xy is NULL"), std::string::npos);
  EXPECT_EQ(ablmg_set_triangles(h.get(), nullptr, nullptr, 1, 0), ABLMG_ERR_NULL);
  EXPECT_EQ(ablmg_set_edges(h.get(), nullptr, nullptr, 3, 0), ABLMG_ERR_NULL);
  EXPECT_EQ(ablmg_set_metric(h.get(), nullptr, 3), ABLMG_ERR_NULL);
  EXPECT_EQ(ablmg_set_sizes(h.get(), nullptr, 3), ABLMG_ERR_NULL);
  EXPECT_EQ(ablmg_set_triangles(h.get(), tri, nullptr, 1, 0), ABLMG_OK);
  EXPECT_EQ(ablmg_get_quality(h.get(), nullptr), ABLMG_ERR_STATE);  // no result yet
  ASSERT_EQ(setAll(h.get(), smallSquare()), ABLMG_OK);
  ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK);
  EXPECT_EQ(ablmg_get_quality(h.get(), nullptr), ABLMG_ERR_NULL);
  EXPECT_EQ(ablmg_get_vertices(h.get(), nullptr, nullptr, 0), ABLMG_ERR_NULL);
}

TEST(CApi, CountsBasesAndOptionsOutOfRangeAreArgumentErrors) {
  Handle h(ablmg_create());
  const Arrays a = smallSquare();
  EXPECT_EQ(ablmg_set_vertices(h.get(), a.xy.data(), nullptr, -1), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_vertices(h.get(), a.xy.data(), nullptr, 2), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_triangles(h.get(), a.tri.data(), nullptr, 0, 1), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_triangles(h.get(), a.tri.data(), nullptr, a.m, 2), ABLMG_ERR_ARGUMENT);
  EXPECT_NE(std::string(ablmg_last_error(h.get())).find("base = 2"), std::string::npos);
  EXPECT_EQ(ablmg_set_edges(h.get(), a.edges.data(), nullptr, a.k, -1), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_metric(h.get(), a.metric.data(), 0), ABLMG_ERR_ARGUMENT);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_HMIN, -1), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_HMIN, nan), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_HMAX, 0), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_HMAX, inf), ABLMG_OK);
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_HGRAD, 0.5), ABLMG_ERR_ARGUMENT);
  EXPECT_NE(std::string(ablmg_last_error(h.get())).find("hgrad = 0.5"), std::string::npos);
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_HGRAD, nan), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_HGRAD, -1), ABLMG_OK);
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_SEED, 1), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_double(h.get(), ablmg_option(99), 1), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_int(h.get(), ABLMG_SEED, -3), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_int(h.get(), ABLMG_THREADS, -1), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_int(h.get(), ABLMG_HMIN, 1), ABLMG_ERR_ARGUMENT);
  // hmin >= hmax is checked when both are known, at remesh.
  ASSERT_EQ(setAll(h.get(), a), ABLMG_OK);
  ASSERT_EQ(ablmg_set_double(h.get(), ABLMG_HMIN, 0.5), ABLMG_OK);
  ASSERT_EQ(ablmg_set_double(h.get(), ABLMG_HMAX, 0.2), ABLMG_OK);
  EXPECT_EQ(ablmg_remesh(h.get()), ABLMG_ERR_ARGUMENT);
  EXPECT_NE(std::string(ablmg_last_error(h.get())).find("hmin"), std::string::npos) << ablmg_last_error(h.get());
}

TEST(CApi, HostileArraysGetTheirErrorCode) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  struct Case {
    const char* what;
    void (*edit)(Arrays&);
    int status;
    const char* message;
  };
  // docs/hostile_inputs.md's rows that arrays can carry (the file-format rows are the parser's).
  const Case cases[] = {
      {"NaN coordinate", [](Arrays& a) { a.xy[3] = std::numeric_limits<double>::quiet_NaN(); }, ABLMG_ERR_INPUT,
       "vertex 1 (1, nan) is not finite"},
      {"overflowing coordinate", [](Arrays& a) { a.xy[0] = std::numeric_limits<double>::infinity(); }, ABLMG_ERR_INPUT,
       "vertex 0 (inf, 0) is not finite"},
      {"index out of range", [](Arrays& a) { a.tri[4] = 10; }, ABLMG_ERR_INPUT, "triangle 1 has vertex index 9"},
      {"index below the base", [](Arrays& a) { a.edges[5] = 0; }, ABLMG_ERR_INPUT,
       "edges[5] = 0 is below the index base 1"},
      {"non-SPD tensor", [](Arrays& a) { a.metric[12] = 1, a.metric[13] = 2, a.metric[14] = 1; }, ABLMG_ERR_INPUT,
       "tensor of vertex 4 (1, 2, 1) is not positive definite"},
      {"NaN tensor entry", [](Arrays& a) { a.metric[1] = std::numeric_limits<double>::quiet_NaN(); }, ABLMG_ERR_INPUT,
       "tensor of vertex 0 (16, nan, 16) is not finite"},
      {"Inf tensor entry", [](Arrays& a) { a.metric[26] = -std::numeric_limits<double>::infinity(); }, ABLMG_ERR_INPUT,
       "tensor of vertex 8 (16, 0, -inf) is not finite"},
      {"metric count mismatch", [](Arrays& a) { a.metric.resize(6 * 3); }, ABLMG_ERR_ARGUMENT,
       "the metric has 6 values but the mesh has 9 vertices"},
      {"overlapping triangles", [](Arrays& a) { a.tri[3] = 1, a.tri[4] = 2, a.tri[5] = 5; }, ABLMG_ERR_INVALID_MESH,
       "input: invalid mesh: "},
      {"missing boundary edge", [](Arrays& a) { a.edges.resize(14), a.erefs.resize(7), a.k = 7; },
       ABLMG_ERR_INVALID_MESH, "input: invalid mesh: "},
      {"unused vertex (a tenth far away)",
       [](Arrays& a) {
         a.xy.push_back(5), a.xy.push_back(5), a.vrefs.push_back(0), a.n = 10;
         for (int k = 0; k < 3; ++k) a.metric.push_back(a.metric[std::size_t(k)]);
       },
       ABLMG_ERR_INVALID_MESH, "input: invalid mesh: "},
      {"size so small it asks for 10^12 nodes",
       [](Arrays& a) {
         for (std::size_t i = 0; i < a.metric.size(); i += 3) a.metric[i] = a.metric[i + 2] = 1e12;
       },
       ABLMG_ERR_INPUT, "more than maxNodes"},
  };
  (void)nan;
  (void)inf;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const auto [status, message] = remeshEdited(c.edit);
    EXPECT_EQ(status, c.status) << message;
    EXPECT_NE(message.find(c.message), std::string::npos) << message;
  }
  // Sizes: NaN, negative, 0, not representable as 1/h².
  Handle h(ablmg_create());
  for (double bad : {nan, -0.2, 0.0, 1e-200, inf}) {
    SCOPED_TRACE(bad);
    std::vector<double> sizes(9, 0.25);
    sizes[3] = bad;
    EXPECT_EQ(ablmg_set_sizes(h.get(), sizes.data(), 9), ABLMG_ERR_INPUT);
    EXPECT_NE(std::string(ablmg_last_error(h.get())).find("size of vertex 3"), std::string::npos);
  }
}

TEST(CApi, ExtremeButValidMetricsGiveValidMeshes) {
  // docs/hostile_inputs.md: a huge size, anisotropy 1e5, near-singular SPD tensors.
  const double tensors[][3] = {{1e-12, 0, 1e-12}, {1e-4, 0, 1e6}, {1e4, 0.99999999e4, 1e4}, {1, 1 - 1e-13, 1}};
  for (const auto& t : tensors) {
    SCOPED_TRACE(t[1]);
    Arrays a = smallSquare();
    for (std::size_t i = 0; i < a.metric.size(); i += 3)
      a.metric[i] = t[0], a.metric[i + 1] = t[1], a.metric[i + 2] = t[2];
    Handle h(ablmg_create());
    ASSERT_EQ(setAll(h.get(), a), ABLMG_OK);
    ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK) << ablmg_last_error(h.get());
    const auto mesh = resultOf(h.get()).first;
    EXPECT_TRUE(mesh.validate().ok) << mesh.validate().firstProblem;
    EXPECT_NEAR(mesh.area(), 4.0, 1e-9);
  }
}

TEST(CApi, GettersRefuseWrongCountsAndAFailedRunDropsTheResult) {
  Handle h(ablmg_create());
  int nv = -1;
  EXPECT_EQ(ablmg_get_sizes(h.get(), &nv, nullptr, nullptr), ABLMG_ERR_STATE);
  EXPECT_EQ(nv, -1);
  EXPECT_EQ(ablmg_remesh(h.get()), ABLMG_ERR_STATE);
  EXPECT_NE(std::string(ablmg_last_error(h.get())).find("no vertices set"), std::string::npos);
  ASSERT_EQ(setAll(h.get(), smallSquare()), ABLMG_OK);
  ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK);
  ASSERT_EQ(ablmg_get_sizes(h.get(), &nv, nullptr, nullptr), ABLMG_OK);
  std::vector<double> xy(2 * std::size_t(nv) + 2);
  EXPECT_EQ(ablmg_get_vertices(h.get(), xy.data(), nullptr, nv + 1), ABLMG_ERR_CAPACITY);
  EXPECT_EQ(ablmg_get_vertices(h.get(), xy.data(), nullptr, nv), ABLMG_OK);
  std::vector<int> tri(3);
  EXPECT_EQ(ablmg_get_triangles(h.get(), tri.data(), nullptr, 1, 0), ABLMG_ERR_CAPACITY);
  // A failed run: the old result is gone, the input stays and runs again once fixed.
  ASSERT_EQ(ablmg_set_double(h.get(), ABLMG_HMIN, 1), ABLMG_OK);
  ASSERT_EQ(ablmg_set_double(h.get(), ABLMG_HMAX, 0.5), ABLMG_OK);
  EXPECT_EQ(ablmg_remesh(h.get()), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_get_sizes(h.get(), &nv, nullptr, nullptr), ABLMG_ERR_STATE);
  ASSERT_EQ(ablmg_set_double(h.get(), ABLMG_HMIN, 0), ABLMG_OK);
  EXPECT_EQ(ablmg_remesh(h.get()), ABLMG_OK) << ablmg_last_error(h.get());
  EXPECT_STREQ(ablmg_version(), "0.2.0");
}

namespace {

/// Field f of `count` vertices at (x, y) (field-major, as ablmg_transfer takes them).
std::vector<double> sampleFields(const std::vector<double>& xy, int count) {
  std::vector<double> u(3 * std::size_t(count));
  for (int i = 0; i < count; ++i) {
    const double x = xy[2 * std::size_t(i)], y = xy[2 * std::size_t(i) + 1];
    u[std::size_t(i)] = 1 + 2 * x - 3 * y;                              // linear
    u[std::size_t(count + i)] = 2 + std::sin(3 * x) * std::cos(2 * y);  // smooth
    u[std::size_t(2 * count + i)] = x + 0.1 * y > 0.5 ? 1.0 : 0.0;      // a jump
  }
  return u;
}

Eigen::VectorXd fieldOf(const std::vector<double>& u, int f, int count) {
  return Eigen::Map<const Eigen::VectorXd>(u.data() + std::size_t(f) * std::size_t(count), count);
}

}  // namespace

TEST(CApi, TransferReproducesLinearFieldsAndKeepsTheIntegral) {
  const Arrays a = fileArrays("freefem");
  Handle h(ablmg_create());
  ASSERT_EQ(setAll(h.get(), a), ABLMG_OK);
  ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK) << ablmg_last_error(h.get());
  const auto [mesh, metric] = resultOf(h.get());
  const int nNew = mesh.numVertices();
  std::vector<double> newXy;
  for (const Vec2& p : mesh.vertices) newXy.insert(newXy.end(), {p.x(), p.y()});
  const std::vector<double> old = sampleFields(a.xy, a.n), exact = sampleFields(newXy, nNew);
  Mesh2 source = io::readMesh(std::string(ABLMG_TEST_DATA) + "/freefem.mesh");
  for (int method : {ABLMG_TRANSFER_INTERPOLATION, ABLMG_TRANSFER_PROJECTION, ABLMG_TRANSFER_PROJECTION_BOUNDED}) {
    SCOPED_TRACE(method);
    std::vector<double> out(3 * std::size_t(nNew), -99.0);
    ablmg_transfer_stats s{};
    ASSERT_EQ(ablmg_transfer(h.get(), old.data(), a.n, 3, method, out.data(), nNew, &s), ABLMG_OK)
        << ablmg_last_error(h.get());
    if (method != ABLMG_TRANSFER_PROJECTION_BOUNDED) {  // linear fields are reproduced
      for (int i = 0; i < nNew; ++i) EXPECT_NEAR(out[std::size_t(i)], exact[std::size_t(i)], 1e-12) << i;
    }
    if (method == ABLMG_TRANSFER_INTERPOLATION) continue;
    EXPECT_NEAR(s.supermesh_area, mesh.area(), 1e-12 * mesh.area());
    EXPECT_GT(s.supermesh_pieces, nNew);
    EXPECT_LT(s.relative_mass_defect, 1e-12);
    for (int f = 0; f < 3; ++f) {  // the integrals, computed on each mesh on its own
      const double before = adapt::integrate(source, fieldOf(old, f, a.n));
      EXPECT_NEAR(adapt::integrate(mesh, fieldOf(out, f, nNew)), before, 1e-12 * std::abs(before)) << f;
    }
    if (method == ABLMG_TRANSFER_PROJECTION_BOUNDED)  // the jump stays within [0, 1]
      for (int i = 0; i < nNew; ++i) {
        EXPECT_GE(out[std::size_t(2 * nNew + i)], 0.0) << i;
        EXPECT_LE(out[std::size_t(2 * nNew + i)], 1.0) << i;
      }
  }
}

TEST(CApi, TransferRefusesBadCallsAndKeepsItsSource) {
  const Arrays a = fileArrays("freefem");
  Handle h(ablmg_create());
  ASSERT_EQ(setAll(h.get(), a), ABLMG_OK);
  std::vector<double> old = sampleFields(a.xy, a.n), out(3 * std::size_t(a.n) + 10000, 7.0);
  EXPECT_EQ(ablmg_transfer(h.get(), old.data(), a.n, 1, 0, out.data(), a.n, nullptr), ABLMG_ERR_STATE);
  ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK);
  int nNew = 0;
  ASSERT_EQ(ablmg_get_sizes(h.get(), &nNew, nullptr, nullptr), ABLMG_OK);
  const auto code = [&](const double* in, int nOld, int nfields, int method, double* o, int n) {
    return ablmg_transfer(h.get(), in, nOld, nfields, method, o, n, nullptr);
  };
  EXPECT_EQ(code(nullptr, a.n, 1, 0, out.data(), nNew), ABLMG_ERR_NULL);
  EXPECT_EQ(code(old.data(), a.n, 1, 0, nullptr, nNew), ABLMG_ERR_NULL);
  EXPECT_EQ(code(old.data(), a.n - 1, 1, 0, out.data(), nNew), ABLMG_ERR_ARGUMENT);
  EXPECT_NE(std::string(ablmg_last_error(h.get())).find("n_old"), std::string::npos);
  EXPECT_EQ(code(old.data(), a.n, 1, 0, out.data(), nNew + 1), ABLMG_ERR_CAPACITY);
  EXPECT_EQ(code(old.data(), a.n, 0, 0, out.data(), nNew), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(code(old.data(), a.n, 1, 3, out.data(), nNew), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(code(old.data(), a.n, 1, -1, out.data(), nNew), ABLMG_ERR_ARGUMENT);
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    old[std::size_t(a.n + 2)] = bad;  // field 1, vertex 2
    EXPECT_EQ(code(old.data(), a.n, 2, 1, out.data(), nNew), ABLMG_ERR_INPUT);
    EXPECT_NE(std::string(ablmg_last_error(h.get())).find("field 1 at vertex 2"), std::string::npos)
        << ablmg_last_error(h.get());
  }
  for (double v : out) EXPECT_EQ(v, 7.0);  // untouched by the failed calls
  // New input arrays do not change the source of the last result.
  const Arrays b = smallSquare();
  ASSERT_EQ(setAll(h.get(), b), ABLMG_OK);
  old = sampleFields(a.xy, a.n);
  EXPECT_EQ(code(old.data(), a.n, 1, 1, out.data(), nNew), ABLMG_OK) << ablmg_last_error(h.get());
}

TEST(CApi, MetricQuantumAbsorbsRoundOffInTheMetric) {
  const Arrays a = fileArrays("freefem");
  Arrays b = a;  // the metric moved by ~1e-11 relative, as another solver's round-off would
  for (std::size_t i = 0; i < b.metric.size(); ++i) b.metric[i] *= 1 + 1e-11 * std::sin(double(i));
  std::vector<Mesh2> meshes;
  for (double quantum : {0.0, 0x1.0p-8})
    for (const Arrays* in : {&a, static_cast<const Arrays*>(&b)}) {
      Handle h(ablmg_create());
      ASSERT_EQ(setAll(h.get(), *in), ABLMG_OK);
      ASSERT_EQ(ablmg_set_double(h.get(), ABLMG_METRIC_QUANTUM, quantum), ABLMG_OK);
      ASSERT_EQ(ablmg_remesh(h.get()), ABLMG_OK) << ablmg_last_error(h.get());
      meshes.push_back(resultOf(h.get()).first);
    }
  EXPECT_NE(meshes[0].vertices, meshes[1].vertices);  // the placement is chaotic in its input
  expectSameMesh(meshes[2], meshes[3]);
  Handle h(ablmg_create());
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_METRIC_QUANTUM, -1), ABLMG_ERR_ARGUMENT);
  EXPECT_EQ(ablmg_set_double(h.get(), ABLMG_METRIC_QUANTUM, std::nan("")), ABLMG_ERR_ARGUMENT);
}
