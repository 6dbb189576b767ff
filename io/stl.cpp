#include "io/stl.hpp"

#include "core/error.hpp"

#include <cstdio>
#include <fstream>
#include <iomanip>

namespace ablmg::io {

void writeStl(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
              const std::vector<std::array<int, 3>>& triangles, const std::string& solidName) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream os(tmp);
    ABLMG_REQUIRE(os, path << ": cannot open for writing");
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
    os.flush();
    if (!os) {
      std::remove(tmp.c_str());
      throw Error(path + ": write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(path + ": cannot rename temporary file into place");
  }
}

} // namespace ablmg::io
