#include "ablmg/cli/config.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/poly.hpp"

#include <climits>
#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <variant>

namespace ablmg::cli {
namespace {

using json = nlohmann::json;
using mesher::ConnectOptions;
using mesher::ImproveOptions;
using mesher::PlacementOptions;

std::string typeName(const json& j) {
  if (j.is_number_integer() || j.is_number_unsigned() || j.is_number_float()) return "number";
  return j.type_name();
}

/// A key path inside the config file, for messages: "config.json: metric.h1".
struct Where {
  std::string file, path;
  Where operator/(const std::string& key) const { return {file, path.empty() ? key : path + "." + key}; }
  Where operator[](std::size_t i) const { return {file, path + "[" + std::to_string(i) + "]"}; }
  std::string str() const { return file + ": " + (path.empty() ? "(top level)" : path); }
};

void requireType(const json& j, bool ok, const char* expected, const Where& w) {
  ABLMG_REQUIRE(ok, w.str() << ": expected " << expected << ", got " << typeName(j));
}
const json& requireObject(const json& j, const Where& w) {
  requireType(j, j.is_object(), "object", w);
  return j;
}
double getNumber(const json& j, const Where& w) {
  requireType(j, j.is_number(), "number", w);
  const double v = j.get<double>();
  ABLMG_REQUIRE(std::isfinite(v), w.str() << ": value is not finite");
  return v;
}
std::string getString(const json& j, const Where& w) {
  requireType(j, j.is_string(), "string", w);
  return j.get<std::string>();
}
Vec2 getPoint(const json& j, const Where& w) {
  requireType(j, j.is_array() && j.size() == 2, "[x, y]", w);
  return {getNumber(j[0], w[0]), getNumber(j[1], w[1])};
}
/// Rejects keys not in `allowed`, naming the first unknown one and the allowed set.
void checkKeys(const json& j, std::initializer_list<const char*> allowed, const Where& w) {
  for (const auto& [k, v] : j.items()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || k == a;
    if (!ok) {
      std::ostringstream os;
      for (const char* a : allowed) os << (os.tellp() > 0 ? ", " : "") << a;
      ABLMG_REQUIRE(false, (w / k).str() << ": unknown key (allowed: " << os.str() << ")");
    }
  }
}
std::string resolve(const std::string& p, const std::string& baseDir) {
  const std::filesystem::path path(p);
  if (path.is_absolute() || baseDir.empty()) return p;
  return (std::filesystem::path(baseDir) / path).string();
}

// ---- options: one binding per field, used both to read and to print ----
template <class S>
using Member = std::variant<double S::*, int S::*, long S::*, std::uint64_t S::*, bool S::*>;
template <class S>
struct Binding {
  const char* name;
  Member<S> member;
};
const std::vector<Binding<PlacementOptions>>& placementBindings() {
  static const std::vector<Binding<PlacementOptions>> b = {
      {"k0", &PlacementOptions::k0},
      {"mass", &PlacementOptions::mass},
      {"damping", &PlacementOptions::damping},
      {"timeStep", &PlacementOptions::timeStep},
      {"adjacencyRadius", &PlacementOptions::adjacencyRadius},
      {"adjacencyRefresh", &PlacementOptions::adjacencyRefresh},
      {"maxSteps", &PlacementOptions::maxSteps},
      {"stallSteps", &PlacementOptions::stallSteps},
      {"plateauSteps", &PlacementOptions::plateauSteps},
      {"plateauGain", &PlacementOptions::plateauGain},
      {"finalRelaxSteps", &PlacementOptions::finalRelaxSteps},
      {"metricLag", &PlacementOptions::metricLag},
      {"defectPasses", &PlacementOptions::defectPasses},
      {"defectEvery", &PlacementOptions::defectEvery},
      {"defectShake", &PlacementOptions::defectShake},
      {"defectMinShare", &PlacementOptions::defectMinShare},
      {"tolerance", &PlacementOptions::tolerance},
      {"relativeTolerance", &PlacementOptions::relativeTolerance},
      {"maxNodes", &PlacementOptions::maxNodes},
      {"seed", &PlacementOptions::seed},
      {"threads", &PlacementOptions::threads},
      {"bubblesOnly", &PlacementOptions::bubblesOnly},
  };
  return b;
}
const std::vector<Binding<ConnectOptions>>& connectBindings() {
  static const std::vector<Binding<ConnectOptions>> b = {{"threads", &ConnectOptions::threads},
                                                         {"localRepair", &ConnectOptions::localRepair}};
  return b;
}
const std::vector<Binding<ImproveOptions>>& improveBindings() {
  static const std::vector<Binding<ImproveOptions>> b = {{"enabled", &ImproveOptions::enabled},
                                                         {"qThreshold", &ImproveOptions::qThreshold},
                                                         {"maxPasses", &ImproveOptions::maxPasses},
                                                         {"swapMargin", &ImproveOptions::swapMargin},
                                                         {"moveMargin", &ImproveOptions::moveMargin},
                                                         {"collapseEdges", &ImproveOptions::collapseEdges},
                                                         {"collapseMargin", &ImproveOptions::collapseMargin}};
  return b;
}

template <class S>
void applyBindings(const json& j, S& s, const std::vector<Binding<S>>& bindings, const Where& w) {
  requireObject(j, w);
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string k = it.key();
    const json& v = it.value();
    const Binding<S>* found = nullptr;
    for (const auto& b : bindings)
      if (k == b.name) found = &b;
    if (!found) {
      std::ostringstream os;
      for (const auto& b : bindings) os << (os.tellp() > 0 ? ", " : "") << b.name;
      ABLMG_REQUIRE(false, (w / k).str() << ": unknown key (allowed: " << os.str() << ")");
    }
    const Where wk = w / k;
    std::visit(
        [&](auto member) {
          using T = std::remove_reference_t<decltype(s.*member)>;
          if constexpr (std::is_same_v<T, bool>) {
            requireType(v, v.is_boolean(), "boolean", wk);
            s.*member = v.get<bool>();
          } else if constexpr (std::is_same_v<T, double>) {
            s.*member = getNumber(v, wk);
          } else {
            requireType(v, v.is_number_integer() || v.is_number_unsigned(), "integer", wk);
            if constexpr (std::is_unsigned_v<T>) {
              ABLMG_REQUIRE(v.is_number_unsigned() || v.get<long long>() >= 0,
                            wk.str() << ": must be ≥ 0, got " << v.dump());
              s.*member = v.get<T>();
            } else {
              const long long x = v.is_number_unsigned() && v.get<unsigned long long>() > (unsigned long long)LLONG_MAX
                                      ? LLONG_MAX
                                      : v.get<long long>();
              ABLMG_REQUIRE(
                  x >= (long long)std::numeric_limits<T>::min() && x <= (long long)std::numeric_limits<T>::max(),
                  wk.str() << ": " << v.dump() << " is out of range");
              s.*member = T(x);
            }
          }
        },
        found->member);
  }
}
template <class S>
json bindingsToJson(const S& s, const std::vector<Binding<S>>& bindings) {
  json j = json::object();
  for (const auto& b : bindings) std::visit([&](auto member) { j[b.name] = s.*member; }, b.member);
  return j;
}

Domain parseDomain(const json& j, const Where& w, const std::string& baseDir);

/// "regions": [{"points": [[x, y], ...] (≥ 3), "tag": T (integer ≥ 1)}, ...].
std::vector<adapt::TaggedRegion> parseRegions(const json& R, const Where& wr) {
  requireType(R, R.is_array(), "array of regions {\"points\": [[x, y], ...], \"tag\": T}", wr);
  std::vector<adapt::TaggedRegion> out;
  for (std::size_t k = 0; k < R.size(); ++k) {
    const Where wk = wr[k];
    requireObject(R[k], wk);
    checkKeys(R[k], {"points", "tag"}, wk);
    ABLMG_REQUIRE(R[k].contains("points"), wk.str() << ": points: missing (required)");
    ABLMG_REQUIRE(R[k].contains("tag"), wk.str() << ": tag: missing (required, an integer >= 1)");
    const json& P = R[k]["points"];
    requireType(P, P.is_array() && P.size() >= 3, "array of >= 3 points [x, y]", wk / "points");
    adapt::TaggedRegion r;
    for (std::size_t i = 0; i < P.size(); ++i) r.points.push_back(getPoint(P[i], (wk / "points")[i]));
    const json& T = R[k]["tag"];
    requireType(T, T.is_number_integer() && T.get<long long>() >= 1 && T.get<long long>() <= 1000000000, "integer >= 1",
                wk / "tag");
    r.tag = T.get<int>();
    out.push_back(std::move(r));
  }
  return out;
}

/// "slits": [{"points": [[x, y], ...], "tags": [left, right]}, ...] added to `d` in order
/// (Domain::withSlit: attached where points[0] is on the boundary, else free).
Domain applySlits(Domain d, const json& S, const Where& ws) {
  requireType(S, S.is_array(), "array of slits {\"points\": [[x, y], ...], \"tags\": [left, right]}", ws);
  for (std::size_t k = 0; k < S.size(); ++k) {
    const Where wk = ws[k];
    requireObject(S[k], wk);
    checkKeys(S[k], {"points", "tags"}, wk);
    ABLMG_REQUIRE(S[k].contains("points"), wk.str() << ": points: missing (required)");
    const json& P = S[k]["points"];
    requireType(P, P.is_array() && P.size() >= 2, "array of ≥ 2 points [x, y]", wk / "points");
    std::vector<Vec2> pts;
    for (std::size_t i = 0; i < P.size(); ++i) pts.push_back(getPoint(P[i], (wk / "points")[i]));
    int tags[2] = {1, 1};
    if (S[k].contains("tags")) {
      const json& T = S[k]["tags"];
      requireType(T, T.is_array() && T.size() == 2 && T[0].is_number_integer() && T[1].is_number_integer(),
                  "[left, right] (two integers)", wk / "tags");
      tags[0] = T[0].get<int>();
      tags[1] = T[1].get<int>();
    }
    try {
      d = d.withSlit(pts, tags[0], tags[1]);
    } catch (const InputError& e) { throw InputError(wk.str() + ": " + e.what()); }
  }
  return d;
}

/// "rectangle": [x0, y0, x1, y1].
Domain parseRectangle(const json& r, const Where& wr) {
  requireType(r, r.is_array() && r.size() == 4, "[x0, y0, x1, y1]", wr);
  double c[4];
  for (int k = 0; k < 4; ++k) c[k] = getNumber(r[k], wr[k]);
  ABLMG_REQUIRE(c[0] < c[2] && c[1] < c[3], wr.str() << ": need x0 < x1 and y0 < y1, got " << r.dump());
  return Domain::rectangle(c[0], c[1], c[2], c[3]);
}

/// "disk": {"center": [x, y], "radius": r, "samples": n (default 2048)}.
Domain parseDisk(const json& dj, const Where& wd) {
  const json& d = requireObject(dj, wd);
  checkKeys(d, {"center", "radius", "samples"}, wd);
  ABLMG_REQUIRE(d.contains("center") && d.contains("radius"), wd.str() << ": needs center and radius");
  const Vec2 c = getPoint(d["center"], wd / "center");
  const double r = getNumber(d["radius"], wd / "radius");
  ABLMG_REQUIRE(r > 0, (wd / "radius").str() << ": must be > 0, got " << r);
  int samples = 2048;
  if (d.contains("samples")) {
    const Where ws = wd / "samples";
    requireType(d["samples"], d["samples"].is_number_integer(), "integer", ws);
    const long long n = d["samples"].get<long long>();
    ABLMG_REQUIRE(n >= 8 && n <= 10'000'000, ws.str() << ": must be in [8, 1e7], got " << n);
    samples = int(n);
  }
  return Domain::disk(c, r, samples);
}

/// "smooth": true/false for every loop, or one boolean per loop (outer first, then the holes).
void applySmooth(const json& S, const Where& ws, std::vector<BoundaryLoop>& loops) {
  if (S.is_boolean()) {
    for (auto& loop : loops) loop.smooth = S.get<bool>();
    return;
  }
  requireType(S, S.is_array() && S.size() == loops.size(), "boolean or one boolean per loop", ws);
  for (std::size_t l = 0; l < S.size(); ++l) {
    requireType(S[l], S[l].is_boolean(), "boolean", ws[l]);
    loops[l].smooth = S[l].get<bool>();
  }
}

/// "tags": one integer per loop, or per loop one integer per segment.
void applyTags(const json& T, const Where& wt, std::vector<BoundaryLoop>& loops) {
  requireType(T, T.is_array() && T.size() == loops.size(), "array with one entry per loop", wt);
  for (std::size_t l = 0; l < T.size(); ++l) {
    if (T[l].is_number_integer()) {
      loops[l].tags.assign(loops[l].points.size(), T[l].get<int>());
      continue;
    }
    requireType(T[l], T[l].is_array() && T[l].size() == loops[l].points.size(), "integer or one integer per segment",
                wt[l]);
    for (std::size_t k = 0; k < T[l].size(); ++k) {
      requireType(T[l][k], T[l][k].is_number_integer(), "integer", wt[l][k]);
      loops[l].tags.push_back(T[l][k].get<int>());
    }
  }
}

/// The outer loop first, then the holes.
Domain domainOfLoops(std::vector<BoundaryLoop> loops) {
  BoundaryLoop outer = std::move(loops.front());
  loops.erase(loops.begin());
  return Domain(std::move(outer), std::move(loops));
}

/// "loops": [[[x, y], ...], ...] with optional "tags" and "smooth".
Domain parseLoops(const json& j, const Where& w) {
  const Where wl = w / "loops";
  const json& L = j["loops"];
  requireType(L, L.is_array() && !L.empty(), "non-empty array of loops", wl);
  std::vector<BoundaryLoop> loops;
  for (std::size_t l = 0; l < L.size(); ++l) {
    requireType(L[l], L[l].is_array() && L[l].size() >= 3, "array of ≥ 3 points [x, y]", wl[l]);
    BoundaryLoop loop;
    for (std::size_t k = 0; k < L[l].size(); ++k) loop.points.push_back(getPoint(L[l][k], wl[l][k]));
    loops.push_back(std::move(loop));
  }
  if (j.contains("tags")) applyTags(j["tags"], w / "tags", loops);
  if (j.contains("smooth")) applySmooth(j["smooth"], w / "smooth", loops);
  try {
    return domainOfLoops(std::move(loops));
  } catch (const InputError& e) { throw InputError(wl.str() + ": " + e.what()); }
}

Domain parseDomain(const json& j, const Where& w, const std::string& baseDir) {
  requireObject(j, w);
  ABLMG_REQUIRE(!j.empty(), w.str() << ": empty; expected one of rectangle, disk, poly, loops");
  if (j.contains("slits")) {
    json rest = j;
    rest.erase("slits");
    return applySlits(parseDomain(rest, w, baseDir), j["slits"], w / "slits");
  }
  if (j.contains("rectangle")) {
    checkKeys(j, {"rectangle"}, w);
    return parseRectangle(j["rectangle"], w / "rectangle");
  }
  if (j.contains("disk")) {
    checkKeys(j, {"disk"}, w);
    return parseDisk(j["disk"], w / "disk");
  }
  if (j.contains("poly")) {
    checkKeys(j, {"poly", "smooth"}, w);
    Domain d = io::readPoly(resolve(getString(j["poly"], w / "poly"), baseDir));
    if (!j.contains("smooth")) return d;
    std::vector<BoundaryLoop> loops = d.loops();
    applySmooth(j["smooth"], w / "smooth", loops);
    return domainOfLoops(std::move(loops));
  }
  if (j.contains("loops")) {
    checkKeys(j, {"loops", "tags", "smooth"}, w);
    return parseLoops(j, w);
  }
  ABLMG_REQUIRE(false, (w / j.begin().key()).str() << ": unknown key (expected one of rectangle, disk, poly, loops)");
  return {};
}

std::unique_ptr<MetricField> parseMetric(const json& j, const Where& w, const std::string& baseDir,
                                         std::string& description) {
  requireObject(j, w);
  const auto expr = [&](const char* key, const char* fallback) {
    return j.contains(key) ? getString(j[key], w / key) : std::string(fallback);
  };
  if (j.contains("mesh") || j.contains("sol")) {
    checkKeys(j, {"mesh", "sol"}, w);
    ABLMG_REQUIRE(j.contains("mesh") && j.contains("sol"), w.str() << ": a background metric needs both mesh and sol");
    const std::string meshPath = resolve(getString(j["mesh"], w / "mesh"), baseDir);
    const std::string solPath = resolve(getString(j["sol"], w / "sol"), baseDir);
    Mesh2 mesh = io::readMesh(meshPath);
    auto metrics = io::readSol(solPath, mesh.numVertices());
    mesh.requireValid(meshPath, std::nullopt, 1e-9, 1);  // the file's own (1-based) ids in errors
    description = "background mesh " + meshPath + " (" + std::to_string(mesh.numVertices()) + " vertices) + " + solPath;
    return std::make_unique<BackgroundMetricField>(std::move(mesh), std::move(metrics));
  }
  const std::string source = w.str();
  if (j.contains("m11") || j.contains("m12") || j.contains("m22")) {
    checkKeys(j, {"m11", "m12", "m22"}, w);
    ABLMG_REQUIRE(j.contains("m11") && j.contains("m22"),
                  w.str() << ": a tensor metric needs m11 and m22 (m12 defaults to 0)");
    const auto a = expr("m11", ""), b = expr("m12", "0"), c = expr("m22", "");
    description = "analytic tensor m11=" + a + " m12=" + b + " m22=" + c;
    return std::make_unique<AnalyticMetricField>(AnalyticMetricField::Form::Tensor, a, b, c, source);
  }
  if (j.contains("h")) {
    checkKeys(j, {"h"}, w);
    const auto h = expr("h", "");
    description = "analytic isotropic h=" + h;
    return std::make_unique<AnalyticMetricField>(AnalyticMetricField::Form::Sizes, h, h, "0", source);
  }
  checkKeys(j, {"h1", "h2", "theta"}, w);
  ABLMG_REQUIRE(j.contains("h1"), w.str() << ": expected h1/h2/theta, h, m11/m12/m22 or mesh/sol");
  const auto h1 = expr("h1", ""), h2 = j.contains("h2") ? expr("h2", "") : h1, th = expr("theta", "0");
  description = "analytic sizes h1=" + h1 + " h2=" + h2 + " theta=" + th;
  return std::make_unique<AnalyticMetricField>(AnalyticMetricField::Form::Sizes, h1, h2, th, source);
}

}  // namespace

