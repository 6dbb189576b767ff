#include "ablmg/mesher/surface.hpp"

#include "ablmg/core/error.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace ablmg::mesher {
namespace {

constexpr double kPi = std::numbers::pi;

/// A built-in surface: closed-form r and derivatives.
class FormulaSurface final : public ParametricSurface {
 public:
  using PointFn = std::function<Vec3(double, double)>;
  using DerivFn = std::function<std::array<Vec3, 2>(double, double)>;
  FormulaSurface(std::string text, Domain domain, PointFn r, DerivFn dr, bool periodic = false)
      : text_(std::move(text)), domain_(std::move(domain)), r_(std::move(r)), dr_(std::move(dr)), periodic_(periodic) {}
  bool periodic() const override { return periodic_; }
  Vec3 point(const Vec2& uv) const override { return r_(uv.x(), uv.y()); }
  std::array<Vec3, 2> derivatives(const Vec2& uv) const override { return dr_(uv.x(), uv.y()); }
  const Domain& parameterDomain() const override { return domain_; }
  std::string description() const override { return text_; }

 private:
  std::string text_;
  Domain domain_;
  PointFn r_;
  DerivFn dr_;
  bool periodic_;
};

/// The torus of major radius 1 and minor radius 0.3 (the "torus" and "torus-closed" built-ins).
Vec3 torusPoint(double u, double v) {
  const double w = 1 + 0.3 * std::cos(v);
  return Vec3(w * std::cos(u), w * std::sin(u), 0.3 * std::sin(v));
}
std::array<Vec3, 2> torusTangents(double u, double v) {
  const double w = 1 + 0.3 * std::cos(v);
  return std::array<Vec3, 2>{
      Vec3(-w * std::sin(u), w * std::cos(u), 0),
      Vec3(-0.3 * std::sin(v) * std::cos(u), -0.3 * std::sin(v) * std::sin(u), 0.3 * std::cos(v))};
}

}  // namespace

std::array<Vec3, 2> ParametricSurface::derivatives(const Vec2& uv) const {
  const double hu = 1e-6 * (1 + std::abs(uv.x())), hv = 1e-6 * (1 + std::abs(uv.y()));
  return {(point(uv + Vec2(hu, 0)) - point(uv - Vec2(hu, 0))) / (2 * hu),
          (point(uv + Vec2(0, hv)) - point(uv - Vec2(0, hv))) / (2 * hv)};
}

std::vector<std::string> builtinSurfaceList() {
  return {"paper-fig16   x=u, y=v, z=cos^2(pi(u^2+v^2))              (u,v) in [-1,1]^2  (paper eq. 18, Fig. 16)",
          "sphere-patch  unit sphere (sin v cos u, sin v sin u, cos v)  (u,v) in [0,pi]x[pi/6,5pi/6]",
          "torus         ((1+0.3cos v)cos u, (1+0.3cos v)sin u, 0.3 sin v)  (u,v) in [0,3pi/2]^2 (seams not glued)",
          "cylinder      (cos u, sin u, v)                            (u,v) in [0,pi]x[0,2]",
          "saddle        x=u, y=v, z=u^2-v^2                          (u,v) in [-1,1]^2",
          "torus-closed  the torus above over (u,v) in [0,2pi]^2, seams welded: a closed surface"};
}

