#include "ablmg/io/stl.hpp"

#include <Eigen/Geometry>  // cross()

#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"

#include <iomanip>

namespace ablmg::io {

void writeStl(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
              const std::vector<std::array<int, 3>>& triangles, const std::string& solidName) {
  const long n = long(vertices.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      ABLMG_REQUIRE(triangles[t][k] >= 0 && triangles[t][k] < n, path << ": triangle " << t << " has vertex id "
                                                                      << triangles[t][k] << " out of range [0, " << n
                                                                      << ")");
  writeFileAtomically(path, [&](std::ostream& os) {
    os << std::setprecision(17) << "solid " << solidName << "\n";
    for (const auto& t : triangles) {
      const Eigen::Vector3d n = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).normalized();
      os << "  facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n    outer loop\n";
      for (int k = 0; k < 3; ++k) {
        const auto& v = vertices[t[k]];
        os << "      vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
      }
      os << "    endloop\n  endfacet\n";
    }
    os << "endsolid " << solidName << "\n";
  });
}

}  // namespace ablmg::io
