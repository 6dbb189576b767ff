#pragma once
/// A shaded PNG of a 3D triangle surface (paper §5–6, Fig. 16(d)) through cairo, written
/// atomically (temporary file + rename).
///
/// Camera: orthographic, looking at the bounding-box centre from the direction given by
/// azimuth φ (about +z, from +x) and elevation ψ (above the xy plane); +z points up on the image.
/// Hidden surfaces: painter's algorithm — triangles are filled back to front by the depth of
/// their centroid. Exact for convex or gently curved surfaces; where large triangles
/// interpenetrate in depth the order can be wrong by a triangle, which at mesh resolution is
/// not visible. Shading: Lambert, c = ambient + (1 − ambient)·|n·ℓ| with the light ℓ from the
/// viewer's upper left; |·| shades both sides alike, so the orientation does not matter.
/// This is a preview, not a renderer; use the .vtu in ParaView for anything more.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace ablmg::io {

struct SurfaceViewOptions {
  int width = 1200;          ///< pixels; the height follows the projected aspect ratio
  int margin = 30;           ///< pixels around the drawing
  double azimuthDeg = -60;   ///< φ, degrees, rotation about +z (0: looking from +x)
  double elevationDeg = 30;  ///< ψ, degrees above the xy plane, in [-90, 90]
  double ambient = 0.25;     ///< share of the colour independent of the light, [0, 1]
  bool edges = true;         ///< draw the mesh edges (thin, dark) over the shading
  double lineWidth = 0.4;    ///< pixels, mesh edges
};

/// Draws the triangles (indices into `vertices`) shaded with one base colour. Throws
/// InputError for an empty mesh, an out-of-range index or non-finite coordinates, and
/// ablmg::Error if the PNG cannot be written (then `path` is untouched).
void drawSurface(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
                 const std::vector<std::array<int, 3>>& triangles, const SurfaceViewOptions& options = {});

}  // namespace ablmg::io
