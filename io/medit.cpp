#include "io/medit.hpp"

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/text_scanner.hpp"

#include <charconv>
#include <string_view>
#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <iomanip>
#include <map>
#include <ostream>

namespace ablmg::io {
namespace {

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = char(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

/// A count read from the file, bounded by what the file can possibly hold (each entry takes
/// at least 2 bytes per number), so a garbage count cannot trigger a huge allocation.
long readCount(TextScanner& s, const char* what, int numbersPerEntry) {
  const long n = s.nextInt(what, 0, INT_MAX - 1);
  ABLMG_REQUIRE(n <= long(s.size() / (2 * std::size_t(numbersPerEntry)) + 1),
                s.where() << what << " " << n << " is more than the file can hold (truncated?)");
  return n;
}

/// Skips the numbers and quoted strings of an unknown section (Corners, Ridges, FreeFem's
/// Identifier "..." and Geometry "..."), up to the next keyword.
void skipSection(TextScanner& s) {
  while (!s.atEnd()) {
    if (s.skipQuotedString()) continue;
    if (!TextScanner::isNumber(s.peek())) break;
    s.next("number");
  }
}

void readHeader(TextScanner& s, int& dim, bool dimRequired) {
  ABLMG_REQUIRE(!s.atEnd(), s.name() << ":1: empty file, expected MeshVersionFormatted");
  const auto kw = lower(s.next("MeshVersionFormatted"));
  ABLMG_REQUIRE(kw == "meshversionformatted",
                s.where() << "expected MeshVersionFormatted, got '" << (TextScanner::isNumber(kw) ? kw : kw.substr(0, 30))
                          << "' (not a medit ASCII file?)");
  s.nextInt("format version", 0, 3);
  dim = 2;
  if (!s.atEnd() && lower(s.peek()) == "dimension") {
    s.next("Dimension");
    dim = int(s.nextInt("dimension", 2, 3));
  } else {
    ABLMG_REQUIRE(!dimRequired, s.name() << ":" << s.line() << ": expected Dimension after MeshVersionFormatted");
  }
}

/// The sections of a .mesh file, in the file's order and orientation. With `zs` null, a
/// Dimension 3 file must be planar (z = 0); otherwise every z is stored there (0 in Dimension 2).
Mesh2 parseSections(const std::string& text, const std::string& name, std::vector<double>* zs, int& dim) {
  TextScanner s(text, name);
  readHeader(s, dim, true);
  Mesh2 mesh;
  std::vector<int> vertexLine;  // line of each vertex (for z ≠ 0 messages)
  bool haveVertices = false;
  while (!s.atEnd()) {
    const auto kw = lower(s.next("section keyword"));
    if (kw == "end") break;
    if (kw == "vertices") {
      ABLMG_REQUIRE(!haveVertices, s.where() << "second Vertices section");
      haveVertices = true;
      const long n = readCount(s, "vertex count", dim + 1);
      mesh.vertices.reserve(n);
      mesh.vertexRefs.reserve(n);
      for (long i = 0; i < n; ++i) {
        const double x = s.nextDouble("vertex x coordinate");
        const double y = s.nextDouble("vertex y coordinate");
        const double z = dim == 3 ? s.nextDouble("vertex z coordinate") : 0.0;
        ABLMG_REQUIRE(zs || z == 0.0, s.where() << "vertex " << i + 1 << " has z = " << z
                                                << ": only planar meshes (Dimension 3 with all z = 0) are read");
        if (zs) zs->push_back(z);
        mesh.vertices.emplace_back(x, y);
        mesh.vertexRefs.push_back(int(s.nextInt("vertex reference", INT_MIN, INT_MAX)));
      }
    } else if (kw == "edges" || kw == "triangles") {
      ABLMG_REQUIRE(haveVertices, s.where() << "section " << kw << " before Vertices");
      const bool tri = kw == "triangles";
      const int nv = tri ? 3 : 2;
      const long n = readCount(s, tri ? "triangle count" : "edge count", nv + 1);
      const long maxId = mesh.numVertices();
      for (long i = 0; i < n; ++i) {
        std::array<int, 3> v{0, 0, 0};
        for (int k = 0; k < nv; ++k) {
          const long id = s.nextInt("vertex index", LONG_MIN, LONG_MAX);
          ABLMG_REQUIRE(id >= 1 && id <= maxId, s.where() << (tri ? "triangle " : "edge ") << i + 1 << ": vertex index " << id
                                                          << " out of range [1, " << maxId << "]");
          v[k] = int(id - 1);
        }
        const int ref = int(s.nextInt("reference", INT_MIN, INT_MAX));
        if (tri) {
          ABLMG_REQUIRE(v[0] != v[1] && v[1] != v[2] && v[0] != v[2],
                        s.where() << "triangle " << i + 1 << " repeats a vertex (" << v[0] + 1 << ", " << v[1] + 1 << ", " << v[2] + 1 << ")");
          mesh.triangles.push_back(v);
          mesh.triangleRefs.push_back(ref);
        } else {
          ABLMG_REQUIRE(v[0] != v[1], s.where() << "edge " << i + 1 << " joins vertex " << v[0] + 1 << " to itself");
          mesh.boundaryEdges.push_back({v[0], v[1], ref});
        }
      }
    } else if (kw == "dimension" || kw == "meshversionformatted") {
      ABLMG_REQUIRE(false, s.where() << "repeated header keyword '" << kw << "'");
    } else {
      ABLMG_REQUIRE(!TextScanner::isNumber(kw), s.where() << "expected a section keyword, got the number '" << kw.substr(0, 30) << "' (count mismatch?)");
      ABLMG_REQUIRE(std::all_of(kw.begin(), kw.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }),
                    s.where() << "expected a section keyword, got garbage");
      skipSection(s);  // Corners, RequiredVertices, Ridges, Normals, Quadrilaterals, ...
    }
  }
  ABLMG_REQUIRE(haveVertices, name << ": no Vertices section");
  return mesh;
}

} // namespace

Mesh2 parseMesh(const std::string& text, const std::string& name) {
  int dim = 2;
  Mesh2 mesh = parseSections(text, name, nullptr, dim);
  // Orientation: triangles counter-clockwise (the format does not fix one).
  for (auto& t : mesh.triangles) {
    const Vec2 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    if (cross(b - a, c - a) < 0) std::swap(t[1], t[2]);
  }
  // Boundary edges a→b with the domain on the left: the triangle using the edge runs a→b.
  if (mesh.boundaryEdges.empty()) return mesh;
  std::vector<std::pair<int, int>> directed;
  directed.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) directed.push_back({t[k], t[(k + 1) % 3]});
  std::sort(directed.begin(), directed.end());
  const auto has = [&](int a, int b) { return std::binary_search(directed.begin(), directed.end(), std::pair<int, int>{a, b}); };
  for (auto& e : mesh.boundaryEdges)
    if (!has(e.a, e.b) && has(e.b, e.a)) std::swap(e.a, e.b);
  return mesh;
}

