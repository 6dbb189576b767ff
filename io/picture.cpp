#include "ablmg/io/picture.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"

#include <cairo.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

namespace ablmg::io {
namespace {

/// World → pixel map with equal scales, y up.
struct View {
  double x0, y0, scale, height;
  int margin;
  double px(double x) const { return margin + (x - x0) * scale; }
  double py(double y) const { return height - margin - (y - y0) * scale; }
};

View makeView(double xmin, double ymin, double xmax, double ymax, const PictureOptions& o, int extraRight, int& w,
              int& h) {
  ABLMG_REQUIRE(std::isfinite(xmin) && std::isfinite(xmax) && std::isfinite(ymin) && std::isfinite(ymax),
                "picture: non-finite coordinates");
  const double dx = std::max(xmax - xmin, 1e-300), dy = std::max(ymax - ymin, 1e-300);
  const int drawW = std::max(50, o.width - 2 * o.margin - extraRight);
  const double scale = drawW / dx;
  w = o.width;
  h = std::clamp(int(std::ceil(dy * scale)) + 2 * o.margin, 50, 20000);
  const double s = std::min(scale, (h - 2 * o.margin) / dy);
  return {xmin, ymin, s, double(h), o.margin};
}

/// The rows of an ARGB32 surface into `png` (set up for `file`) as 8-bit RGB: premultiplied
/// ARGB in native byte order composited on white, c + (255 − a). False on a libpng error, which
/// libpng reports by longjmp to the setjmp here (nothing with a destructor lives in this frame).
bool writeRgbRows(png_structp png, png_infop info, std::FILE* file, cairo_surface_t* surface, png_byte* row) {
  if (setjmp(png_jmpbuf(png)) != 0) return false;
  const int w = cairo_image_surface_get_width(surface), h = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  png_init_io(png, file);
  png_set_compression_level(png, 1);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_set_IHDR(png, info, png_uint_32(w), png_uint_32(h), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) {
    const auto* px = reinterpret_cast<const std::uint32_t*>(data + std::ptrdiff_t(y) * stride);
    for (int x = 0; x < w; ++x) {
      const std::uint32_t v = px[x], white = 255 - (v >> 24);
      row[3 * x] = png_byte(((v >> 16) & 255) + white);
      row[3 * x + 1] = png_byte(((v >> 8) & 255) + white);
      row[3 * x + 2] = png_byte((v & 255) + white);
    }
    png_write_row(png, row);
  }
  png_write_end(png, nullptr);
  return true;
}

/// An ARGB32 image surface as an RGB PNG (the canvases are painted white first, so nothing of
/// the alpha is lost), zlib's fastest level and the Up filter. cairo's own writer (level 6,
/// libpng's adaptive filter choice per row) spent 1.5·10⁹ instructions on a 1200 × 1200 mesh
/// picture, 10–15 % of an `ablmg adapt` run to 3·10⁴ vertices. False on an I/O or libpng error.
bool writeRgbPng(cairo_surface_t* surface, const std::string& path) {
  std::vector<png_byte> row(std::size_t(cairo_image_surface_get_width(surface)) * 3);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool ok = png && info && writeRgbRows(png, info, file, surface, row.data());
  if (png) png_destroy_write_struct(&png, info ? &info : nullptr);
  return std::fclose(file) == 0 && ok;
}

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

struct Canvas {
  Surface surface;
  Context cr;
  Canvas(int w, int h)
      : surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h), cairo_surface_destroy),
        cr(cairo_create(surface.get()), cairo_destroy) {
    ABLMG_REQUIRE(cairo_surface_status(surface.get()) == CAIRO_STATUS_SUCCESS,
                  "picture: cannot create a " << w << "×" << h << " image");
    cairo_set_source_rgb(cr.get(), 1, 1, 1);
    cairo_paint(cr.get());
  }
  void save(const std::string& path) {
    cairo_surface_flush(surface.get());
    writePathAtomically(path, [&](const std::string& tmp) {
      if (!writeRgbPng(surface.get(), tmp)) ABLMG_FAIL(path << ": cannot write PNG");
    });
  }
};

