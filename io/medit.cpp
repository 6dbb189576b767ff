#include "ablmg/io/medit.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/io/text_scanner.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <future>
#include <ostream>
#include <string_view>

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
  ABLMG_REQUIRE(kw == "meshversionformatted", s.where() << "expected MeshVersionFormatted, got '"
                                                        << (TextScanner::isNumber(kw) ? kw : kw.substr(0, 30))
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
Mesh2 parseSections(std::string text, const std::string& name, std::vector<double>* zs, int& dim) {
  TextScanner s(std::move(text), name);
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
      if (tri) {
        mesh.triangles.reserve(mesh.triangles.size() + std::size_t(n));
        mesh.triangleRefs.reserve(mesh.triangleRefs.size() + std::size_t(n));
      } else {
        mesh.boundaryEdges.reserve(mesh.boundaryEdges.size() + std::size_t(n));
      }
      for (long i = 0; i < n; ++i) {
        std::array<int, 3> v{0, 0, 0};
        for (int k = 0; k < nv; ++k) {
          const long id = s.nextInt("vertex index", LONG_MIN, LONG_MAX);
          ABLMG_REQUIRE(id >= 1 && id <= maxId, s.where() << (tri ? "triangle " : "edge ") << i + 1 << ": vertex index "
                                                          << id << " out of range [1, " << maxId << "]");
          v[k] = int(id - 1);
        }
        const int ref = int(s.nextInt("reference", INT_MIN, INT_MAX));
        if (tri) {
          ABLMG_REQUIRE(v[0] != v[1] && v[1] != v[2] && v[0] != v[2],
                        s.where() << "triangle " << i + 1 << " repeats a vertex (" << v[0] + 1 << ", " << v[1] + 1
                                  << ", " << v[2] + 1 << ")");
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
      ABLMG_REQUIRE(!TextScanner::isNumber(kw), s.where() << "expected a section keyword, got the number '"
                                                          << kw.substr(0, 30) << "' (count mismatch?)");
      ABLMG_REQUIRE(std::all_of(kw.begin(), kw.end(),
                                [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }),
                    s.where() << "expected a section keyword, got garbage");
      skipSection(s);  // Corners, RequiredVertices, Ridges, Normals, Quadrilaterals, ...
    }
  }
  ABLMG_REQUIRE(haveVertices, name << ": no Vertices section");
  return mesh;
}

/// parseMesh on a string it owns (readMesh moves the file's text in: no copy).
Mesh2 meshFromText(std::string text, const std::string& name) {
  int dim = 2;
  Mesh2 mesh = parseSections(std::move(text), name, nullptr, dim);
  // Orientation: triangles counter-clockwise (the format does not fix one).
  for (auto& t : mesh.triangles) {
    const Vec2 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    if (cross(b - a, c - a) < 0) std::swap(t[1], t[2]);
  }
  // Boundary edges a→b with the domain on the left: the triangle using the edge runs a→b.
  // Directed triangle edges grouped by their first vertex (counting sort, O(n)): the rows are
  // a vertex's few outgoing edges, scanned linearly.
  if (mesh.boundaryEdges.empty()) return mesh;
  const std::size_t nv = mesh.vertices.size();
  std::vector<int> rowStart(nv + 1, 0), heads(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++rowStart[std::size_t(t[k]) + 1];
  for (std::size_t v = 0; v < nv; ++v) rowStart[v + 1] += rowStart[v];
  {
    std::vector<int> fill(rowStart.begin(), rowStart.end() - 1);
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) heads[std::size_t(fill[std::size_t(t[k])]++)] = t[(k + 1) % 3];
  }
  const auto has = [&](int a, int b) {
    return std::find(heads.begin() + rowStart[std::size_t(a)], heads.begin() + rowStart[std::size_t(a) + 1], b) !=
           heads.begin() + rowStart[std::size_t(a) + 1];
  };
  for (auto& e : mesh.boundaryEdges)
    if (!has(e.a, e.b) && has(e.b, e.a)) std::swap(e.a, e.b);
  return mesh;
}

/// parseSol on a string it owns (readSol moves the file's text in).
std::vector<Metric2> solFromText(std::string text, const std::string& name, int expectedVertices) {
  TextScanner s(std::move(text), name);
  int dim = 2;
  readHeader(s, dim, false);
  while (!s.atEnd()) {
    const auto kw = lower(s.next("SolAtVertices"));
    if (kw == "end") break;
    if (kw != "solatvertices") {
      ABLMG_REQUIRE(!TextScanner::isNumber(kw) &&
                        std::all_of(kw.begin(), kw.end(),
                                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }),
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
    ABLMG_REQUIRE(
        n <= long(s.size() / (2 * std::size_t(perVertex)) + 1),
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
      // "<file>:<line>: " is built only for a message, not for every vertex.
      const auto at = [&] { return name + ":" + std::to_string(firstLine) + ": "; };
      if (types[0] == 1) {
        ABLMG_REQUIRE(v[0] > 0, at() << "size of vertex " << i + 1 << " is " << v[0] << ", must be > 0");
        // A size so small or large that 1/h² (or h²) over- or underflows (1e-200, 1e200) has
        // no SPD tensor: the error names the line, not only Metric2's "metric: sizes ...".
        try {
          out.push_back(Metric2::isotropic(v[0]));
        } catch (const InputError&) {
          ABLMG_REQUIRE(
              false, at() << "size of vertex " << i + 1 << " is " << v[0] << ": its tensor 1/h² is not representable");
        }
      } else {
        double m11 = v[0], m12 = v[1], m22 = v[2];
        if (dim == 3) {
          ABLMG_REQUIRE(v[2] == 0 && v[4] == 0, at() << "tensor of vertex " << i + 1 << " has m13 = " << v[2]
                                                     << ", m23 = " << v[4]
                                                     << ": only planar (m13 = m23 = 0) metrics are read");
          m22 = v[3];
        }
        const bool spd = m11 > 0 && m22 > 0 && m11 * m22 - m12 * m12 > 0;
        ABLMG_REQUIRE(spd, at() << "tensor of vertex " << i + 1 << " (" << m11 << ", " << m12 << ", " << m22
                                << ") is not positive definite");
        // Metric2::fromTensor's checks without its message argument; on failure it is called
        // with the message, so the error is the same.
        const Metric2 m = Metric2::raw(m11, m12, m22);
        out.push_back(
            m.isSpd() ? m : Metric2::fromTensor(m11, m12, m22, at() + "tensor of vertex " + std::to_string(i + 1)));
      }
    }
    return out;
  }
  ABLMG_REQUIRE(false, name << ": no SolAtVertices section");
  return {};
}

}  // namespace

Mesh2 parseMesh(const std::string& text, const std::string& name) { return meshFromText(text, name); }

Mesh2 readMesh(const std::string& path) { return meshFromText(readTextFile(path), path); }

SurfaceMeshFile parseSurfaceMesh(const std::string& text, const std::string& name) {
  SurfaceMeshFile f;
  std::vector<double> zs;
  const Mesh2 mesh = parseSections(text, name, &zs, f.dimension);
  for (int i = 0; i < mesh.numVertices(); ++i)
    f.vertices.emplace_back(mesh.vertices[i].x(), mesh.vertices[i].y(), zs[i]);
  f.triangles = mesh.triangles;
  f.triangleRefs = mesh.triangleRefs;
  return f;
}

SurfaceMeshFile readSurfaceMesh(const std::string& path) { return parseSurfaceMesh(readTextFile(path), path); }

std::vector<Metric2> parseSol(const std::string& text, const std::string& name, int expectedVertices) {
  return solFromText(text, name, expectedVertices);
}

std::vector<Metric2> readSol(const std::string& path, int expectedVertices) {
  return solFromText(readTextFile(path), path, expectedVertices);
}

namespace {

/// Text built in memory: numbers by std::to_chars (a double in the shortest form that reads
/// back to the same bits, e.g. 0.1 and not 0.10000000000000001; ints in decimal), written into
/// a buffer that grows in large steps. The .mesh + .sol of a 2.3·10^5-triangle remesh took
/// 0.3 s through an ostream with setprecision(17), 0.05 s this way.
class TextBuilder {
 public:
  explicit TextBuilder(std::size_t expectedSize) { buf_.resize(expectedSize + 64); }
  TextBuilder& text(std::string_view s) {
    room(s.size());
    std::copy(s.begin(), s.end(), buf_.data() + n_);
    n_ += s.size();
    return *this;
  }
  template <class T>
  TextBuilder& num(T v) {
    room(kNumberRoom);
    n_ = std::size_t(std::to_chars(buf_.data() + n_, buf_.data() + n_ + kNumberRoom, v).ptr - buf_.data());
    return *this;
  }
  TextBuilder& ch(char c) {
    room(1);
    buf_[n_++] = c;
    return *this;
  }
  std::string take() {
    buf_.resize(n_);
    return std::move(buf_);
  }

 private:
  static constexpr std::size_t kNumberRoom = 32;  ///< the longest double is 24 characters
  void room(std::size_t k) {
    if (buf_.size() - n_ < k) buf_.resize(std::max(2 * buf_.size(), n_ + k + 4096));
  }
  std::string buf_;
  std::size_t n_ = 0;
};

void header(TextBuilder& out, int dim) { out.text("MeshVersionFormatted 2\n\nDimension ").num(dim).text("\n\n"); }
int refOr0(const std::vector<int>& refs, std::size_t i) { return i < refs.size() ? refs[i] : 0; }

std::string formatMesh(const Mesh2& mesh) {
  TextBuilder out(48 * mesh.vertices.size() + 32 * mesh.triangles.size() + 24 * mesh.boundaryEdges.size() + 128);
  header(out, 2);
  out.text("Vertices\n").num(mesh.vertices.size()).ch('\n');
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    out.num(mesh.vertices[i].x()).ch(' ').num(mesh.vertices[i].y()).ch(' ').num(refOr0(mesh.vertexRefs, i)).ch('\n');
  out.text("\nEdges\n").num(mesh.boundaryEdges.size()).ch('\n');
  for (const auto& e : mesh.boundaryEdges) out.num(e.a + 1).ch(' ').num(e.b + 1).ch(' ').num(e.ref).ch('\n');
  out.text("\nTriangles\n").num(mesh.triangles.size()).ch('\n');
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tr = mesh.triangles[t];
    out.num(tr[0] + 1).ch(' ').num(tr[1] + 1).ch(' ').num(tr[2] + 1).ch(' ').num(refOr0(mesh.triangleRefs, t)).ch('\n');
  }
  out.text("\nEnd\n");
  return out.take();
}

std::string formatSol(std::span<const Metric2> metrics) {
  TextBuilder out(66 * metrics.size() + 128);
  header(out, 2);
  out.text("SolAtVertices\n").num(metrics.size()).text("\n1 3\n\n");
  for (const auto& m : metrics) out.num(m.m11()).ch(' ').num(m.m12()).ch(' ').num(m.m22()).ch('\n');
  out.text("\nEnd\n");
  return out.take();
}

void writeText(const std::string& path, const std::string& text) {
  writeFileAtomically(path, [&](std::ostream& os) { os.write(text.data(), std::streamsize(text.size())); });
}

}  // namespace

