#include "ablmg/fem/test_problems.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace ablmg::fem {
namespace {

using std::numbers::pi;

std::map<std::string, double> defaultsOf(const std::string& name) {
  if (name == "wavefront") return {{"alpha", 20.0}, {"xc", -0.05}, {"yc", -0.05}, {"r0", 0.7}};
  if (name == "peak") return {{"alpha", 1000.0}, {"xc", 0.5}, {"yc", 0.5}};
  if (name == "tanhlayer") return {{"epsilon", 0.01}};
  return {};
}

Domain lshapeDomain() {
  BoundaryLoop loop;
  loop.points = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(-1, 1), Vec2(-1, -1), Vec2(0, -1)};
  loop.tags = {1, 2, 3, 4, 5, 6};
  return Domain(loop);
}

}  // namespace

std::vector<std::string> problemNames() {
  return {"wavefront", "peak", "lshape", "tanhlayer", "smooth", "sine", "linear"};
}

PoissonProblem TestProblem::poisson() const {
  PoissonProblem p;
  p.kappa = 1.0;
  p.f = f;
  p.setDirichletEverywhere(u);
  p.threadSafeFunctions = true;  // pure lambdas
  return p;
}

TestProblem makeProblem(const std::string& name, const std::map<std::string, double>& params) {
  const auto names = problemNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::ostringstream os;
    for (const auto& n : names) os << (&n == &names.front() ? "" : ", ") << n;
    ABLMG_REQUIRE(false, "unknown problem '" << name << "' (valid: " << os.str() << ")");
  }
  TestProblem p;
  p.name = name;
  p.params = defaultsOf(name);
  for (const auto& [key, value] : params) {
    if (!p.params.count(key)) {
      std::ostringstream os;
      for (const auto& [k, v] : p.params) os << (os.tellp() > 0 ? ", " : "") << k;
      ABLMG_REQUIRE(false, "problem '" << name << "': unknown parameter '" << key
                                       << "' (valid: " << (p.params.empty() ? std::string("none") : os.str()) << ")");
    }
    ABLMG_REQUIRE(std::isfinite(value), "problem '" << name << "': parameter " << key << " = " << value);
    p.params[key] = value;
  }
  p.domain = Domain::rectangle(0, 0, 1, 1);

  if (name == "wavefront") {
    // Mitchell (2013): u = atan(α(r − r0)); u_r = α/(1+s²), u_rr = −2α² s/(1+s²)², s = α(r − r0).
    const double a = p.params["alpha"], xc = p.params["xc"], yc = p.params["yc"], r0 = p.params["r0"];
    ABLMG_REQUIRE(a > 0, "problem 'wavefront': alpha = " << a << " must be positive");
    p.formula = "atan(alpha*(sqrt((x-xc)^2+(y-yc)^2)-r0))";
    p.u = [=](double x, double y) { return std::atan(a * (std::hypot(x - xc, y - yc) - r0)); };
    p.grad = [=](double x, double y) -> Vec2 {
      const double r = std::hypot(x - xc, y - yc), s = a * (r - r0);
      return Vec2(x - xc, y - yc) * (a / (1 + s * s) / r);
    };
    p.f = [=](double x, double y) {
      const double r = std::hypot(x - xc, y - yc), s = a * (r - r0), d = 1 + s * s;
      const double ur = a / d, urr = -2 * a * a * s / (d * d);
      return -(urr + ur / r);
    };
  } else if (name == "peak") {
    // Mitchell (2013): u = exp(−α ρ²), ρ² = |x − xc|²; Δu = u (4α²ρ² − 4α).
    const double a = p.params["alpha"], xc = p.params["xc"], yc = p.params["yc"];
    ABLMG_REQUIRE(a > 0, "problem 'peak': alpha = " << a << " must be positive");
    p.formula = "exp(-alpha*((x-xc)^2+(y-yc)^2))";
    p.u = [=](double x, double y) { return std::exp(-a * ((x - xc) * (x - xc) + (y - yc) * (y - yc))); };
    p.grad = [=](double x, double y) -> Vec2 {
      const double u = std::exp(-a * ((x - xc) * (x - xc) + (y - yc) * (y - yc)));
      return Vec2(x - xc, y - yc) * (-2 * a * u);
    };
    p.f = [=](double x, double y) {
      const double r2 = (x - xc) * (x - xc) + (y - yc) * (y - yc);
      return std::exp(-a * r2) * (4 * a - 4 * a * a * r2);
    };
  } else if (name == "lshape") {
    // Mitchell (2013) (reentrant corner, ω = 3π/2): u = r^(2/3) sin(2θ/3), harmonic, so f = 0;
    // ∇u = (2/3) r^(−1/3) (−sin(θ/3), cos(θ/3)).
    p.domain = lshapeDomain();
    p.formula = "r^(2/3)*sin(2*theta/3)";
    auto theta = [](double x, double y) {
      double t = std::atan2(y, x);
      return t < 0 ? t + 2 * pi : t;
    };
    p.u = [=](double x, double y) {
      const double r = std::hypot(x, y);
      return r == 0 ? 0.0 : std::pow(r, 2.0 / 3) * std::sin(2 * theta(x, y) / 3);
    };
    p.grad = [=](double x, double y) -> Vec2 {
      const double r = std::hypot(x, y), t = theta(x, y);
      return Vec2(-std::sin(t / 3), std::cos(t / 3)) * (2.0 / 3 * std::pow(r, -1.0 / 3));
    };
    p.f = [](double, double) { return 0.0; };
  } else if (name == "tanhlayer") {
    // u = tanh((y − 0.5)/ε): u_y = (1 − u²)/ε, u_yy = −2u(1 − u²)/ε².
    const double e = p.params["epsilon"];
    ABLMG_REQUIRE(e > 0, "problem 'tanhlayer': epsilon = " << e << " must be positive");
    p.formula = "tanh((y-0.5)/epsilon)";
    p.u = [=](double, double y) { return std::tanh((y - 0.5) / e); };
    p.grad = [=](double, double y) -> Vec2 {
      const double u = std::tanh((y - 0.5) / e);
      return Vec2(0, (1 - u * u) / e);
    };
    p.f = [=](double, double y) {
      const double u = std::tanh((y - 0.5) / e);
      return 2 * u * (1 - u * u) / (e * e);
    };
  } else if (name == "smooth") {
    // u = eˣ sin(πy) + x y: Δu = (1 − π²) eˣ sin(πy).
    p.formula = "exp(x)*sin(pi*y)+x*y";
    p.u = [](double x, double y) { return std::exp(x) * std::sin(pi * y) + x * y; };
    p.grad = [](double x, double y) -> Vec2 {
      return Vec2(std::exp(x) * std::sin(pi * y) + y, pi * std::exp(x) * std::cos(pi * y) + x);
    };
    p.f = [](double x, double y) { return (pi * pi - 1) * std::exp(x) * std::sin(pi * y); };
  } else if (name == "sine") {
    p.formula = "sin(pi*x)*sin(pi*y)";
    p.u = [](double x, double y) { return std::sin(pi * x) * std::sin(pi * y); };
    p.grad = [](double x, double y) -> Vec2 {
      return Vec2(pi * std::cos(pi * x) * std::sin(pi * y), pi * std::sin(pi * x) * std::cos(pi * y));
    };
    p.f = [](double x, double y) { return 2 * pi * pi * std::sin(pi * x) * std::sin(pi * y); };
  } else {  // linear
    p.formula = "1+2*x-3*y";
    p.u = [](double x, double y) { return 1 + 2 * x - 3 * y; };
    p.grad = [](double, double) -> Vec2 { return Vec2(2, -3); };
    p.f = [](double, double) { return 0.0; };
  }
  return p;
}

}  // namespace ablmg::fem