/// Blue → cyan → yellow → red ramp for t in [0, 1].
void ramp(double t, double& r, double& g, double& b) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  r = std::clamp(1.5 - std::abs(4 * t - 3), 0.0, 1.0);
  g = std::clamp(1.5 - std::abs(4 * t - 2), 0.0, 1.0);
  b = std::clamp(1.5 - std::abs(4 * t - 1), 0.0, 1.0);
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size = 13) {
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

/// Strokes the boundary or interface edges `edges` of `mesh` in the current colour, `width` wide.
template <class Edges>
void strokeEdges(cairo_t* cr, const View& v, const Mesh2& mesh, const Edges& edges, double width) {
  cairo_set_line_width(cr, width);
  for (const auto& e : edges) {
    cairo_move_to(cr, v.px(mesh.vertices[e.a].x()), v.py(mesh.vertices[e.a].y()));
    cairo_line_to(cr, v.px(mesh.vertices[e.b].x()), v.py(mesh.vertices[e.b].y()));
  }
  cairo_stroke(cr);
}

void drawEdges(cairo_t* cr, const View& v, const Mesh2& mesh, double width, double grey) {
  cairo_set_source_rgb(cr, grey, grey, grey);
  cairo_set_line_width(cr, width);
  for (const auto& e : mesh.edges()) {
    cairo_move_to(cr, v.px(mesh.vertices[e[0]].x()), v.py(mesh.vertices[e[0]].y()));
    cairo_line_to(cr, v.px(mesh.vertices[e[1]].x()), v.py(mesh.vertices[e[1]].y()));
  }
  cairo_stroke(cr);
}

}  // namespace

void drawMesh(const std::string& path, const Mesh2& mesh, std::span<const double> triangleValues,
              const std::string& valueName, const PictureOptions& o) {
  ABLMG_REQUIRE(mesh.numVertices() > 0, path << ": empty mesh");
  ABLMG_REQUIRE(
      triangleValues.empty() || triangleValues.size() == std::size_t(mesh.numTriangles()),
      path << ": " << triangleValues.size() << " triangle values for " << mesh.numTriangles() << " triangles");
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  for (const auto& p : mesh.vertices) {
    xmin = std::min(xmin, p.x()), xmax = std::max(xmax, p.x()), ymin = std::min(ymin, p.y()),
    ymax = std::max(ymax, p.y());
  }
  const bool coloured = !triangleValues.empty();
  int w, h;
  const View v = makeView(xmin, ymin, xmax, ymax, o, coloured ? 110 : 0, w, h);
  Canvas c(w, h);
  cairo_t* cr = c.cr.get();
  if (coloured) {
    double lo = 1e300, hi = -1e300;
    for (double x : triangleValues)
      if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
    if (!(lo <= hi)) lo = 0, hi = 1;
    const double span = hi > lo ? hi - lo : 1;
    for (int t = 0; t < mesh.numTriangles(); ++t) {
      double r, g, b;
      ramp((triangleValues[t] - lo) / span, r, g, b);
      cairo_set_source_rgb(cr, r, g, b);
      const auto& tr = mesh.triangles[t];
      cairo_move_to(cr, v.px(mesh.vertices[tr[0]].x()), v.py(mesh.vertices[tr[0]].y()));
      for (int k = 1; k < 3; ++k) cairo_line_to(cr, v.px(mesh.vertices[tr[k]].x()), v.py(mesh.vertices[tr[k]].y()));
      cairo_close_path(cr);
      cairo_fill(cr);
    }
    // Colour bar.
    const double bx = w - 100, by0 = o.margin, by1 = h - o.margin;
    for (int i = 0; i < 100; ++i) {
      double r, g, b;
      ramp(i / 99.0, r, g, b);
      cairo_set_source_rgb(cr, r, g, b);
      cairo_rectangle(cr, bx, by1 - (i + 1) * (by1 - by0) / 100, 20, (by1 - by0) / 100 + 1);
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, bx + 24, by0 + 12, fmt(hi));
    text(cr, bx + 24, by1, fmt(lo));
    text(cr, bx - 10, by0 - 8, valueName);
  }
  drawEdges(cr, v, mesh, o.lineWidth, coloured ? 0.2 : 0.0);
  cairo_set_source_rgb(cr, 0, 0, 0);
  strokeEdges(cr, v, mesh, mesh.boundaryEdges, 2 * o.lineWidth + 0.8);
  if (!mesh.interfaceEdges.empty()) {
    cairo_set_source_rgb(cr, 0.75, 0, 0);
    strokeEdges(cr, v, mesh, mesh.interfaceEdges, 1.5 * o.lineWidth + 0.6);
  }
  c.save(path);
}

