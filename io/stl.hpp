#pragma once
/// ASCII STL output of a 3D triangle mesh (surfaces, paper §5–6). Written atomically
/// (temporary file + rename): a failed run leaves no partial file.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace ablmg::io {

/// Facet normals are computed from the triangle orientation (right-hand rule).
void writeStl(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
              const std::vector<std::array<int, 3>>& triangles, const std::string& solidName = "ablmg");

}  // namespace ablmg::io
