#pragma once
/// PNG pictures through cairo, written atomically (temporary file + rename).
///
/// The view maps the bounding box of what is drawn to the image with equal x/y scale (y up)
/// and a margin. Colours of scalar values use a blue→red ramp with a colour bar at the right.
#include "ablmg/core/domain.hpp"
#include "ablmg/core/mesh2.hpp"
#include "ablmg/core/metric2.hpp"

#include <span>
#include <string>
#include <vector>

namespace ablmg::io {

struct PictureOptions {
  int width = 1200;        ///< pixels; height follows the aspect ratio of the drawing
  int margin = 30;         ///< pixels around the drawing
  double lineWidth = 0.6;  ///< pixels, mesh edges
};

/// Mesh edges (boundary edges thicker, interface edges thicker and dark red). If `triangleValues` is non-empty (one per triangle),
/// triangles are filled by value with a colour bar labelled `valueName`.
void drawMesh(const std::string& path, const Mesh2& mesh, std::span<const double> triangleValues = {},
              const std::string& valueName = "", const PictureOptions& options = {});

/// Bubbles over the domain boundary: for node i the unit-metric ellipse of metrics[i] scaled
/// by 1/2 (semi-axes h1/2, h2/2, rotated by θ) centred at centres[i]. If `mesh` is non-null its
/// edges are drawn underneath (light grey).
void drawBubbles(const std::string& path, const Domain& domain, std::span<const Vec2> centres,
                 std::span<const Metric2> metrics, const Mesh2* mesh = nullptr, const PictureOptions& options = {});

/// One named curve of a log-log plot; x, y > 0 (non-positive points are skipped).
struct Curve {
  std::string name;
  std::vector<double> x, y;
};

/// Log-log plot (convergence): curves with markers, a legend, and one dashed reference line
/// per entry of `referenceSlopes` (labelled "slope s"), anchored at the first curve's first point.
void drawLogLogPlot(const std::string& path, const std::vector<Curve>& curves,
                    const std::vector<double>& referenceSlopes = {}, const std::string& xLabel = "N",
                    const std::string& yLabel = "error", const std::string& title = "",
                    const PictureOptions& options = {});

/// Several PNGs side by side on one image (e.g. two convergence plots over two meshes): the
/// pictures in `pngPaths` are laid out row by row, `columns` per row, each scaled down to the
/// width of its cell (the output width / columns, never scaled up) and given its caption (when
/// `captions` is non-empty, one per picture) in a band above it. The output width is
/// options.width; the height follows the tallest scaled picture of each row. Throws InputError
/// if a file cannot be read as PNG or the counts do not match.
void tilePictures(const std::string& path, const std::vector<std::string>& pngPaths, int columns,
                  const std::vector<std::string>& captions = {}, const PictureOptions& options = {});

}  // namespace ablmg::io