void drawBubbles(const std::string& path, const Domain& domain, std::span<const Vec2> centres,
                 std::span<const Metric2> metrics, const Mesh2* mesh, const PictureOptions& o) {
  ABLMG_REQUIRE(centres.size() == metrics.size(),
                path << ": " << centres.size() << " centres but " << metrics.size() << " metrics");
  auto [lo, hi] = domain.boundingBox();
  for (std::size_t i = 0; i < centres.size(); ++i) {  // bubbles crossing the boundary stay in the picture
    const double r = 0.5 * metrics[i].eigen().h1;
    if (!std::isfinite(r) || !centres[i].allFinite()) continue;
    lo = lo.cwiseMin(centres[i] - Vec2(r, r));
    hi = hi.cwiseMax(centres[i] + Vec2(r, r));
  }
  int w, h;
  const View v = makeView(lo.x(), lo.y(), hi.x(), hi.y(), o, 0, w, h);
  Canvas c(w, h);
  cairo_t* cr = c.cr.get();
  if (mesh) drawEdges(cr, v, *mesh, o.lineWidth, 0.75);
  // Bubbles: unit-metric ellipse scaled by 1/2 (semi-axes h1/2, h2/2, angle θ).
  cairo_set_line_width(cr, 0.8);
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const auto e = metrics[i].eigen();
    cairo_save(cr);
    cairo_translate(cr, v.px(centres[i].x()), v.py(centres[i].y()));
    cairo_rotate(cr, -e.theta);  // y is flipped on screen
    cairo_scale(cr, std::max(0.5 * e.h1 * v.scale, 1e-3), std::max(0.5 * e.h2 * v.scale, 1e-3));
    cairo_arc(cr, 0, 0, 1, 0, 2 * std::numbers::pi);
    cairo_restore(cr);
    cairo_set_source_rgba(cr, 0.2, 0.45, 0.9, 0.25);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.1, 0.25, 0.6);
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1.6);
  for (const auto& loop : domain.loops()) {
    for (std::size_t k = 0; k < loop.points.size(); ++k) {
      const auto& p = loop.points[k];
      if (k == 0)
        cairo_move_to(cr, v.px(p.x()), v.py(p.y()));
      else
        cairo_line_to(cr, v.px(p.x()), v.py(p.y()));
    }
    cairo_close_path(cr);
  }
  cairo_stroke(cr);
  c.save(path);
}

void drawLogLogPlot(const std::string& path, const std::vector<Curve>& curves,
                    const std::vector<double>& referenceSlopes, const std::string& xLabel, const std::string& yLabel,
                    const std::string& title, const PictureOptions& o) {
  double lx0 = 1e300, lx1 = -1e300, ly0 = 1e300, ly1 = -1e300;
  for (const auto& c : curves) {
    ABLMG_REQUIRE(c.x.size() == c.y.size(),
                  path << ": curve '" << c.name << "' has " << c.x.size() << " x and " << c.y.size() << " y");
    for (std::size_t i = 0; i < c.x.size(); ++i)
      if (c.x[i] > 0 && c.y[i] > 0 && std::isfinite(c.x[i]) && std::isfinite(c.y[i])) {
        const double a = std::log10(c.x[i]), b = std::log10(c.y[i]);
        lx0 = std::min(lx0, a), lx1 = std::max(lx1, a), ly0 = std::min(ly0, b), ly1 = std::max(ly1, b);
      }
  }
  ABLMG_REQUIRE(lx0 <= lx1, path << ": no positive data points to plot");
  lx0 = std::floor(lx0), lx1 = std::max(std::ceil(lx1), lx0 + 1), ly0 = std::floor(ly0),
  ly1 = std::max(std::ceil(ly1), ly0 + 1);
  const int W = o.width, H = int(o.width * 0.75), L = 80, R = 30, T = 40, B = 60;
  Canvas c(W, H);
  cairo_t* cr = c.cr.get();
  const auto X = [&](double lx) { return L + (lx - lx0) / (lx1 - lx0) * (W - L - R); };
  const auto Y = [&](double ly) { return H - B - (ly - ly0) / (ly1 - ly0) * (H - T - B); };
  // Grid and decade labels.
  cairo_set_line_width(cr, 0.5);
  for (double d = lx0; d <= lx1 + 1e-9; d += 1) {
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_move_to(cr, X(d), Y(ly0)), cairo_line_to(cr, X(d), Y(ly1)), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, X(d) - 14, H - B + 20, "1e" + fmt(d));
  }
  for (double d = ly0; d <= ly1 + 1e-9; d += 1) {
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_move_to(cr, X(lx0), Y(d)), cairo_line_to(cr, X(lx1), Y(d)), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, 10, Y(d) + 4, "1e" + fmt(d));
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, X(lx0), Y(ly1), X(lx1) - X(lx0), Y(ly0) - Y(ly1));
  cairo_stroke(cr);
  text(cr, W / 2.0 - 20, H - 15, xLabel, 15);
  text(cr, 10, T - 12, yLabel, 15);
  text(cr, W / 2.0 - 6.0 * title.size() / 2, 22, title, 16);
  static const double palette[][3] = {{0.12, 0.47, 0.71}, {0.84, 0.15, 0.16}, {0.17, 0.63, 0.17},
                                      {0.58, 0.40, 0.74}, {1.0, 0.5, 0.05},   {0.55, 0.34, 0.29}};
  cairo_save(cr);
  cairo_rectangle(cr, X(lx0), Y(ly1), X(lx1) - X(lx0), Y(ly0) - Y(ly1));
  cairo_clip(cr);
  // Reference slopes through the first point of the first curve.
  if (!curves.empty() && !curves[0].x.empty() && curves[0].x[0] > 0 && curves[0].y[0] > 0) {
    const double ax = std::log10(curves[0].x[0]), ay = std::log10(curves[0].y[0]);
    const double dash[] = {6, 4};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_set_line_width(cr, 1);
    for (double s : referenceSlopes) {
      cairo_move_to(cr, X(lx0), Y(ay + s * (lx0 - ax)));
      cairo_line_to(cr, X(lx1), Y(ay + s * (lx1 - ax)));
      cairo_stroke(cr);
    }
    cairo_set_dash(cr, nullptr, 0, 0);
  }
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const auto* col = palette[k % 6];
    cairo_set_source_rgb(cr, col[0], col[1], col[2]);
    cairo_set_line_width(cr, 2);
    bool started = false;
    for (std::size_t i = 0; i < curves[k].x.size(); ++i) {
      if (!(curves[k].x[i] > 0 && curves[k].y[i] > 0)) continue;
      const double px = X(std::log10(curves[k].x[i])), py = Y(std::log10(curves[k].y[i]));
      if (!started)
        cairo_move_to(cr, px, py), started = true;
      else
        cairo_line_to(cr, px, py);
    }
    cairo_stroke(cr);
    for (std::size_t i = 0; i < curves[k].x.size(); ++i) {
      if (!(curves[k].x[i] > 0 && curves[k].y[i] > 0)) continue;
      cairo_arc(cr, X(std::log10(curves[k].x[i])), Y(std::log10(curves[k].y[i])), 3.5, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    }
  }
  cairo_restore(cr);
  // Legend.
  double ly = T + 20;
  for (std::size_t k = 0; k < curves.size(); ++k, ly += 20) {
    const auto* col = palette[k % 6];
    cairo_set_source_rgb(cr, col[0], col[1], col[2]);
    cairo_rectangle(cr, W - R - 200, ly - 9, 18, 10);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, W - R - 175, ly, curves[k].name);
  }
  for (double s : referenceSlopes) {
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    text(cr, W - R - 175, ly, "- - slope " + fmt(s));
    ly += 20;
  }
  c.save(path);
}

