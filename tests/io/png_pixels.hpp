// Test helper: a PNG read back through cairo, to check what a picture shows where.
#pragma once

#include <cairo.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace ablmg::test {

/// A PNG file loaded as a cairo image surface (ok() is false if it could not be read).
struct Png {
  cairo_surface_t* s;
  explicit Png(const std::string& p) : s(cairo_image_surface_create_from_png(p.c_str())) {}
  Png(const Png&) = delete;
  Png& operator=(const Png&) = delete;
  ~Png() { cairo_surface_destroy(s); }
  bool ok() const { return cairo_surface_status(s) == CAIRO_STATUS_SUCCESS; }
  int width() const { return cairo_image_surface_get_width(s); }
  int height() const { return cairo_image_surface_get_height(s); }
  /// (r, g, b) of pixel (x, y), 0..255.
  std::array<int, 3> rgb(int x, int y) const {
    cairo_surface_flush(s);
    const auto* row = cairo_image_surface_get_data(s) + y * cairo_image_surface_get_stride(s);
    const std::uint32_t p = reinterpret_cast<const std::uint32_t*>(row)[x];
    return {int((p >> 16) & 255), int((p >> 8) & 255), int(p & 255)};
  }
};

/// A path in the temporary directory, unique to this process: <tmp>/<prefix><pid><name>.
inline std::string tempPath(const std::string& prefix, const std::string& name) {
  return (std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()) + name)).string();
}

}  // namespace ablmg::test
