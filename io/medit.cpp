#include "ablmg/io/medit.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/io/text_scanner.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <future>
#include <ostream>
#include <string_view>
#include <unordered_map>

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
  // Files other tools write that users pass by mistake: say what they are and how to convert.
  const char* hint = kw.starts_with("$meshformat") ? "a gmsh .msh file: write medit with gmsh -format mesh"
                     : kw.starts_with("<")         ? "an XML file (VTK?): convert with meshio convert IN OUT.mesh"
                                                   : "not a medit ASCII file?";
  ABLMG_REQUIRE(kw == "meshversionformatted", s.where() << "expected MeshVersionFormatted, got '"
                                                        << (TextScanner::isNumber(kw) ? kw : kw.substr(0, 30)) << "' ("
                                                        << hint << ")");
  s.nextInt("format version", 0, 3);
  dim = 2;
  if (!s.atEnd() && lower(s.peek()) == "dimension") {
    s.next("Dimension");
    dim = int(s.nextInt("dimension", 2, 3));
  } else {
    ABLMG_REQUIRE(!dimRequired, s.name() << ":" << s.line() << ": expected Dimension after MeshVersionFormatted");
  }
}

/// The feature sections as the file gives them: vertex indices (0-based) and indices into
/// the file's Edges section (0-based), with the line of each section for messages.
struct FeatureSections {
  std::vector<int> corners, requiredVertices, requiredEdgeIds, ridgeIds;
  int requiredEdgesLine = 0, ridgesLine = 0;
};

/// A feature section: a count, then that many 1-based indices in [1, max]; 0-based out.
void readIndexSection(TextScanner& s, const std::string& kw, long max, std::vector<int>& out) {
  const long n = readCount(s, (kw + " count").c_str(), 1);
  out.reserve(out.size() + std::size_t(n));
  for (long i = 0; i < n; ++i) {
    const long id = s.nextInt("index", LONG_MIN, LONG_MAX);
    ABLMG_REQUIRE(id >= 1 && id <= max,
                  s.where() << kw << " entry " << i + 1 << ": index " << id << " out of range [1, " << max << "]");
    out.push_back(int(id - 1));
  }
}