void writeMesh(const std::string& path, const Mesh2& mesh) { writeText(path, formatMesh(mesh)); }

void writeSurfaceMesh(const std::string& path, const std::vector<Eigen::Vector3d>& vertices,
                      const std::vector<std::array<int, 3>>& triangles, const std::vector<int>& triangleRefs) {
  TextBuilder out(72 * vertices.size() + 32 * triangles.size() + 128);
  header(out, 3);
  out.text("Vertices\n").num(vertices.size()).ch('\n');
  for (const auto& v : vertices) out.num(v.x()).ch(' ').num(v.y()).ch(' ').num(v.z()).text(" 0\n");
  out.text("\nTriangles\n").num(triangles.size()).ch('\n');
  for (std::size_t t = 0; t < triangles.size(); ++t)
    out.num(triangles[t][0] + 1)
        .ch(' ')
        .num(triangles[t][1] + 1)
        .ch(' ')
        .num(triangles[t][2] + 1)
        .ch(' ')
        .num(refOr0(triangleRefs, t))
        .ch('\n');
  out.text("\nEnd\n");
  writeText(path, out.take());
}

void writeSol(const std::string& path, std::span<const Metric2> metrics) { writeText(path, formatSol(metrics)); }

void writeMeshAndSol(const std::string& meshPath, const Mesh2& mesh, const std::string& solPath,
                     std::span<const Metric2> metrics) {
  // The .sol is formatted on a second thread while this one formats the .mesh (formatting is
  // most of the cost); then the files are written one after the other.
  auto sol = std::async(std::launch::async, [metrics] { return formatSol(metrics); });
  std::string meshText;
  try {
    meshText = formatMesh(mesh);
  } catch (...) {
    sol.wait();
    throw;
  }
  const std::string solText = sol.get();
  writeText(meshPath, meshText);
  try {
    writeText(solPath, solText);
  } catch (...) {
    std::remove(meshPath.c_str());
    throw;
  }
}

void writeScalarSol(const std::string& path, std::span<const double> values) {
  TextBuilder out(25 * values.size() + 128);
  header(out, 2);
  out.text("SolAtVertices\n").num(values.size()).text("\n1 1\n\n");
  for (double v : values) out.num(v).ch('\n');
  out.text("\nEnd\n");
  writeText(path, out.take());
}

}  // namespace ablmg::io
