#include "ablmg/io/time_plot.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace ablmg::io {
namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size = 13) {
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

bool usable(double t, double y) { return std::isfinite(t) && std::isfinite(y) && y > 0; }

}  // namespace

void drawTimePlot(const std::string& path, const std::vector<TimeCurve>& curves, const std::string& tLabel,
                  const std::string& yLabel, const std::string& title, const PictureOptions& o) {
  double t0 = 1e300, t1 = -1e300, ly0 = 1e300, ly1 = -1e300;
  for (const auto& c : curves) {
    ABLMG_REQUIRE(c.t.size() == c.y.size(),
                  path << ": curve '" << c.name << "' has " << c.t.size() << " times and " << c.y.size() << " values");
    for (std::size_t i = 0; i < c.t.size(); ++i)
      if (usable(c.t[i], c.y[i])) {
        t0 = std::min(t0, c.t[i]), t1 = std::max(t1, c.t[i]);
        ly0 = std::min(ly0, std::log10(c.y[i])), ly1 = std::max(ly1, std::log10(c.y[i]));
      }
  }
  ABLMG_REQUIRE(t0 <= t1, path << ": no positive data points to plot");
  if (t1 <= t0) t1 = t0 + 1;
  ly0 = std::floor(ly0), ly1 = std::max(std::ceil(ly1), ly0 + 1);
  const int W = o.width, H = int(o.width * 0.6), L = 80, R = 30, T = 40, B = 60;
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, W, H), cairo_surface_destroy);
  ABLMG_REQUIRE(cairo_surface_status(surface.get()) == CAIRO_STATUS_SUCCESS, path << ": cannot create the image");
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> ctx(cairo_create(surface.get()), cairo_destroy);
  cairo_t* cr = ctx.get();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const auto X = [&](double t) { return L + (t - t0) / (t1 - t0) * (W - L - R); };
  const auto Y = [&](double ly) { return H - B - (ly - ly0) / (ly1 - ly0) * (H - T - B); };
  cairo_set_line_width(cr, 0.5);
  for (int k = 0; k <= 10; ++k) {
    const double t = t0 + (t1 - t0) * k / 10;
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_move_to(cr, X(t), Y(ly0)), cairo_line_to(cr, X(t), Y(ly1)), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, X(t) - 12, H - B + 20, fmt(t));
  }
  for (double d = ly0; d <= ly1 + 1e-9; d += 1) {
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_move_to(cr, X(t0), Y(d)), cairo_line_to(cr, X(t1), Y(d)), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, 10, Y(d) + 4, "1e" + fmt(d));
  }
  cairo_rectangle(cr, X(t0), Y(ly1), X(t1) - X(t0), Y(ly0) - Y(ly1));
  cairo_stroke(cr);
  text(cr, W / 2.0 - 10, H - 15, tLabel, 15);
  text(cr, 10, T - 12, yLabel, 15);
  text(cr, W / 2.0 - 6.0 * double(title.size()) / 2, 22, title, 16);
  static const double palette[][3] = {{0.12, 0.47, 0.71}, {0.84, 0.15, 0.16}, {0.17, 0.63, 0.17},
                                      {0.58, 0.40, 0.74}, {1.0, 0.5, 0.05},   {0.55, 0.34, 0.29}};
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const auto* col = palette[k % 6];
    cairo_set_source_rgb(cr, col[0], col[1], col[2]);
    cairo_set_line_width(cr, 1.8);
    bool started = false;
    for (std::size_t i = 0; i < curves[k].t.size(); ++i) {
      if (!usable(curves[k].t[i], curves[k].y[i])) continue;
      const double px = X(curves[k].t[i]), py = Y(std::log10(curves[k].y[i]));
      if (!started)
        cairo_move_to(cr, px, py), started = true;
      else
        cairo_line_to(cr, px, py);
    }
    cairo_stroke(cr);
    const double ly = T + 20 + 20.0 * double(k);
    cairo_rectangle(cr, W - R - 260, ly - 9, 18, 10);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, W - R - 235, ly, curves[k].name);
  }
  cairo_surface_flush(surface.get());
  writePathAtomically(path, [&](const std::string& tmp) {
    if (cairo_surface_write_to_png(surface.get(), tmp.c_str()) != CAIRO_STATUS_SUCCESS)
      ABLMG_FAIL(path << ": cannot write PNG");
  });
}

}  // namespace ablmg::io