/// The sections of a .mesh file, in the file's order and orientation. With `zs` null, a
/// Dimension 3 file must be planar (z = 0); otherwise every z is stored there (0 in Dimension 2).
Mesh2 parseSections(std::string text, const std::string& name, std::vector<double>* zs, int& dim,
                    FeatureSections* features = nullptr) {
  TextScanner s(std::move(text), name);
  readHeader(s, dim, true);
  Mesh2 mesh;
  std::vector<int> vertexLine;  // line of each vertex (for z ≠ 0 messages)
  bool haveVertices = false, haveEnd = false;
  while (!s.atEnd()) {
    const auto kw = lower(s.next("section keyword"));
    if (kw == "end") {
      haveEnd = true;
      break;
    }
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
    } else if (features && (kw == "corners" || kw == "requiredvertices")) {
      ABLMG_REQUIRE(haveVertices, s.where() << "section " << kw << " before Vertices");
      readIndexSection(s, kw == "corners" ? "Corners" : "RequiredVertices", mesh.numVertices(),
                       kw == "corners" ? features->corners : features->requiredVertices);
    } else if (features && (kw == "requirededges" || kw == "ridges")) {
      // indices into Edges, which may come later: checked once the file is read
      const bool req = kw == "requirededges";
      (req ? features->requiredEdgesLine : features->ridgesLine) = s.line();
      readIndexSection(s, req ? "RequiredEdges" : "Ridges", INT_MAX - 1,
                       req ? features->requiredEdgeIds : features->ridgeIds);
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
  // Every writer ends with End (medit, gmsh, FreeFem++, MMG, meshio): without it the file was
  // cut between two sections, and what was read would be meshed as if it were whole.
  ABLMG_REQUIRE(haveEnd, name << ":" << s.line() << ": no End keyword (truncated file?)");
  return mesh;
}

/// Drops triangles repeating an earlier one's vertex set (any order); returns how many.
/// Triangles are grouped by their smallest vertex (counting sort, O(n)) and compared there.
long dropDuplicateTriangles(Mesh2& mesh) {
  const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
  const auto sorted = [&](std::size_t t) {
    auto v = mesh.triangles[t];
    std::sort(v.begin(), v.end());
    return v;
  };
  std::vector<int> rowStart(nv + 1, 0), ids(nt);
  for (std::size_t t = 0; t < nt; ++t) ++rowStart[std::size_t(sorted(t)[0]) + 1];
  for (std::size_t v = 0; v < nv; ++v) rowStart[v + 1] += rowStart[v];
  std::vector<int> fill(rowStart.begin(), rowStart.end() - 1);
  for (std::size_t t = 0; t < nt; ++t) ids[std::size_t(fill[std::size_t(sorted(t)[0])]++)] = int(t);
  std::vector<char> drop(nt, 0);
  long dropped = 0;
  for (std::size_t v = 0; v < nv; ++v)
    for (int i = rowStart[v]; i < rowStart[v + 1]; ++i)
      for (int j = rowStart[v]; j < i; ++j)
        if (!drop[std::size_t(ids[std::size_t(j)])] &&
            sorted(std::size_t(ids[std::size_t(i)])) == sorted(std::size_t(ids[std::size_t(j)]))) {
          drop[std::size_t(std::max(ids[std::size_t(i)], ids[std::size_t(j)]))] = 1;
          ++dropped;
          break;
        }
  if (dropped == 0) return 0;
  std::size_t k = 0;
  for (std::size_t t = 0; t < nt; ++t)
    if (!drop[t]) {
      mesh.triangles[k] = mesh.triangles[t];
      mesh.triangleRefs[k] = mesh.triangleRefs[t];
      ++k;
    }
  mesh.triangles.resize(k);
  mesh.triangleRefs.resize(k);
  return dropped;
}

std::uint64_t edgeKey(int a, int b) {
  return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
}

/// The file's Edges sorted into Mesh2's lists, as MMG reads them: an edge in one triangle is a
/// boundary edge (oriented with the triangle on its left), an edge in two is an interface edge;
/// boundary edges the file does not list are added with ref 0, and so are edges between
/// triangles of different refs. Repeated edges are merged (the first ref kept). An edge in no
/// triangle is an error. Listed edges keep the file's order; added ones follow in triangle order.
/// Returns the number of repeated and of added edges through the counters.
void classifyEdges(Mesh2& mesh, const std::string& name, const std::vector<std::uint64_t>& fileKeys, long& repeated,
                   long& addedBoundary, long& addedInterface) {
  std::unordered_map<std::uint64_t, int> firstOf;  // edge key -> index of its first listing
  firstOf.reserve(mesh.boundaryEdges.size());
  std::vector<BoundaryEdge> listed;
  listed.reserve(mesh.boundaryEdges.size());
  std::vector<int> kind;  // per listed edge: 0 none yet, 1 boundary, 2 interface
  for (std::size_t i = 0; i < mesh.boundaryEdges.size(); ++i) {
    if (!firstOf.emplace(fileKeys[i], int(listed.size())).second) {
      ++repeated;
      continue;
    }
    listed.push_back(mesh.boundaryEdges[i]);
  }
  kind.assign(listed.size(), 0);
  const auto nb = mesh.triangleNeighbours();
  std::vector<BoundaryEdge> extraBoundary, extraInterface;
  const auto refOf = [&](int t) { return mesh.triangleRefs[std::size_t(t)]; };
  for (int t = 0; t < mesh.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles[std::size_t(t)][(k + 1) % 3], b = mesh.triangles[std::size_t(t)][(k + 2) % 3];
      const int u = nb[std::size_t(t)][k];
      if (u >= 0 && u < t) continue;  // interior edge, seen from its other triangle
      const auto it = firstOf.find(edgeKey(a, b));
      if (it != firstOf.end()) {
        auto& e = listed[std::size_t(it->second)];
        kind[std::size_t(it->second)] = u < 0 ? 1 : 2;
        if (u < 0) e.a = a, e.b = b;  // domain on the left
      } else if (u < 0) {
        extraBoundary.push_back({a, b, 0});
      } else if (refOf(u) != refOf(t)) {
        extraInterface.push_back({a, b, 0});
      }
    }
  mesh.boundaryEdges.clear();
  for (std::size_t i = 0; i < listed.size(); ++i) {
    ABLMG_REQUIRE(kind[i] != 0, name << ": edge (" << listed[i].a + 1 << ", " << listed[i].b + 1
                                     << ") of Edges is a side of no triangle");
    (kind[i] == 1 ? mesh.boundaryEdges : mesh.interfaceEdges).push_back(listed[i]);
  }
  addedBoundary = long(extraBoundary.size());
  addedInterface = long(extraInterface.size());
  mesh.boundaryEdges.insert(mesh.boundaryEdges.end(), extraBoundary.begin(), extraBoundary.end());
  mesh.interfaceEdges.insert(mesh.interfaceEdges.end(), extraInterface.begin(), extraInterface.end());
}

/// RequiredEdges / Ridges: indices into the file's Edges → vertex pairs.
void resolveEdgeIds(const std::vector<int>& ids, const std::vector<BoundaryEdge>& fileEdges, const std::string& name,
                    int line, const char* what, std::vector<std::array<int, 2>>& out) {
  for (int id : ids) {
    ABLMG_REQUIRE(std::size_t(id) < fileEdges.size(), name << ":" << line << ": " << what << " names edge " << id + 1
                                                           << " but Edges has " << fileEdges.size());
    out.push_back({fileEdges[std::size_t(id)].a, fileEdges[std::size_t(id)].b});
  }
}

std::string plural(long n, const char* word) { return std::to_string(n) + " " + word + (n == 1 ? "" : "s"); }

/// parseMesh on a string it owns (readMesh moves the file's text in: no copy).
MeshFile meshFromText(std::string text, const std::string& name) {
  int dim = 2;
  FeatureSections f;
  MeshFile file;
  Mesh2& mesh = file.mesh;
  mesh = parseSections(std::move(text), name, nullptr, dim, &f);
  for (int v : f.corners) mesh.corners.push_back(v);
  for (int v : f.requiredVertices) mesh.requiredVertices.push_back(v);
  resolveEdgeIds(f.requiredEdgeIds, mesh.boundaryEdges, name, f.requiredEdgesLine, "RequiredEdges", mesh.requiredEdges);
  resolveEdgeIds(f.ridgeIds, mesh.boundaryEdges, name, f.ridgesLine, "Ridges", mesh.ridges);
  // Orientation: triangles counter-clockwise (the format does not fix one).
  for (auto& t : mesh.triangles) {
    const Vec2 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    if (cross(b - a, c - a) < 0) std::swap(t[1], t[2]);
  }
  if (mesh.triangles.empty()) {  // a boundary discretization: Edges as given, repeats merged
    std::unordered_map<std::uint64_t, int> seen;
    std::size_t k = 0;
    for (std::size_t i = 0; i < mesh.boundaryEdges.size(); ++i)
      if (seen.emplace(edgeKey(mesh.boundaryEdges[i].a, mesh.boundaryEdges[i].b), 0).second)
        mesh.boundaryEdges[k++] = mesh.boundaryEdges[i];
    if (k < mesh.boundaryEdges.size())
      file.warnings.push_back(name + ": " + plural(long(mesh.boundaryEdges.size() - k), "repeated edge") + " merged");
    mesh.boundaryEdges.resize(k);
    return file;
  }
  if (const long d = dropDuplicateTriangles(mesh); d > 0)
    file.warnings.push_back(name + ": " + plural(d, "repeated triangle") + " merged");
  std::vector<std::uint64_t> keys;
  keys.reserve(mesh.boundaryEdges.size());
  for (const auto& e : mesh.boundaryEdges) keys.push_back(edgeKey(e.a, e.b));
  long repeated = 0, addedBoundary = 0, addedInterface = 0;
  classifyEdges(mesh, name, keys, repeated, addedBoundary, addedInterface);
  if (repeated > 0) file.warnings.push_back(name + ": " + plural(repeated, "repeated edge") + " merged");
  if (addedBoundary > 0)
    file.warnings.push_back(name + ": " + plural(addedBoundary, "boundary edge") + " not in Edges, added with ref 0");
  if (addedInterface > 0)
    file.warnings.push_back(name + ": " + plural(addedInterface, "edge") +
                            " between subdomains not in Edges, added as interface edges with ref 0");
  return file;
}

/// parseSol on a string it owns (readSol moves the file's text in).
std::vector<Metric2> solFromText(std::string text, const std::string& name, int expectedVertices, int field) {
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
    std::vector<int> offsets;  // first value of each field within a vertex's values
    for (auto& t : types) {
      t = int(s.nextInt("solution type (1 scalar, 2 vector, 3 tensor)", 1, 3));
      offsets.push_back(perVertex);
      perVertex += t == 1 ? 1 : t == 2 ? dim : tensorSize;
    }
    ABLMG_REQUIRE(field <= nsol, s.where() << "field " << field << " asked for, but the file has " << nsol
                                           << " solution field" << (nsol == 1 ? "" : "s"));
    int chosen = field - 1;  // 0-based
    if (field <= 0) {
      const long tensors = std::count(types.begin(), types.end(), 3);
      chosen = tensors == 1 ? int(std::find(types.begin(), types.end(), 3) - types.begin()) : 0;
    }
    const int type = types[std::size_t(chosen)], offset = offsets[std::size_t(chosen)];
    ABLMG_REQUIRE(type == 1 || type == 3, s.where() << "solution field " << chosen + 1
                                                    << " has type 2 (vector); a metric needs type 1 (size) or 3 "
                                                       "(tensor) (choose a field)");
    ABLMG_REQUIRE(
        n <= long(s.size() / (2 * std::size_t(perVertex)) + 1),
        name << ":" << countLine << ": solution count " << n << " is more than the file can hold (truncated?)");
    std::vector<Metric2> out;
    out.reserve(n);
    std::vector<double> all(perVertex);
    for (long i = 0; i < n; ++i) {
      int firstLine = 0;
      for (int k = 0; k < perVertex; ++k) {
        all[k] = s.nextDouble(k < offset ? "solution value" : type == 1 ? "size value" : "tensor entry");
        if (k == offset) firstLine = s.line();
      }
      const double* v = all.data() + offset;
      // "<file>:<line>: " is built only for a message, not for every vertex.
      const auto at = [&] { return name + ":" + std::to_string(firstLine) + ": "; };
      if (type == 1) {
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

MeshFile parseMeshFile(const std::string& text, const std::string& name) { return meshFromText(text, name); }

MeshFile readMeshFile(const std::string& path) { return meshFromText(readTextFile(path), path); }

Mesh2 parseMesh(const std::string& text, const std::string& name) { return meshFromText(text, name).mesh; }

Mesh2 readMesh(const std::string& path) { return meshFromText(readTextFile(path), path).mesh; }

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

std::vector<Metric2> parseSol(const std::string& text, const std::string& name, int expectedVertices, int field) {
  return solFromText(text, name, expectedVertices, field);
}

std::vector<Metric2> readSol(const std::string& path, int expectedVertices, int field) {
  return solFromText(readTextFile(path), path, expectedVertices, field);
}

namespace {

/// Text built in memory: numbers by std::to_chars (a double in the shortest form that reads
/// back to the same bits, e.g. 0.1 and not 0.10000000000000001; ints in decimal), written into
/// a buffer that grows in large steps. The .mesh + .sol of a 2.3·10^5-triangle remesh took
/// 0.3 s through an ostream with setprecision(17), 0.05 s this way.
/// With a sink, the buffer is a block of kBlock characters handed to the stream whenever it
/// fills (finish() hands over the rest): a 10⁶-triangle .mesh + .sol no longer holds ≈ 90 MB
/// of text in memory next to the mesh.
class TextBuilder {
 public:
  explicit TextBuilder(std::size_t expectedSize) { buf_.resize(expectedSize + 64); }
  explicit TextBuilder(std::ostream& sink) : sink_(&sink) { buf_.resize(kBlock); }
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
  /// Streaming: hands the rest of the text to the sink.
  void finish() {
    if (sink_ && n_ > 0) sink_->write(buf_.data(), std::streamsize(n_));
    n_ = 0;
  }

 private:
  static constexpr std::size_t kNumberRoom = 32;  ///< the longest double is 24 characters
  static constexpr std::size_t kBlock = std::size_t(1) << 20;
  void room(std::size_t k) {
    if (buf_.size() - n_ >= k) return;
    if (sink_) finish();
    if (buf_.size() - n_ < k) buf_.resize(std::max(2 * buf_.size(), n_ + k + 4096));
  }
  std::string buf_;
  std::size_t n_ = 0;
  std::ostream* sink_ = nullptr;
};

void header(TextBuilder& out, int dim) { out.text("MeshVersionFormatted 2\n\nDimension ").num(dim).text("\n\n"); }
int refOr0(const std::vector<int>& refs, std::size_t i) { return i < refs.size() ? refs[i] : 0; }

void emitMesh(TextBuilder& out, const Mesh2& mesh) {
  header(out, 2);
  out.text("Vertices\n").num(mesh.vertices.size()).ch('\n');
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    out.num(mesh.vertices[i].x()).ch(' ').num(mesh.vertices[i].y()).ch(' ').num(refOr0(mesh.vertexRefs, i)).ch('\n');
  // Edges: boundary, then interface, then required edges and ridges not among them (ref 0).
  std::vector<BoundaryEdge> edges = mesh.boundaryEdges;
  edges.insert(edges.end(), mesh.interfaceEdges.begin(), mesh.interfaceEdges.end());
  std::vector<std::vector<int>> edgeIds(2);  // RequiredEdges, Ridges as 1-based indices into Edges
  if (!mesh.requiredEdges.empty() || !mesh.ridges.empty()) {
    std::unordered_map<std::uint64_t, int> index;
    for (std::size_t i = 0; i < edges.size(); ++i) index.emplace(edgeKey(edges[i].a, edges[i].b), int(i) + 1);
    for (int l = 0; l < 2; ++l)
      for (const auto& e : l == 0 ? mesh.requiredEdges : mesh.ridges) {
        auto [it, added] = index.emplace(edgeKey(e[0], e[1]), int(edges.size()) + 1);
        if (added) edges.push_back({e[0], e[1], 0});
        edgeIds[std::size_t(l)].push_back(it->second);
      }
  }
  out.text("\nEdges\n").num(edges.size()).ch('\n');
  for (const auto& e : edges) out.num(e.a + 1).ch(' ').num(e.b + 1).ch(' ').num(e.ref).ch('\n');
  out.text("\nTriangles\n").num(mesh.triangles.size()).ch('\n');
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tr = mesh.triangles[t];
    out.num(tr[0] + 1).ch(' ').num(tr[1] + 1).ch(' ').num(tr[2] + 1).ch(' ').num(refOr0(mesh.triangleRefs, t)).ch('\n');
  }
  const auto section = [&](const char* kw, const std::vector<int>& ids, int plus) {
    if (ids.empty()) return;
    out.text("\n").text(kw).ch('\n').num(ids.size()).ch('\n');
    for (int i : ids) out.num(i + plus).ch('\n');
  };
  section("Corners", mesh.corners, 1);
  section("RequiredVertices", mesh.requiredVertices, 1);
  section("RequiredEdges", edgeIds[0], 0);
  section("Ridges", edgeIds[1], 0);
  out.text("\nEnd\n");
}

void emitSol(TextBuilder& out, std::span<const Metric2> metrics) {
  header(out, 2);
  out.text("SolAtVertices\n").num(metrics.size()).text("\n1 3\n\n");
  for (const auto& m : metrics) out.num(m.m11()).ch(' ').num(m.m12()).ch(' ').num(m.m22()).ch('\n');
  out.text("\nEnd\n");
}

/// Streams emit(out) into `os` through a block buffer.
template <class Emit>
void streamTo(std::ostream& os, Emit&& emit) {
  TextBuilder out(os);
  emit(out);
  out.finish();
}

void writeText(const std::string& path, const std::string& text) {
  writeFileAtomically(path, [&](std::ostream& os) { os.write(text.data(), std::streamsize(text.size())); });
}

}  // namespace

void writeMesh(const std::string& path, const Mesh2& mesh) {
  writeFileAtomically(path, [&](std::ostream& os) { streamTo(os, [&](TextBuilder& out) { emitMesh(out, mesh); }); });
}

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

void writeSol(const std::string& path, std::span<const Metric2> metrics) {
  writeFileAtomically(path, [&](std::ostream& os) { streamTo(os, [&](TextBuilder& out) { emitSol(out, metrics); }); });
}

void writeMeshAndSol(const std::string& meshPath, const Mesh2& mesh, const std::string& solPath,
                     std::span<const Metric2> metrics) {
  // The .sol is formatted and streamed into its temporary file on a second thread while this
  // one writes the .mesh (formatting is most of the cost). The .sol is renamed into place only
  // once the .mesh is: if the .mesh fails, the .sol is left as it was; if the .sol fails, the
  // new .mesh is removed again.
  struct MeshFailed {};
  std::promise<bool> meshWritten;
  std::shared_future<bool> meshOk = meshWritten.get_future().share();
  auto sol = std::async(std::launch::async, [&] {
    writeFileAtomically(solPath, [&](std::ostream& os) {
      streamTo(os, [&](TextBuilder& out) { emitSol(out, metrics); });
      if (!meshOk.get()) throw MeshFailed{};  // unwinds: the temporary is removed
    });
  });
  try {
    writeMesh(meshPath, mesh);
  } catch (...) {
    meshWritten.set_value(false);
    try {
      sol.get();
    } catch (...) {  // MeshFailed, or the .sol's own error: the .mesh's is the one to report
    }
    throw;
  }
  meshWritten.set_value(true);
  try {
    sol.get();
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