void tilePictures(const std::string& path, const std::vector<std::string>& pngPaths, int columns,
                  const std::vector<std::string>& captions, const PictureOptions& o) {
  ABLMG_REQUIRE(columns >= 1, path << ": columns = " << columns << " must be at least 1");
  ABLMG_REQUIRE(captions.empty() || captions.size() == pngPaths.size(),
                path << ": " << captions.size() << " captions for " << pngPaths.size() << " pictures");
  std::vector<Surface> tiles;
  for (const auto& p : pngPaths) {
    tiles.emplace_back(cairo_image_surface_create_from_png(p.c_str()), cairo_surface_destroy);
    ABLMG_REQUIRE(cairo_surface_status(tiles.back().get()) == CAIRO_STATUS_SUCCESS, p << ": cannot read as PNG");
  }
  const double cellW = double(o.width) / columns;
  const int band = captions.empty() ? 0 : 26;
  const auto scaleOf = [&](std::size_t i) {
    return std::min(1.0, cellW / cairo_image_surface_get_width(tiles[i].get()));
  };
  std::vector<double> rowHeight;  // tallest scaled picture of each row, caption band included
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    if (i % columns == 0) rowHeight.push_back(0);
    rowHeight.back() = std::max(rowHeight.back(), band + scaleOf(i) * cairo_image_surface_get_height(tiles[i].get()));
  }
  double total = 0;
  for (double h : rowHeight) total += h;
  Canvas c(o.width, std::clamp(int(std::ceil(total)), 1, 40000));
  cairo_t* cr = c.cr.get();
  double y = 0;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const std::size_t row = i / columns;
    const double x = double(i % columns) * cellW, s = scaleOf(i);
    if (band > 0) {
      cairo_set_source_rgb(cr, 0, 0, 0);
      text(cr, x + 12, y + 19, captions[i], 15);
    }
    cairo_save(cr);
    cairo_translate(cr, x, y + band);
    cairo_scale(cr, s, s);
    cairo_set_source_surface(cr, tiles[i].get(), 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
    cairo_paint(cr);
    cairo_restore(cr);
    if (i + 1 == tiles.size() || (i + 1) % columns == 0) y += rowHeight[row];
  }
  c.save(path);
}

}  // namespace ablmg::io
