#include "ablmg/fem/test_problems.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace ablmg::fem {
namespace {

using std::numbers::pi;

/// The angle of (x, y) in the wedge [0, ω] (θ = 0 along the positive x axis, counter-clockwise).
/// A point of the excluded sector ω < θ < 2π (only round-off puts one there, e.g. y = −1e−17 on
/// the edge θ = 0, where atan2 gives ≈ 2π) takes the angle of the nearer edge, 0 or ω.
double angle(double x, double y, double omega) {
  double t = std::atan2(y, x);
  if (t < 0) t += 2 * pi;
  if (t > omega) t = t > 0.5 * (omega + 2 * pi) ? 0.0 : omega;
  return t;
}

/// (−1,1)² without the sector ω < θ < 2π (θ = angle above), vertices counter-clockwise from the
/// corner at the origin, segments tagged 1, 2, ... in order. ω ∈ (π, 2π]; ω = 2π is the square
/// with a slit from (1, 0) to the origin (Domain: a zero-width gap; tags 1 upper lip, 7 lower).
Domain wedgeDomain(double omega) {
  if (omega == 2 * pi) {
    BoundaryLoop slit;
    slit.points = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(-1, 1), Vec2(-1, -1), Vec2(1, -1), Vec2(1, 0)};
    slit.tags = {1, 2, 3, 4, 5, 6, 7};
    return Domain(slit);
  }
  BoundaryLoop loop;
  loop.points = {Vec2(0, 0), Vec2(1, 0)};
  const Vec2 corners[] = {Vec2(1, 1), Vec2(-1, 1), Vec2(-1, -1), Vec2(1, -1)};
  const double cornerAngles[] = {pi / 4, 3 * pi / 4, 5 * pi / 4, 7 * pi / 4};
  for (int k = 0; k < 4; ++k)
    if (cornerAngles[k] < omega - 1e-12) loop.points.push_back(corners[k]);
  const Vec2 d(std::cos(omega), std::sin(omega));
  Vec2 end = d / d.cwiseAbs().maxCoeff();  // the ray θ = ω meets the square's boundary here
  for (int k = 0; k < 2; ++k)
    if (std::abs(end[k] - std::round(end[k])) < 1e-12) end[k] = std::round(end[k]);  // exact corners (ω = 3π/2)
  if ((end - loop.points.back()).norm() > 1e-12) loop.points.push_back(end);
  for (std::size_t k = 0; k < loop.points.size(); ++k) loop.tags.push_back(int(k) + 1);
  return Domain(loop);
}

/// r^a sin(aθ) (harmonic), a = π/ω, θ ∈ [0, ω], and its gradient a r^(a−1) (sin((a−1)θ), cos((a−1)θ)).
double cornerU(double omega, double x, double y) {
  const double r = std::hypot(x, y), a = pi / omega;
  return r == 0 ? 0.0 : std::pow(r, a) * std::sin(a * angle(x, y, omega));
}
Vec2 cornerGrad(double omega, double x, double y) {
  const double r = std::hypot(x, y), t = angle(x, y, omega), a = pi / omega;
  return Vec2(std::sin((a - 1) * t), std::cos((a - 1) * t)) * (a * std::pow(r, a - 1));
}
/// cornerU and cornerGrad with one r and θ (the same values).
double cornerUAndGrad(double omega, double x, double y, Vec2& grad) {
  const double r = std::hypot(x, y), t = angle(x, y, omega), a = pi / omega;
  grad = Vec2(std::sin((a - 1) * t), std::cos((a - 1) * t)) * (a * std::pow(r, a - 1));
  return r == 0 ? 0.0 : std::pow(r, a) * std::sin(a * t);
}

/// atan(α(r − r0)), r = |x − c|: value, gradient and −Δ (u_r = α/(1+s²), u_rr = −2α²s/(1+s²)², s = α(r − r0)).
struct Front {
  double a, xc, yc, r0;
  double u(double x, double y) const { return std::atan(a * (std::hypot(x - xc, y - yc) - r0)); }
  Vec2 grad(double x, double y) const {
    const double r = std::hypot(x - xc, y - yc), s = a * (r - r0);
    return Vec2(x - xc, y - yc) * (a / (1 + s * s) / r);
  }
  double f(double x, double y) const {
    const double r = std::hypot(x - xc, y - yc), s = a * (r - r0), d = 1 + s * s;
    return -(-2 * a * a * s / (d * d) + a / d / r);
  }
};