Domain parseDomainJson(const nlohmann::json& j, const std::string& file, const std::string& baseDir) {
  return parseDomain(j, Where{file, "domain"}, baseDir);
}

void applyMeshOptions(const nlohmann::json& j, mesher::MeshOptions& options, const std::string& where) {
  const std::size_t colon = where.find(": ");
  const Where w =
      colon == std::string::npos ? Where{where, ""} : Where{where.substr(0, colon), where.substr(colon + 2)};
  requireObject(j, w);
  checkKeys(j, {"preset", "placement", "connect", "improve"}, w);
  if (j.contains("preset")) {  // the named configuration first (mesher/mesher.hpp), then the fields
    const Where wp = w / "preset";
    const std::string name = getString(j["preset"], wp);
    mesher::MeshOptions base;
    try {
      base = mesher::meshPreset(mesher::parseMeshPreset(name));
    } catch (const InputError& e) { ABLMG_REQUIRE(false, wp.str() << ": " << e.what()); }
    base.progress = std::move(options.progress);
    base.progressEvery = options.progressEvery;
    options = std::move(base);
  }
  if (j.contains("placement")) {
    // The numeric fields by binding; the lattice orientation is the one string-valued field.
    json placement = j["placement"];
    requireObject(placement, w / "placement");
    if (placement.contains("latticeOrientation")) {
      const Where wl = w / "placement" / "latticeOrientation";
      const std::string name = getString(placement["latticeOrientation"], wl);
      try {
        options.placement.lattice.orientation = mesher::parseLatticeOrientation(name);
      } catch (const InputError& e) { ABLMG_REQUIRE(false, wl.str() << ": " << e.what()); }
      placement.erase("latticeOrientation");
    }
    if (placement.contains("pairDistance")) {
      const Where wp = w / "placement" / "pairDistance";
      const std::string name = getString(placement["pairDistance"], wp);
      try {
        options.placement.pairDistance = mesher::parsePairDistance(name);
      } catch (const InputError& e) { ABLMG_REQUIRE(false, wp.str() << ": " << e.what()); }
      placement.erase("pairDistance");
    }
    applyBindings(placement, options.placement, placementBindings(), w / "placement");
    try {
      mesher::validate(options.placement);
    } catch (const InputError& e) { ABLMG_REQUIRE(false, (w / "placement").str() << ": " << e.what()); }
  }
  if (j.contains("connect")) applyBindings(j["connect"], options.connect, connectBindings(), w / "connect");
  if (j.contains("improve")) {
    applyBindings(j["improve"], options.improve, improveBindings(), w / "improve");
    try {
      mesher::requireValid(options.improve);
    } catch (const InputError& e) { ABLMG_REQUIRE(false, (w / "improve").str() << ": " << e.what()); }
  }
}