Mesh2 readMesh(const std::string& path) { return parseMesh(readTextFile(path), path); }

SurfaceMeshFile parseSurfaceMesh(const std::string& text, const std::string& name) {
  SurfaceMeshFile f;
  std::vector<double> zs;
  const Mesh2 mesh = parseSections(text, name, &zs, f.dimension);
  for (int i = 0; i < mesh.numVertices(); ++i) f.vertices.emplace_back(mesh.vertices[i].x(), mesh.vertices[i].y(), zs[i]);
  f.triangles = mesh.triangles;
  f.triangleRefs = mesh.triangleRefs;
  return f;
}

SurfaceMeshFile readSurfaceMesh(const std::string& path) { return parseSurfaceMesh(readTextFile(path), path); }

std::vector<Metric2> parseSol(const std::string& text, const std::string& name, int expectedVertices) {
  TextScanner s(text, name);
  int dim = 2;
  readHeader(s, dim, false);
  while (!s.atEnd()) {
    const auto kw = lower(s.next("SolAtVertices"));
    if (kw == "end") break;
    if (kw != "solatvertices") {
      ABLMG_REQUIRE(!TextScanner::isNumber(kw) &&
                        std::all_of(kw.begin(), kw.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }),
                    s.where() << "expected a section keyword (SolAtVertices)");
      skipSection(s);
      continue;
    }
    const long n = readCount(s, "solution count", 1);
    const int countLine = s.line();
    if (expectedVertices >= 0)
      ABLMG_REQUIRE(n == expectedVertices, name << ":" << countLine << ": " << n << " solution values but the mesh has "
                                                << expectedVertices << " vertices");
    const long nsol = s.nextInt("number of solution fields", 1, 64);
    std::vector<int> types(nsol);
    int perVertex = 0;
    const int tensorSize = dim == 2 ? 3 : 6;
    for (auto& t : types) {
      t = int(s.nextInt("solution type (1 scalar, 2 vector, 3 tensor)", 1, 3));
      perVertex += t == 1 ? 1 : t == 2 ? dim : tensorSize;
    }
    ABLMG_REQUIRE(types[0] == 1 || types[0] == 3,
                  s.where() << "first solution field has type 2 (vector); a metric needs type 1 (size) or 3 (tensor)");
    ABLMG_REQUIRE(n <= long(s.size() / (2 * std::size_t(perVertex)) + 1),
                  name << ":" << countLine << ": solution count " << n << " is more than the file can hold (truncated?)");
    std::vector<Metric2> out;
    out.reserve(n);
    std::vector<double> v(perVertex);
    for (long i = 0; i < n; ++i) {
      int firstLine = 0;
      for (int k = 0; k < perVertex; ++k) {
        v[k] = s.nextDouble(types[0] == 1 ? "size value" : "tensor entry");
        if (k == 0) firstLine = s.line();
      }
      const std::string at = name + ":" + std::to_string(firstLine) + ": ";
      if (types[0] == 1) {
        ABLMG_REQUIRE(v[0] > 0, at << "size of vertex " << i + 1 << " is " << v[0] << ", must be > 0");
        out.push_back(Metric2::isotropic(v[0]));
      } else {
        double m11 = v[0], m12 = v[1], m22 = v[2];
        if (dim == 3) {
          ABLMG_REQUIRE(v[2] == 0 && v[4] == 0, at << "tensor of vertex " << i + 1 << " has m13 = " << v[2] << ", m23 = " << v[4]
                                                   << ": only planar (m13 = m23 = 0) metrics are read");
          m22 = v[3];
        }
        const bool spd = m11 > 0 && m22 > 0 && m11 * m22 - m12 * m12 > 0;
        ABLMG_REQUIRE(spd, at << "tensor of vertex " << i + 1 << " (" << m11 << ", " << m12 << ", " << m22 << ") is not positive definite");
        out.push_back(Metric2::fromTensor(m11, m12, m22, at + "tensor of vertex " + std::to_string(i + 1)));
      }
    }
    return out;
  }
  ABLMG_REQUIRE(false, name << ": no SolAtVertices section");
  return {};
}