/// exp(−α ρ²), ρ = |x − c|: value, gradient and −Δ = u (4α − 4α²ρ²).
struct Peak {
  double a, xc, yc;
  double u(double x, double y) const { return std::exp(-a * ((x - xc) * (x - xc) + (y - yc) * (y - yc))); }
  Vec2 grad(double x, double y) const { return Vec2(x - xc, y - yc) * (-2 * a * u(x, y)); }
  double f(double x, double y) const {
    const double r2 = (x - xc) * (x - xc) + (y - yc) * (y - yc);
    return std::exp(-a * r2) * (4 * a - 4 * a * a * r2);
  }
};

void buildWavefront(TestProblem& p) {
  // Mitchell (2013), wave front: u = atan(α(r − r0)).
  const Front w{p.params["alpha"], p.params["xc"], p.params["yc"], p.params["r0"]};
  ABLMG_REQUIRE(w.a > 0, "problem 'wavefront': alpha = " << w.a << " must be positive");
  p.formula = "atan(alpha*(sqrt((x-xc)^2+(y-yc)^2)-r0))";
  p.u = [=](double x, double y) { return w.u(x, y); };
  p.grad = [=](double x, double y) { return w.grad(x, y); };
  p.f = [=](double x, double y) { return w.f(x, y); };
}

void buildPeak(TestProblem& p) {
  // Mitchell (2013), peak: u = exp(−α ρ²).
  const Peak k{p.params["alpha"], p.params["xc"], p.params["yc"]};
  ABLMG_REQUIRE(k.a > 0, "problem 'peak': alpha = " << k.a << " must be positive");
  p.formula = "exp(-alpha*((x-xc)^2+(y-yc)^2))";
  p.u = [=](double x, double y) { return k.u(x, y); };
  p.grad = [=](double x, double y) { return k.grad(x, y); };
  p.f = [=](double x, double y) { return k.f(x, y); };
}

void buildCorner(TestProblem& p, double omega) {
  // Mitchell (2013), reentrant corner: u = r^(π/ω) sin(πθ/ω), harmonic (f = 0).
  p.u = [=](double x, double y) { return cornerU(omega, x, y); };
  p.grad = [=](double x, double y) { return cornerGrad(omega, x, y); };
  p.valueAndGrad = [=](double x, double y, Vec2& g) { return cornerUAndGrad(omega, x, y, g); };
  p.f = [](double, double) { return 0.0; };
}

void buildLineSingularity(TestProblem& p) {
  // Mitchell (2013), interior line singularity on (−1,1)²: u = cos(πy/2) + s^α for
  // s = x − β(y + 1) > 0 (cos(πy/2) elsewhere); −Δu = (π²/4) cos(πy/2) − α(α−1)(1+β²) s^(α−2).
  const double a = p.params["alpha"], b = p.params["beta"];
  ABLMG_REQUIRE(a > 1, "problem 'linesing': alpha = " << a << " must be > 1 (u in H1 with a load in L1)");
  p.domain = Domain::rectangle(-1, -1, 1, 1);
  p.formula = "cos(pi*y/2)+max(x-beta*(y+1),0)^alpha";
  p.u = [=](double x, double y) {
    const double s = x - b * (y + 1);
    return std::cos(pi * y / 2) + (s > 0 ? std::pow(s, a) : 0.0);
  };
  p.grad = [=](double x, double y) -> Vec2 {
    const double s = x - b * (y + 1), g = s > 0 ? a * std::pow(s, a - 1) : 0.0;
    return Vec2(g, -pi / 2 * std::sin(pi * y / 2) - b * g);
  };
  p.f = [=](double x, double y) {
    const double s = x - b * (y + 1);
    return pi * pi / 4 * std::cos(pi * y / 2) - (s > 0 ? a * (a - 1) * (1 + b * b) * std::pow(s, a - 2) : 0.0);
  };
}