std::unique_ptr<ParametricSurface> makeBuiltinSurface(const std::string& name) {
  if (name == "paper-fig16")
    return std::make_unique<FormulaSurface>(
        builtinSurfaceList()[0], Domain::rectangle(-1, -1, 1, 1),
        [](double u, double v) {
          const double c = std::cos(kPi * (u * u + v * v));
          return Vec3(u, v, c * c);
        },
        [](double u, double v) {
          const double s2 = std::sin(2 * kPi * (u * u + v * v));  // d/du cos²(s) = −sin(2s)·2πu
          return std::array<Vec3, 2>{Vec3(1, 0, -2 * kPi * u * s2), Vec3(0, 1, -2 * kPi * v * s2)};
        });
  if (name == "sphere-patch")
    return std::make_unique<FormulaSurface>(
        builtinSurfaceList()[1], Domain::rectangle(0, kPi / 6, kPi, 5 * kPi / 6),
        [](double u, double v) { return Vec3(std::sin(v) * std::cos(u), std::sin(v) * std::sin(u), std::cos(v)); },
        [](double u, double v) {
          return std::array<Vec3, 2>{Vec3(-std::sin(v) * std::sin(u), std::sin(v) * std::cos(u), 0),
                                     Vec3(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), -std::sin(v))};
        });
  if (name == "torus")
    return std::make_unique<FormulaSurface>(builtinSurfaceList()[2], Domain::rectangle(0, 0, 1.5 * kPi, 1.5 * kPi),
                                            torusPoint, torusTangents);
  if (name == "torus-closed")
    return std::make_unique<FormulaSurface>(builtinSurfaceList()[5], Domain::rectangle(0, 0, 2 * kPi, 2 * kPi),
                                            torusPoint, torusTangents, true);
  if (name == "cylinder")
    return std::make_unique<FormulaSurface>(
        builtinSurfaceList()[3], Domain::rectangle(0, 0, kPi, 2),
        [](double u, double v) { return Vec3(std::cos(u), std::sin(u), v); },
        [](double u, double) {
          return std::array<Vec3, 2>{Vec3(-std::sin(u), std::cos(u), 0), Vec3(0, 0, 1)};
        });
  if (name == "saddle")
    return std::make_unique<FormulaSurface>(
        builtinSurfaceList()[4], Domain::rectangle(-1, -1, 1, 1),
        [](double u, double v) { return Vec3(u, v, u * u - v * v); },
        [](double u, double v) {
          return std::array<Vec3, 2>{Vec3(1, 0, 2 * u), Vec3(0, 1, -2 * v)};
        });
  throw InputError(
      "surface: unknown built-in '" + name +
      "' (known: paper-fig16, sphere-patch, torus, torus-closed, cylinder, saddle; see `ablmg surface --list`)");
}

Metric3Field isotropicMetric3(double h) {
  ABLMG_REQUIRE(std::isfinite(h) && h > 0, "surface: size h must be positive and finite (got " << h << ")");
  const Metric3 m = Metric3::Identity() / (h * h);
  return [m](const Vec3&) { return m; };
}

Metric2 InducedMetricField::at(const Vec2& uv) const {
  const auto d = surface_.derivatives(uv);
  Eigen::Matrix<double, 3, 2> J;
  J.col(0) = d[0];
  J.col(1) = d[1];
  const Metric3 m3 = m3_(surface_.point(uv));
  const Eigen::Matrix2d m2 = J.transpose() * m3 * J;  // eq. (16)
  // rank test on the first fundamental form JᵀJ: relative determinant
  const Eigen::Matrix2d g = J.transpose() * J;
  const double rel = g.determinant() / std::max(1e-300, g(0, 0) * g(1, 1));
  ABLMG_REQUIRE(J.allFinite() && rel > 1e-12, "surface: the Jacobian [r_u r_v] is rank-deficient at (u, v) = ("
                                                  << uv.x() << ", " << uv.y()
                                                  << ") (a pole or fold); restrict the parameter domain");
  std::ostringstream where;
  where << "induced metric at (u, v) = (" << uv.x() << ", " << uv.y() << ")";
  return Metric2::fromTensor(m2(0, 0), 0.5 * (m2(0, 1) + m2(1, 0)), m2(1, 1), where.str());
}

double SurfaceMesh::area() const {
  double a = 0;
  for (const auto& t : triangles)
    a += 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
  return a;
}

SurfaceMesh mapToSurface(const Mesh2& parameterMesh, const ParametricSurface& surface) {
  SurfaceMesh s;
  s.vertices.reserve(parameterMesh.vertices.size());
  for (const auto& uv : parameterMesh.vertices) {
    const Vec3 p = surface.point(uv);
    ABLMG_REQUIRE(p.allFinite(), "surface: r(" << uv.x() << ", " << uv.y() << ") is not finite");
    s.vertices.push_back(p);
  }
  s.triangles = parameterMesh.triangles;
  if (surface.periodic() && !s.vertices.empty()) {
    Vec3 lo = s.vertices.front(), hi = lo;
    for (const auto& p : s.vertices) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    s = weldSeams(s, 1e-9 * (hi - lo).norm());
  }
  return s;
}

std::vector<double> leeQuality(const SurfaceMesh& mesh, const Metric3Field& m3) {
  std::vector<double> q;
  q.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Vec3 &p1 = mesh.vertices[t[0]], &p2 = mesh.vertices[t[1]], &p3 = mesh.vertices[t[2]];
    const Vec3 e12 = p2 - p1, e13 = p3 - p1, e23 = p3 - p2;
    const Vec3 n = e12.cross(e13);
    const double area2 = n.norm();  // Det([P2−P1, P3−P1]) in the triangle's plane
    if (!(area2 > 0)) {
      q.push_back(0.0);
      continue;
    }
    Eigen::Matrix<double, 3, 2> T;  // orthonormal basis of the triangle's plane
    T.col(0) = e12.normalized();
    T.col(1) = n.cross(e12).normalized();
    double alpha = 1e300;
    for (int i = 0; i < 3; ++i) {
      const Metric3 M = m3(mesh.vertices[t[i]]);
      const double detM = (T.transpose() * M * T).determinant();
      const double d2 = e12.dot(M * e12) + e23.dot(M * e23) + e13.dot(M * e13);
      alpha = std::min(alpha, 2 * std::sqrt(3.0) * std::sqrt(detM) * area2 / d2);  // eq. (20)
    }
    q.push_back(alpha);  // eq. (19)
  }
  return q;
}