void printEffectiveOptions(const std::string& command, const std::string& preset, const mesher::MeshOptions& options,
                           const nlohmann::json& commandOptions) {
  json out = {{"command", command}};
  if (commandOptions.is_object())
    for (const auto& [k, v] : commandOptions.items()) out[k] = v;
  json mesh = {{"preset", preset}};
  const json fields = meshOptionsToJson(options);
  for (const auto& [k, v] : fields.items()) mesh[k] = v;
  out["options"] = std::move(mesh);
  std::cout << out.dump(2) << "\n";
}

nlohmann::json meshOptionsToJson(const mesher::MeshOptions& options) {
  json placement = bindingsToJson(options.placement, placementBindings());
  placement["latticeOrientation"] = mesher::latticeOrientationName(options.placement.lattice.orientation);
  placement["pairDistance"] = mesher::pairDistanceName(options.placement.pairDistance);
  return {{"placement", placement},
          {"connect", bindingsToJson(options.connect, connectBindings())},
          {"improve", bindingsToJson(options.improve, improveBindings())}};
}

namespace {
/// JSON text → object; a syntax error reads "NAME: invalid JSON: <parser's message>".
json parseJsonText(const std::string& text, const std::string& name) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    std::string msg = e.what();
    const auto p = msg.find("] ");
    if (p != std::string::npos) msg = msg.substr(p + 2);
    ABLMG_REQUIRE(false, name << ": invalid JSON: " << msg);
  }
  return {};
}

