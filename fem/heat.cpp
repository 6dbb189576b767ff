#include "ablmg/fem/heat.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/fem/cholmod_threads.hpp"
#include "ablmg/fem/p1_matrices.hpp"
#include "ablmg/fem/quadrature.hpp"

#include <Eigen/CholmodSupport>

#include <cmath>

namespace ablmg::fem {

struct HeatSolver::Factor {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  Eigen::SparseMatrix<double> Afd;  ///< free rows × Dirichlet columns (all vertex columns, Dirichlet ones kept)
};

TimeScheme parseTimeScheme(const std::string& name) {
  if (name == "euler") return TimeScheme::BackwardEuler;
  if (name == "bdf2") return TimeScheme::BDF2;
  ABLMG_REQUIRE(false, "unknown time scheme '" << name << "' (valid: euler, bdf2)");
  return TimeScheme::BDF2;
}

std::string toString(TimeScheme scheme) { return scheme == TimeScheme::BackwardEuler ? "euler" : "bdf2"; }

HeatProblem heatProblem(const TransientProblem& problem) { return {problem.kappa, problem.f, problem.u}; }

HeatSolver::HeatSolver(const Mesh2& mesh, HeatProblem problem, TimeScheme scheme)
    : mesh_(&mesh), problem_(std::move(problem)), scheme_(scheme) {
  ABLMG_REQUIRE(problem_.dirichlet, "heat solver: no Dirichlet data");
  const P1Pattern pattern = p1Pattern(mesh);
  M_ = massMatrix(mesh, pattern);
  K_ = stiffnessMatrix(mesh, pattern, problem_.kappa);
  std::vector<char> boundary(std::size_t(mesh.numVertices()), 0);
  for (const auto& e : mesh.boundaryEdges) boundary[std::size_t(e.a)] = boundary[std::size_t(e.b)] = 1;
  dofOfVertex_.assign(std::size_t(mesh.numVertices()), -1);
  for (int v = 0; v < mesh.numVertices(); ++v)
    if (!boundary[std::size_t(v)]) {
      dofOfVertex_[std::size_t(v)] = int(vertexOfDof_.size());
      vertexOfDof_.push_back(v);
    }
  ABLMG_REQUIRE(!vertexOfDof_.empty(), "heat solver: every vertex is on the boundary (no unknown)");
  u_ = Eigen::VectorXd::Zero(mesh.numVertices());
}

HeatSolver::~HeatSolver() = default;
HeatSolver::HeatSolver(HeatSolver&&) noexcept = default;
HeatSolver& HeatSolver::operator=(HeatSolver&&) noexcept = default;

void HeatSolver::setState(double t, Eigen::VectorXd u, std::optional<Eigen::VectorXd> previous, double dtPrevious) {
  ABLMG_REQUIRE(u.size() == mesh_->numVertices(),
                "heat solver: state has " << u.size() << " values for " << mesh_->numVertices() << " vertices");
  ABLMG_REQUIRE(!previous || previous->size() == u.size(), "heat solver: previous state has the wrong size");
  t_ = t;
  u_ = std::move(u);
  previous_ = previous ? std::move(*previous) : Eigen::VectorXd();
  dtPrevious_ = previous ? dtPrevious : 0;
}

void HeatSolver::factorise(double c) {
  const Stopwatch watch;
  const Eigen::SparseMatrix<double> A = c * M_ + K_;
  const int nf = int(vertexOfDof_.size());
  std::vector<Eigen::Triplet<double>> ff, fd;
  for (int col = 0; col < A.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
      const int r = dofOfVertex_[std::size_t(it.row())], cc = dofOfVertex_[std::size_t(col)];
      if (r < 0) continue;
      if (cc >= 0)
        ff.emplace_back(r, cc, it.value());
      else
        fd.emplace_back(r, col, it.value());
    }
  auto f = std::make_unique<Factor>();
  Eigen::SparseMatrix<double> Aff(nf, nf);
  Aff.setFromTriplets(ff.begin(), ff.end());
  f->Afd.resize(nf, A.cols());
  f->Afd.setFromTriplets(fd.begin(), fd.end());
  f->llt.cholmod().print = 0;
  f->llt.cholmod().nmethods = 1;
  f->llt.cholmod().method[0].ordering = CHOLMOD_AMD;
  fixBlasThreads();
  const CholmodScope serial;
  f->llt.compute(Aff);
  ABLMG_REQUIRE(f->llt.info() == Eigen::Success, "heat solver: CHOLMOD could not factorise the "
                                                     << nf << "×" << nf << " matrix (not positive definite)");
  factor_ = std::move(f);
  factorC_ = c;
  ++factorizations_;
  factorSeconds_ += watch.seconds();
}

namespace {
/// F_i = ∫ f(·, t) φ_i, degree-5 rule, serial in triangle order.
Eigen::VectorXd load(const Mesh2& mesh, const SpaceTimeFn& f, double t) {
  Eigen::VectorXd F = Eigen::VectorXd::Zero(mesh.numVertices());
  if (!f) return F;
  const TriangleRule& rule = triangleRule(5);
  for (int tr = 0; tr < mesh.numTriangles(); ++tr) {
    const auto& v = mesh.triangles[std::size_t(tr)];
    const double area = mesh.triangleArea(tr);
    for (int q = 0; q < rule.size(); ++q) {
      const auto& l = rule.points[std::size_t(q)];
      const Vec2 x = l[0] * mesh.vertices[v[0]] + l[1] * mesh.vertices[v[1]] + l[2] * mesh.vertices[v[2]];
      const double w = rule.weights[std::size_t(q)] * area * f(x.x(), x.y(), t);
      for (int k = 0; k < 3; ++k) F[v[k]] += w * l[std::size_t(k)];
    }
  }
  return F;
}
}  // namespace

void HeatSolver::step(double dt) {
  ABLMG_REQUIRE(dt > 0 && std::isfinite(dt), "heat solver: time step dt = " << dt << " (must be > 0)");
  const bool bdf2 =
      scheme_ == TimeScheme::BDF2 && previous_.size() == u_.size() && std::abs(dtPrevious_ - dt) <= 1e-12 * dt;
  const double c = bdf2 ? 1.5 / dt : 1.0 / dt;
  if (!factor_ || factorC_ != c) factorise(c);
  const double t1 = t_ + dt;
  Eigen::VectorXd history = bdf2 ? Eigen::VectorXd((4 * u_ - previous_) / (2 * dt)) : Eigen::VectorXd(u_ / dt);
  Eigen::VectorXd rhs = M_ * history + load(*mesh_, problem_.f, t1);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(mesh_->numVertices());
  for (int v = 0; v < mesh_->numVertices(); ++v)
    if (dofOfVertex_[std::size_t(v)] < 0)
      g[v] = problem_.dirichlet(mesh_->vertices[std::size_t(v)].x(), mesh_->vertices[std::size_t(v)].y(), t1);
  const Eigen::VectorXd lift = factor_->Afd * g;
  Eigen::VectorXd b(Eigen::Index(vertexOfDof_.size()));
  for (std::size_t d = 0; d < vertexOfDof_.size(); ++d)
    b[Eigen::Index(d)] = rhs[vertexOfDof_[d]] - lift[Eigen::Index(d)];
  const Eigen::VectorXd x = [&] {
    const CholmodScope serial;
    return Eigen::VectorXd(factor_->llt.solve(b));
  }();
  ABLMG_REQUIRE(x.allFinite(), "heat solver: the solve at t = " << t1 << " gave non-finite values");
  Eigen::VectorXd next = g;
  for (std::size_t d = 0; d < vertexOfDof_.size(); ++d) next[vertexOfDof_[d]] = x[Eigen::Index(d)];
  previous_ = std::move(u_);
  u_ = std::move(next);
  dtPrevious_ = dt;
  t_ = t1;
}

}  // namespace ablmg::fem