std::vector<double> surfaceEdgeLengths(const SurfaceMesh& mesh, const Metric3Field& m3) {
  std::vector<std::array<int, 2>> edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> len;
  len.reserve(edges.size());
  for (const auto& e : edges) {
    const Vec3 d = mesh.vertices[e[1]] - mesh.vertices[e[0]];
    const Metric3 M = 0.5 * (m3(mesh.vertices[e[0]]) + m3(mesh.vertices[e[1]]));
    len.push_back(std::sqrt(d.dot(M * d)));
  }
  return len;
}

SurfaceMesh weldSeams(const SurfaceMesh& mesh, double tolerance) {
  const int n = int(mesh.vertices.size());
  // Sort by x; candidates of a vertex are the following ones within tolerance in x.
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order[std::size_t(i)] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return mesh.vertices[std::size_t(a)].x() < mesh.vertices[std::size_t(b)].x() ||
           (mesh.vertices[std::size_t(a)].x() == mesh.vertices[std::size_t(b)].x() && a < b);
  });
  std::vector<int> rep(static_cast<std::size_t>(n));  // union-find, each group's root its lowest index
  for (int i = 0; i < n; ++i) rep[std::size_t(i)] = i;
  auto find = [&](int i) {
    while (rep[std::size_t(i)] != i) i = rep[std::size_t(i)] = rep[std::size_t(rep[std::size_t(i)])];
    return i;
  };
  for (int k = 0; k < n; ++k) {
    const int a = order[std::size_t(k)];
    for (int q = k + 1; q < n; ++q) {
      const int b = order[std::size_t(q)];
      if (mesh.vertices[std::size_t(b)].x() - mesh.vertices[std::size_t(a)].x() > tolerance) break;
      if ((mesh.vertices[std::size_t(b)] - mesh.vertices[std::size_t(a)]).norm() <= tolerance) {
        const int ra = find(a), rb = find(b);
        rep[std::size_t(std::max(ra, rb))] = std::min(ra, rb);
      }
    }
  }
  for (int i = 0; i < n; ++i) rep[std::size_t(i)] = find(i);
  SurfaceMesh out;
  std::vector<int> index(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i)
    if (rep[std::size_t(i)] == i) {
      index[std::size_t(i)] = int(out.vertices.size());
      out.vertices.push_back(mesh.vertices[std::size_t(i)]);
    }
  for (const auto& t : mesh.triangles) {
    std::array<int, 3> w{};
    for (int k = 0; k < 3; ++k) w[std::size_t(k)] = index[std::size_t(rep[std::size_t(t[std::size_t(k)])])];
    if (w[0] != w[1] && w[1] != w[2] && w[0] != w[2]) out.triangles.push_back(w);
  }
  return out;
}

long countBoundaryEdges(const SurfaceMesh& mesh) {
  std::vector<std::pair<int, int>> e;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) e.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  std::sort(e.begin(), e.end());
  long single = 0;
  for (std::size_t i = 0; i < e.size();) {
    std::size_t j = i;
    while (j < e.size() && e[j] == e[i]) ++j;
    single += j - i == 1;
    i = j;
  }
  return single;
}

std::string checkManifold(const SurfaceMesh& mesh) {
  std::vector<std::array<int, 3>> half;  // (lo, hi, forward)
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      half.push_back({std::min(a, b), std::max(a, b), a < b});
    }
  std::sort(half.begin(), half.end());
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    while (j < half.size() && half[j][0] == half[i][0] && half[j][1] == half[i][1]) ++j;
    const std::string name = "edge (" + std::to_string(half[i][0]) + ", " + std::to_string(half[i][1]) + ")";
    if (j - i > 2) return name + " lies in " + std::to_string(j - i) + " triangles";
    if (j - i == 2 && half[i][2] == half[i + 1][2])
      return name + " is used twice in the same direction (inconsistent orientation)";
    i = j;
  }
  return "";
}

}  // namespace ablmg::mesher