void buildMultiple(TestProblem& p) {
  // Mitchell (2013), multiple difficulties on the L-shape (ω = 3π/2): u = r^(2/3) sin(2θ/3)
  // + exp(−α_p ρ_p²) + atan(α_w(r_w − r0)) + exp(−(1 + y)/ε) (a boundary layer along y = −1).
  const Peak k{p.params["alpha_p"], p.params["xp"], p.params["yp"]};
  const Front w{p.params["alpha_w"], p.params["xw"], p.params["yw"], p.params["r0"]};
  const double e = p.params["epsilon"], omega = 1.5 * pi;
  ABLMG_REQUIRE(k.a > 0 && w.a > 0 && e > 0, "problem 'multiple': alpha_p, alpha_w and epsilon must be positive (got "
                                                 << k.a << ", " << w.a << ", " << e << ")");
  p.domain = wedgeDomain(omega);
  p.formula =
      "r^(2/3)*sin(2*theta/3)+exp(-alpha_p*((x-xp)^2+(y-yp)^2))+atan(alpha_w*(sqrt((x-xw)^2+(y-yw)^2)-r0))"
      "+exp(-(1+y)/epsilon)";
  p.u = [=](double x, double y) { return cornerU(omega, x, y) + k.u(x, y) + w.u(x, y) + std::exp(-(1 + y) / e); };
  p.grad = [=](double x, double y) -> Vec2 {
    return cornerGrad(omega, x, y) + k.grad(x, y) + w.grad(x, y) + Vec2(0, -std::exp(-(1 + y) / e) / e);
  };
  p.valueAndGrad = [=](double x, double y, Vec2& g) {
    Vec2 corner;
    const double uc = cornerUAndGrad(omega, x, y, corner), layer = std::exp(-(1 + y) / e);
    g = corner + k.grad(x, y) + w.grad(x, y) + Vec2(0, -layer / e);
    return uc + k.u(x, y) + w.u(x, y) + layer;
  };
  p.f = [=](double x, double y) { return k.f(x, y) + w.f(x, y) - std::exp(-(1 + y) / e) / (e * e); };
}

void buildTanhLayer(TestProblem& p) {
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
}

void buildVerification(TestProblem& p) {
  if (p.name == "smooth") {  // u = eˣ sin(πy) + x y: Δu = (1 − π²) eˣ sin(πy).
    p.formula = "exp(x)*sin(pi*y)+x*y";
    p.u = [](double x, double y) { return std::exp(x) * std::sin(pi * y) + x * y; };
    p.grad = [](double x, double y) -> Vec2 {
      return Vec2(std::exp(x) * std::sin(pi * y) + y, pi * std::exp(x) * std::cos(pi * y) + x);
    };
    p.f = [](double x, double y) { return (pi * pi - 1) * std::exp(x) * std::sin(pi * y); };
  } else if (p.name == "sine") {
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
}

std::map<std::string, double> defaultsOf(const std::string& name) {
  if (name == "wavefront") return {{"alpha", 20.0}, {"xc", -0.05}, {"yc", -0.05}, {"r0", 0.7}};
  if (name == "peak") return {{"alpha", 1000.0}, {"xc", 0.5}, {"yc", 0.5}};
  if (name == "tanhlayer") return {{"epsilon", 0.01}};
  if (name == "reentrant") return {{"omega", 1.75 * pi}};
  if (name == "linesing") return {{"alpha", 2.5}, {"beta", 0.6}};
  if (name == "multiple")
    return {{"alpha_p", 1000.0}, {"xp", -std::sqrt(5.0) / 4},
            {"yp", -0.25},       {"alpha_w", 200.0},
            {"xw", 0.0},         {"yw", -0.75},
            {"r0", 0.75},        {"epsilon", 0.01}};
  return {};
}

void requireKnown(const std::string& name) {
  const auto names = problemNames();
  if (std::find(names.begin(), names.end(), name) != names.end()) return;
  std::ostringstream os;
  for (const auto& n : names) os << (&n == &names.front() ? "" : ", ") << n;
  ABLMG_REQUIRE(false, "unknown problem '" << name << "' (valid: " << os.str() << ")");
}

}  // namespace

std::vector<std::string> problemNames() {
  return {"wavefront", "peak", "lshape", "tanhlayer", "reentrant", "linesing", "multiple", "smooth", "sine", "linear"};
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
  requireKnown(name);
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
    buildWavefront(p);
  } else if (name == "peak") {
    buildPeak(p);
  } else if (name == "lshape") {
    p.domain = wedgeDomain(1.5 * pi);
    p.formula = "r^(2/3)*sin(2*theta/3)";
    buildCorner(p, 1.5 * pi);
  } else if (name == "reentrant") {
    double omega = p.params["omega"];
    if (std::abs(omega - 2 * pi) <= 1e-9) omega = p.params["omega"] = 2 * pi;  // the slit
    ABLMG_REQUIRE(omega > pi && omega <= 2 * pi,
                  "problem 'reentrant': omega = " << omega << " must be in (pi, 2 pi] (2 pi: the slit)");
    p.domain = wedgeDomain(omega);
    p.formula = "r^(pi/omega)*sin(pi*theta/omega)";
    buildCorner(p, omega);
  } else if (name == "linesing") {
    buildLineSingularity(p);
  } else if (name == "multiple") {
    buildMultiple(p);
  } else if (name == "tanhlayer") {
    buildTanhLayer(p);
  } else {
    buildVerification(p);
  }
  return p;
}

}  // namespace ablmg::fem
