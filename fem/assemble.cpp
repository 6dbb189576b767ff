#include "ablmg/fem/assemble.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/parallel_failure.hpp"
#include "ablmg/fem/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include <omp.h>

namespace ablmg::fem {
namespace {

void requireSize(const ScalarData& d, const Mesh2& mesh, const char* what) {
  ABLMG_REQUIRE(!d.isVertexValues() || int(d.vertexValues.size()) == mesh.numVertices(),
                what << ": " << d.vertexValues.size() << " per-vertex values given for a mesh of " << mesh.numVertices()
                     << " vertices");
}

double valueAtVertex(const ScalarData& d, const Mesh2& mesh, int v) {
  if (d.isFunction()) return d.fn(mesh.vertices[v].x(), mesh.vertices[v].y());
  if (d.isVertexValues()) return d.vertexValues[v];
  return d.constant;
}

/// Local stiffness A_kl = ∫_T κ ∇λ_k·∇λ_l and load ∫_T f λ_k of one triangle.
struct ElementData {
  double a[3][3];
  double load[3];
};

/// Union–find root with path halving.
int findRoot(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

/// Every connected piece of the mesh must hold a Dirichlet vertex, else A is singular.
void requireDirichletInEveryPiece(const Mesh2& mesh, const std::vector<char>& isDirichlet) {
  std::vector<int> parent(mesh.numVertices());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) {
      const int a = findRoot(parent, t[0]), b = findRoot(parent, t[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<char> rootHasDirichlet(mesh.numVertices(), 0);
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (isDirichlet[v]) rootHasDirichlet[findRoot(parent, v)] = 1;
  for (int v = 0; v < mesh.numVertices(); ++v)
    ABLMG_REQUIRE(rootHasDirichlet[findRoot(parent, v)],
                  "assemble: the connected piece of the mesh containing vertex "
                      << v << " (" << mesh.vertices[v].x() << ", " << mesh.vertices[v].y()
                      << ") has no Dirichlet vertex: the system is singular (pure Neumann problem)");
}

}  // namespace

Eigen::VectorXd LinearSystem::expand(const Eigen::VectorXd& x) const {
  Eigen::VectorXd u = dirichletValues;
  for (int d = 0; d < int(vertexOfDof.size()); ++d) u[vertexOfDof[d]] = x[d];
  return u;
}

std::vector<char> dirichletVertices(const Mesh2& mesh, const PoissonProblem& problem, Eigen::VectorXd& values) {
  const int nv = mesh.numVertices();
  std::vector<char> is(nv, 0);
  std::vector<int> tagOf(nv, 0);
  values = Eigen::VectorXd::Zero(nv);
  for (const auto& [tag, data] : problem.dirichlet) requireSize(data, mesh, "Dirichlet data");
  requireSize(problem.dirichletDefault, mesh, "default Dirichlet data");
  for (const auto& e : mesh.boundaryEdges) {
    const ScalarData* data = nullptr;
    if (auto it = problem.dirichlet.find(e.ref); it != problem.dirichlet.end())
      data = &it->second;
    else if (!problem.neumann.count(e.ref) && problem.hasDirichletDefault)
      data = &problem.dirichletDefault;
    if (!data) continue;
    for (int v : {e.a, e.b}) {
      if (is[v] && tagOf[v] <= e.ref) continue;  // the lowest Dirichlet tag at a vertex wins
      is[v] = 1;
      tagOf[v] = e.ref;
      values[v] = valueAtVertex(*data, mesh, v);
      ABLMG_REQUIRE(std::isfinite(values[v]),
                    "Dirichlet data (tag " << e.ref << ") at vertex " << v << " is " << values[v]);
    }
  }
  return is;
}

namespace {

/// ∫_T κ of triangle t (area `area`, vertices p): the rule for a function, the vertex mean
/// for vertex values; κ must be positive (InputError naming the point or vertex otherwise).
double kappaIntegral(const Mesh2& mesh, const ScalarData& kappa, const TriangleRule& rule, int t, const Vec2 (&p)[3],
                     double area) {
  const auto& tri = mesh.triangles[t];
  if (kappa.isFunction()) {
    double kappaInt = 0;
    for (int q = 0; q < rule.size(); ++q) {
      const auto& l = rule.points[q];
      const Vec2 x = l[0] * p[0] + l[1] * p[1] + l[2] * p[2];
      const double k = kappa.fn(x.x(), x.y());
      ABLMG_REQUIRE(k > 0 && std::isfinite(k), "assemble: kappa = " << k << " at (" << x.x() << ", " << x.y()
                                                                    << ") in triangle " << t
                                                                    << " (kappa must be positive: the system "
                                                                       "would not be SPD)");
      kappaInt += rule.weights[q] * k;
    }
    return kappaInt * area;
  }
  if (kappa.isVertexValues()) {
    const auto& kv = kappa.vertexValues;
    for (int v : tri)
      ABLMG_REQUIRE(kv[v] > 0 && std::isfinite(kv[v]),
                    "assemble: kappa = " << kv[v] << " at vertex " << v << " (kappa must be positive)");
    return area * (kv[tri[0]] + kv[tri[1]] + kv[tri[2]]) / 3;
  }
  ABLMG_REQUIRE(kappa.constant > 0 && std::isfinite(kappa.constant),
                "assemble: kappa = " << kappa.constant << " in triangle " << t
                                     << " (kappa must be positive: the system would not be SPD)");
  return area * kappa.constant;
}

/// The datum of triangle t: `bySubdomain`'s entry for t's ref when that map is given, else `all`.
const ScalarData& subdomainDatum(const Mesh2& mesh, const std::map<int, ScalarData>& bySubdomain, const ScalarData& all,
                                 int t, const char* what) {
  if (bySubdomain.empty()) return all;
  const int ref = mesh.triangleRefs.empty() ? 0 : mesh.triangleRefs[std::size_t(t)];
  const auto it = bySubdomain.find(ref);
  ABLMG_REQUIRE(it != bySubdomain.end(), "assemble: triangle " << t << " has subdomain ref " << ref << ", and " << what
                                                               << " has no entry for it");
  return it->second;
}

/// The InputError for a NaN or infinite load in triangle t (vertices p), naming the point.
[[noreturn]] void throwNonFiniteLoad(const ScalarData& f, const TriangleRule& rule, int t, const Vec2 (&p)[3]) {
  if (f.isFunction())
    for (int q = 0; q < rule.size(); ++q) {
      const auto& l = rule.points[q];
      const Vec2 x = l[0] * p[0] + l[1] * p[1] + l[2] * p[2];
      const double v = f.fn(x.x(), x.y());
      ABLMG_REQUIRE(std::isfinite(v),
                    "assemble: f = " << v << " at (" << x.x() << ", " << x.y() << ") in triangle " << t);
    }
  ABLMG_REQUIRE(false, "assemble: the load of triangle " << t << " is not finite (f at its vertices, or f too large)");
  std::abort();  // not reached
}

/// The local stiffness and load of triangle t.
void computeElement(const Mesh2& mesh, const PoissonProblem& problem, const TriangleRule& rule, int t, ElementData& d) {
  const auto& tri = mesh.triangles[t];
  const Vec2 p[3] = {mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]};
  const double area = 0.5 * cross(p[1] - p[0], p[2] - p[0]);
  ABLMG_REQUIRE(area > 0, "assemble: triangle " << t << " has non-positive area " << area);
  const ScalarData& kappa = subdomainDatum(mesh, problem.kappaBySubdomain, problem.kappa, t, "kappaBySubdomain");
  const ScalarData& f = subdomainDatum(mesh, problem.fBySubdomain, problem.f, t, "fBySubdomain");
  const double kappaInt = kappaIntegral(mesh, kappa, rule, t, p, area);
  // ∇λ_k = e_k / (2|T|), e_k = perp of the opposite edge; A_kl = ∫κ ∇λ_k·∇λ_l.
  Vec2 e[3];
  for (int k = 0; k < 3; ++k) {
    const Vec2& a = p[(k + 1) % 3];
    const Vec2& b = p[(k + 2) % 3];
    e[k] = Vec2(a.y() - b.y(), b.x() - a.x());
  }
  const double scale = kappaInt / (4 * area * area);
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) d.a[k][l] = scale * e[k].dot(e[l]);
  // ∫_T f λ_k
  for (double& v : d.load) v = 0;
  if (f.isFunction()) {
    for (int q = 0; q < rule.size(); ++q) {
      const auto& l = rule.points[q];
      const Vec2 x = l[0] * p[0] + l[1] * p[1] + l[2] * p[2];
      const double fq = rule.weights[q] * f.fn(x.x(), x.y());
      for (int k = 0; k < 3; ++k) d.load[k] += fq * l[k];
    }
    for (double& v : d.load) v *= area;
  } else if (f.isVertexValues()) {
    const auto& fv = f.vertexValues;
    const double s = fv[tri[0]] + fv[tri[1]] + fv[tri[2]];
    for (int k = 0; k < 3; ++k) d.load[k] = area / 12 * (s + fv[tri[k]]);
  } else {
    for (double& v : d.load) v = f.constant * area / 3;
  }
  if (!std::isfinite(d.load[0] + d.load[1] + d.load[2])) throwNonFiniteLoad(f, rule, t, p);
}

/// Numbers the free (non-Dirichlet) vertices as dofs; fills the Dirichlet values.
void numberDofs(const Mesh2& mesh, const PoissonProblem& problem, LinearSystem& sys) {
  const int nv = mesh.numVertices();
  const std::vector<char> isDirichlet = dirichletVertices(mesh, problem, sys.dirichletValues);
  sys.dofOfVertex.assign(nv, -1);
  for (int v = 0; v < nv; ++v)
    if (!isDirichlet[v]) {
      sys.dofOfVertex[v] = int(sys.vertexOfDof.size());
      sys.vertexOfDof.push_back(v);
      sys.dofPoints.push_back(mesh.vertices[v]);
    }
  sys.numDirichletVertices = nv - int(sys.vertexOfDof.size());
  ABLMG_REQUIRE(sys.numDirichletVertices > 0,
                "assemble: no boundary vertex has Dirichlet data (no tag of the mesh's "
                    << mesh.boundaryEdges.size()
                    << " boundary edges is Dirichlet): the pure Neumann system is singular");
  requireDirichletInEveryPiece(mesh, isDirichlet);
}

/// Sorts a vertex's few neighbour ids: insertion sort up to 32 entries (cheaper than
/// std::sort's set-up at the usual 13), std::sort beyond (a fan of many triangles).
void sortSmall(std::vector<int>& a) {
  if (a.size() > 32) {
    std::sort(a.begin(), a.end());
    return;
  }
  for (std::size_t i = 1; i < a.size(); ++i) {
    const int x = a[i];
    std::size_t j = i;
    for (; j > 0 && a[j - 1] > x; --j) a[j] = a[j - 1];
    a[j] = x;
  }
}

/// Systems this large build their pattern and scatter their elements on all threads.
constexpr int kParallelUnknowns = 20000;

/// 1. Sparsity pattern: column d holds the free vertices sharing a triangle with vertex d;
/// values 0, b = 0. Each thread builds the columns of one contiguous range of dofs; the
/// ranges are concatenated in order (the same pattern on any thread count).
void buildPattern(const Mesh2& mesh, LinearSystem& sys) {
  const int n = int(sys.vertexOfDof.size());
  const Mesh2::VertexTriangles vt = mesh.vertexTriangles();
  std::vector<int> outer(std::size_t(n) + 1, 0);
  std::vector<std::vector<int>> chunks(std::size_t(std::max(1, omp_get_max_threads())));
#pragma omp parallel if (n >= kParallelUnknowns)
  {
    const int nt = std::min(omp_get_num_threads(), int(chunks.size())), t = omp_get_thread_num();
    if (t < nt) {
      const int d0 = int(long(n) * t / nt), d1 = int(long(n) * (t + 1) / nt);
      std::vector<int>& inner = chunks[std::size_t(t)];
      inner.reserve(std::size_t(d1 - d0) * 7);
      std::vector<int> buf;
      for (int d = d0; d < d1; ++d) {
        // d itself (every dof has a triangle: assemble() refused isolated free vertices), then
        // the other two vertices of each triangle at v: 13 entries on an interior vertex of
        // valence 6, against 18 with v counted once per triangle; the same set.
        const int v = sys.vertexOfDof[std::size_t(d)];
        buf.assign(1, d);
        for (int k = vt.offsets[std::size_t(v)]; k < vt.offsets[std::size_t(v) + 1]; ++k)
          for (int w : mesh.triangles[std::size_t(vt.ids[std::size_t(k)])])
            if (w != v && sys.dofOfVertex[std::size_t(w)] >= 0) buf.push_back(sys.dofOfVertex[std::size_t(w)]);
        sortSmall(buf);
        buf.erase(std::unique(buf.begin(), buf.end()), buf.end());
        inner.insert(inner.end(), buf.begin(), buf.end());
        outer[std::size_t(d) + 1] = int(buf.size());
      }
    }
  }
  for (int d = 0; d < n; ++d) outer[std::size_t(d) + 1] += outer[std::size_t(d)];
  sys.A.resize(n, n);
  sys.A.resizeNonZeros(Eigen::Index(outer[std::size_t(n)]));
  std::copy(outer.begin(), outer.end(), sys.A.outerIndexPtr());
  // Each thread copies its own chunk and zeroes its values (the first touch of the matrix's
  // pages, shared between the threads).
  std::vector<std::size_t> chunkStart(chunks.size() + 1, 0);
  for (std::size_t c = 0; c < chunks.size(); ++c) chunkStart[c + 1] = chunkStart[c] + chunks[c].size();
#pragma omp parallel for schedule(static, 1) if (n >= kParallelUnknowns)
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    std::copy(chunks[c].begin(), chunks[c].end(), sys.A.innerIndexPtr() + chunkStart[c]);
    std::fill(sys.A.valuePtr() + chunkStart[c], sys.A.valuePtr() + chunkStart[c + 1], 0.0);
  }
  sys.b = Eigen::VectorXd::Zero(n);
}

/// Adds one element's data into the pattern and the load (Dirichlet columns lifted to b),
/// for the rows (dofs) in [rowBegin, rowEnd) only.
void scatterElement(const std::array<int, 3>& tri, const ElementData& d, LinearSystem& sys, int rowBegin, int rowEnd) {
  double* values = sys.A.valuePtr();
  const int* outer = sys.A.outerIndexPtr();
  for (int k = 0; k < 3; ++k) {
    const int dk = sys.dofOfVertex[tri[k]];
    if (dk < rowBegin || dk >= rowEnd) continue;  // Dirichlet (−1) or another thread's row
    sys.b[dk] += d.load[k];
    const int* colBegin = sys.A.innerIndexPtr() + outer[dk];
    const int* colEnd = sys.A.innerIndexPtr() + outer[dk + 1];
    for (int l = 0; l < 3; ++l) {
      const int dl = sys.dofOfVertex[tri[l]];
      if (dl < 0) {
        sys.b[dk] -= d.a[k][l] * sys.dirichletValues[tri[l]];  // lifting
        continue;
      }
      const int* it = std::find(colBegin, colEnd, dl);
      ABLMG_ASSERT(it != colEnd, "pattern misses (" << dl << ", " << dk << ")");
      values[it - sys.A.innerIndexPtr()] += d.a[k][l];
    }
  }
}

constexpr int kMaxScatterThreads = 64;

/// Row ranges [cut[k], cut[k + 1]) for `threads` scattering threads (cut[0] = 0,
/// cut[threads] = n): the k/threads quantiles of the first free dof of every 16th triangle
/// of [t0, t1). Each row belongs to one range, so every entry still sums its terms in triangle
/// order: the split changes who adds, not the order or the result.
void rowCuts(const Mesh2& mesh, const LinearSystem& sys, int t0, int t1, int threads, int* cut) {
  const int n = int(sys.A.rows());
  cut[0] = 0;
  cut[threads] = n;
  if (threads == 1) return;
  std::vector<int> sample;
  sample.reserve(std::size_t(t1 - t0) / 16 + 1);
  for (int t = t0; t < t1; t += 16)
    for (int v : mesh.triangles[std::size_t(t)])
      if (const int d = sys.dofOfVertex[std::size_t(v)]; d >= 0) {
        sample.push_back(d);
        break;
      }
  for (int k = 1; k < threads; ++k) {
    if (sample.empty()) {
      cut[k] = int(long(n) * k / threads);
      continue;
    }
    const auto at = sample.begin() + std::ptrdiff_t(sample.size() * std::size_t(k) / std::size_t(threads));
    std::nth_element(sample.begin(), at, sample.end());
    cut[k] = std::max(cut[k - 1], *at);
  }
}

/// 2. Element loop: local stiffness and load, scattered into the pattern. Local data are
///    computed in blocks (in parallel when the problem's functions allow it), then scattered
///    in triangle order, each thread adding into the rows of its own range of dofs: every
///    entry sums its terms in triangle order, so the result is bitwise the same for any
///    thread count.
void assembleElements(const Mesh2& mesh, const PoissonProblem& problem, LinearSystem& sys) {
  const int nt = mesh.numTriangles(), n = int(sys.A.rows());
  const TriangleRule& rule = triangleRule(5);
  constexpr int kBlock = 16384;  // block data stay in cache for the scatter
  std::vector<ElementData> block(std::size_t(std::min(nt, kBlock)));
  const bool parallel = problem.threadSafeFunctions && nt >= 2 * kBlock;
  for (int t0 = 0; t0 < nt; t0 += kBlock) {
    const int t1 = std::min(nt, t0 + kBlock);
    ParallelFailure failure;  // the error of the lowest triangle is rethrown, as a serial loop would
#pragma omp parallel for schedule(static) if (parallel)
    for (int t = t0; t < t1; ++t) failure.run(t, [&] { computeElement(mesh, problem, rule, t, block[t - t0]); });
    failure.rethrow();
    // The block's rows are split between the threads at quantiles of a sample of its
    // triangles' dofs: a block of a mesh numbered along its rows touches a narrow band of
    // rows, which a split of all n rows would give to one thread.
    const int threads = n >= kParallelUnknowns ? std::min(omp_get_max_threads(), kMaxScatterThreads) : 1;
    int cut[kMaxScatterThreads + 1];
    rowCuts(mesh, sys, t0, t1, threads, cut);
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
      // A team smaller than asked (nested regions) takes the ranges in turn.
      for (int k = omp_get_thread_num(); k < threads; k += omp_get_num_threads())
        for (int t = t0; t < t1; ++t) scatterElement(mesh.triangles[t], block[t - t0], sys, cut[k], cut[k + 1]);
    }
  }
}

/// 3. Neumann flux on non-Dirichlet boundary edges: ∫_e g_N λ_k ds.
void addNeumann(const Mesh2& mesh, const PoissonProblem& problem, LinearSystem& sys) {
  for (const auto& be : mesh.boundaryEdges) {
    const auto it = problem.neumann.find(be.ref);
    if (it == problem.neumann.end() || problem.dirichlet.count(be.ref)) continue;
    const ScalarData& g = it->second;
    const Vec2 a = mesh.vertices[be.a], b = mesh.vertices[be.b];
    const double len = (b - a).norm();
    double ga = 0, gb = 0;  // ∫_e g λ_a, ∫_e g λ_b
    if (g.isFunction()) {
      for (const auto& [s, w] : gaussLegendre01(3)) {
        const Vec2 x = (1 - s) * a + s * b;
        const double gq = w * len * g.fn(x.x(), x.y());
        ga += gq * (1 - s);
        gb += gq * s;
      }
    } else if (g.isVertexValues()) {
      ga = len * (2 * g.vertexValues[be.a] + g.vertexValues[be.b]) / 6;
      gb = len * (g.vertexValues[be.a] + 2 * g.vertexValues[be.b]) / 6;
    } else {
      ga = gb = g.constant * len / 2;
    }
    if (sys.dofOfVertex[be.a] >= 0) sys.b[sys.dofOfVertex[be.a]] += ga;
    if (sys.dofOfVertex[be.b] >= 0) sys.b[sys.dofOfVertex[be.b]] += gb;
  }
}

}  // namespace

LinearSystem assemble(const Mesh2& mesh, const PoissonProblem& problem) {
  ABLMG_REQUIRE(mesh.numTriangles() > 0, "assemble: the mesh has no triangles");
  requireSize(problem.kappa, mesh, "kappa");
  requireSize(problem.f, mesh, "f");
  ABLMG_REQUIRE(
      mesh.triangleRefs.empty() || mesh.triangleRefs.size() == mesh.triangles.size(),
      "assemble: " << mesh.triangleRefs.size() << " triangle refs for " << mesh.triangles.size() << " triangles");
  for (const auto& [ref, data] : problem.kappaBySubdomain) requireSize(data, mesh, "kappaBySubdomain");
  for (const auto& [ref, data] : problem.fBySubdomain) requireSize(data, mesh, "fBySubdomain");
  for (const auto& [tag, data] : problem.neumann) requireSize(data, mesh, "Neumann data");
  LinearSystem sys;
  numberDofs(mesh, problem, sys);
  buildPattern(mesh, sys);
  assembleElements(mesh, problem, sys);
  addNeumann(mesh, problem, sys);
  return sys;
}

}  // namespace ablmg::fem