std::string readText(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  ABLMG_REQUIRE(is, path << ": cannot open for reading");
  std::ostringstream ss;
  ss << is.rdbuf();
  return ss.str();
}
}  // namespace

std::unique_ptr<MetricField> loadMetricConfig(const std::string& path, std::string& description) {
  const json j = parseJsonText(readText(path), path);
  const std::string baseDir = std::filesystem::path(path).parent_path().string();
  requireObject(j, Where{path, ""});
  if (j.contains("metric")) return parseMetric(j["metric"], Where{path, "metric"}, baseDir, description);
  return parseMetric(j, Where{path, ""}, baseDir, description);
}

Config parseConfig(const std::string& text, const std::string& name, const std::string& baseDir) {
  const json j = parseJsonText(text, name);
  const Where top{name, ""};
  requireObject(j, top);
  checkKeys(j, {"domain", "regions", "metric", "options", "outputs"}, top);
  ABLMG_REQUIRE(j.contains("domain"), name << ": domain: missing (required)");
  ABLMG_REQUIRE(j.contains("metric"), name << ": metric: missing (required)");
  Config c;
  // Cheap checks first: options and outputs before reading any file.
  if (j.contains("options")) {
    applyMeshOptions(j["options"], c.options, name + ": options");
    if (j["options"].contains("preset")) c.preset = j["options"]["preset"].get<std::string>();
  }
  if (j.contains("outputs")) {
    const Where wo = top / "outputs";
    const json& o = requireObject(j["outputs"], wo);
    checkKeys(o, {"mesh", "vtu", "png", "report"}, wo);
    const auto get = [&](const char* k) {
      return o.contains(k) ? resolve(getString(o[k], wo / k), baseDir) : std::string();
    };
    c.outputs = {get("mesh"), get("vtu"), get("png"), get("report")};
  }
  c.domain = parseDomain(j["domain"], top / "domain", baseDir);
  if (j.contains("regions")) c.regions = parseRegions(j["regions"], top / "regions");
  c.metric = parseMetric(j["metric"], top / "metric", baseDir, c.metricDescription);
  return c;
}

Config loadConfig(const std::string& path) {
  return parseConfig(readText(path), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace ablmg::cli
