#include "ablmg/io/surface_picture.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"

#include <Eigen/Geometry>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>

namespace ablmg::io {

void drawSurface(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
                 const std::vector<std::array<int, 3>>& triangles, const SurfaceViewOptions& o) {
  using V3 = Eigen::Vector3d;
  ABLMG_REQUIRE(!vertices.empty() && !triangles.empty(), path << ": empty surface mesh");
  ABLMG_REQUIRE(o.width >= 50 && o.margin >= 0 && 2 * o.margin < o.width, path << ": bad picture size");
  ABLMG_REQUIRE(o.elevationDeg >= -90 && o.elevationDeg <= 90, path << ": elevation must be in [-90, 90]");
  const int n = int(vertices.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int v : triangles[t])
      ABLMG_REQUIRE(v >= 0 && v < n, path << ": triangle " << t << " has vertex " << v << " (of " << n << ")");
  for (int v = 0; v < n; ++v) ABLMG_REQUIRE(vertices[v].allFinite(), path << ": vertex " << v << " is not finite");

  // 1. Camera frame: d towards the viewer, `right` horizontal, `up` = right × forward.
  const double phi = o.azimuthDeg * std::numbers::pi / 180, psi = o.elevationDeg * std::numbers::pi / 180;
  const V3 d(std::cos(psi) * std::cos(phi), std::cos(psi) * std::sin(phi), std::sin(psi));
  V3 right(-std::sin(phi), std::cos(phi), 0.0);
  const V3 up = right.cross(-d).normalized();
  const V3 light = (d + 0.6 * up - 0.4 * right).normalized();

  // 2. Projection and image size (equal scales, screen y down).
  std::vector<double> sx(n), sy(n);
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (int v = 0; v < n; ++v) {
    sx[v] = vertices[v].dot(right), sy[v] = vertices[v].dot(up);
    xmin = std::min(xmin, sx[v]), xmax = std::max(xmax, sx[v]), ymin = std::min(ymin, sy[v]),
    ymax = std::max(ymax, sy[v]);
  }
  const double dx = std::max(xmax - xmin, 1e-300), dy = std::max(ymax - ymin, 1e-300);
  const double scale = (o.width - 2 * o.margin) / dx;
  const int height = std::clamp(int(std::ceil(dy * scale)) + 2 * o.margin, 50, 20000);
  const double s = std::min(scale, (height - 2 * o.margin) / dy);
  const auto px = [&](int v) { return o.margin + (sx[v] - xmin) * s; };
  const auto py = [&](int v) { return height - o.margin - (sy[v] - ymin) * s; };

  // 3. Painter's order: farthest centroid first (stable: ties keep the input order).
  std::vector<double> depth(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    depth[t] = (vertices[tri[0]] + vertices[tri[1]] + vertices[tri[2]]).dot(d);
  }
  std::vector<std::size_t> order(triangles.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });

  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, o.width, height), cairo_surface_destroy);
  ABLMG_REQUIRE(cairo_surface_status(surface.get()) == CAIRO_STATUS_SUCCESS,
                path << ": cannot create a " << o.width << "x" << height << " image");
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> context(cairo_create(surface.get()), cairo_destroy);
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);

  // 4. Fill back to front with Lambert shading; each outline is stroked right after its fill
  //    (in the fill colour when edges are off: it hides the antialiasing seams).
  const double base[3] = {0.55, 0.70, 0.92};
  const double ambient = std::clamp(o.ambient, 0.0, 1.0);
  for (std::size_t t : order) {
    const auto& tri = triangles[t];
    const V3 nrm = (vertices[tri[1]] - vertices[tri[0]]).cross(vertices[tri[2]] - vertices[tri[0]]);
    const double len = nrm.norm();
    const double lambert = len > 0 ? std::abs(nrm.dot(light)) / len : 0.0;
    const double c = ambient + (1 - ambient) * lambert;
    cairo_move_to(cr, px(tri[0]), py(tri[0]));
    cairo_line_to(cr, px(tri[1]), py(tri[1]));
    cairo_line_to(cr, px(tri[2]), py(tri[2]));
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, c * base[0], c * base[1], c * base[2]);
    cairo_fill_preserve(cr);
    if (o.edges) {
      cairo_set_source_rgb(cr, 0.25 * c, 0.25 * c, 0.3 * c);
      cairo_set_line_width(cr, o.lineWidth);
    } else {
      cairo_set_line_width(cr, 0.5);
    }
    cairo_stroke(cr);
  }

  cairo_surface_flush(surface.get());
  writePathAtomically(path, [&](const std::string& tmp) {
    if (cairo_surface_write_to_png(surface.get(), tmp.c_str()) != CAIRO_STATUS_SUCCESS)
      ABLMG_FAIL(path << ": cannot write PNG");
  });
}

}  // namespace ablmg::io