std::vector<Metric2> readSol(const std::string& path, int expectedVertices) {
  return parseSol(readTextFile(path), path, expectedVertices);
}

namespace {

/// Text output through one buffer: numbers formatted with std::to_chars (doubles in their
/// shortest form that reads back to the same bits; ints in decimal), flushed to the stream
/// every megabyte. ~10× faster than iostream formatting with setprecision(17).
class LineBuffer {
public:
  explicit LineBuffer(std::ostream& os) : os_(os) { buf_.reserve(kFlush + 256); }
  ~LineBuffer() { flush(); }
  LineBuffer& text(std::string_view s) {
    buf_.append(s);
    return *this;
  }
  template <class T> LineBuffer& num(T v) {
    char tmp[32];
    const auto [end, ec] = std::to_chars(tmp, tmp + sizeof tmp, v);
    buf_.append(tmp, end);
    return *this;
  }
  LineBuffer& sp() { return text(" "); }
  LineBuffer& nl() {
    buf_.push_back('\n');
    if (buf_.size() >= kFlush) flush();
    return *this;
  }
  void flush() {
    os_.write(buf_.data(), std::streamsize(buf_.size()));
    buf_.clear();
  }

private:
  static constexpr std::size_t kFlush = 1 << 20;
  std::ostream& os_;
  std::string buf_;
};

void header(LineBuffer& out, int dim) { out.text("MeshVersionFormatted 2\n\nDimension ").num(dim).text("\n\n"); }
int refOr0(const std::vector<int>& refs, std::size_t i) { return i < refs.size() ? refs[i] : 0; }
} // namespace

void writeMesh(const std::string& path, const Mesh2& mesh) {
  writeFileAtomically(path, [&](std::ostream& os) {
    LineBuffer out(os);
    header(out, 2);
    out.text("Vertices\n").num(mesh.vertices.size()).nl();
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
      out.num(mesh.vertices[i].x()).sp().num(mesh.vertices[i].y()).sp().num(refOr0(mesh.vertexRefs, i)).nl();
    out.text("\nEdges\n").num(mesh.boundaryEdges.size()).nl();
    for (const auto& e : mesh.boundaryEdges) out.num(e.a + 1).sp().num(e.b + 1).sp().num(e.ref).nl();
    out.text("\nTriangles\n").num(mesh.triangles.size()).nl();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tr = mesh.triangles[t];
      out.num(tr[0] + 1).sp().num(tr[1] + 1).sp().num(tr[2] + 1).sp().num(refOr0(mesh.triangleRefs, t)).nl();
    }
    out.text("\nEnd\n");
  });
}

void writeSurfaceMesh(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
                      const std::vector<std::array<int, 3>>& triangles, const std::vector<int>& triangleRefs) {
  writeFileAtomically(path, [&](std::ostream& os) {
    LineBuffer out(os);
    header(out, 3);
    out.text("Vertices\n").num(vertices.size()).nl();
    for (const auto& v : vertices) out.num(v.x()).sp().num(v.y()).sp().num(v.z()).text(" 0").nl();
    out.text("\nTriangles\n").num(triangles.size()).nl();
    for (std::size_t t = 0; t < triangles.size(); ++t)
      out.num(triangles[t][0] + 1).sp().num(triangles[t][1] + 1).sp().num(triangles[t][2] + 1).sp().num(refOr0(triangleRefs, t)).nl();
    out.text("\nEnd\n");
  });
}

void writeSol(const std::string& path, std::span<const Metric2> metrics) {
  writeFileAtomically(path, [&](std::ostream& os) {
    LineBuffer out(os);
    header(out, 2);
    out.text("SolAtVertices\n").num(metrics.size()).text("\n1 3\n\n");
    for (const auto& m : metrics) out.num(m.m11()).sp().num(m.m12()).sp().num(m.m22()).nl();
    out.text("\nEnd\n");
  });
}

void writeScalarSol(const std::string& path, std::span<const double> values) {
  writeFileAtomically(path, [&](std::ostream& os) {
    LineBuffer out(os);
    header(out, 2);
    out.text("SolAtVertices\n").num(values.size()).text("\n1 1\n\n");
    for (double v : values) out.num(v).nl();
    out.text("\nEnd\n");
  });
}

} // namespace ablmg::io
