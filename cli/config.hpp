#pragma once
/// JSON configuration of `ablmg mesh` → Domain, MetricField, mesher::MeshOptions, outputs
/// (written by cli/mesh_output.hpp).
/// Schema (full text with examples: docs/config.md):
///
///   {
///     "domain":  {"rectangle": [x0, y0, x1, y1]}
///              | {"disk": {"center": [x, y], "radius": r, "samples": 2048}}
///              | {"poly": "file.poly"}
///              | {"loops": [[[x, y], ...], ...], "tags": [[t, ...], ...] or [t, ...]}
///                (first loop outer, the others holes; tags per segment, or one per loop),
///     "metric":  {"h1": "expr", "h2": "expr", "theta": "expr"}    (h2 default = h1, theta "0")
///              | {"h": "expr"}                                   (isotropic)
///              | {"m11": "expr", "m12": "expr", "m22": "expr"}   (muparser, variables x, y)
///              | {"mesh": "bg.mesh", "sol": "bg.sol"}            (BackgroundMetricField),
///     "options": {"placement": {<PlacementOptions field>: value, ...},
///                 "connect":   {<ConnectOptions field>: value, ...}},
///     "outputs": {"mesh": "out.mesh", "vtu": "out.vtu", "png": "out.png", "report": "r.json"}
///   }
///
/// Only "domain" and "metric" are required. Option names are the C++ field names; omitted
/// fields keep their defaults. Relative paths (poly, mesh, sol, outputs) are relative to the
/// config file's directory. Unknown keys, wrong types and bad values are ablmg::InputError
/// naming the file and key path: "config.json: metric.h1: expected string, got number".
#include "ablmg/adapt/remesh.hpp"
#include "ablmg/core/domain.hpp"
#include "ablmg/core/metric_field.hpp"
#include "ablmg/mesher/mesher.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <string>

namespace ablmg::cli {

struct ConfigOutputs {
  std::string mesh, vtu, png, report;  ///< empty = not requested; resolved paths
};

struct Config {
  Domain domain;
  /// "regions": [{"points": [[x, y], ...], "tag": T}, ...]: tagged polygons inside the domain,
  /// meshed as subdomains (adapt::meshDomainWithRegions; the rest of the domain has ref 0).
  std::vector<adapt::TaggedRegion> regions;
  std::unique_ptr<MetricField> metric;
  std::string metricDescription;  ///< one line, e.g. "analytic sizes h1=0.1 h2=0.1 theta=0"
  mesher::MeshOptions options;
  std::string preset = "mesh";  ///< options.preset in the file, else "mesh" (mesher::MeshPreset)
  ConfigOutputs outputs;
};

/// Reads and checks `path` (file name used in messages).
Config loadConfig(const std::string& path);
/// From text; `name` is used in messages, `baseDir` resolves relative paths.
Config parseConfig(const std::string& text, const std::string& name, const std::string& baseDir);

/// The metric of a JSON file (`ablmg stats --metric`): either a whole `ablmg mesh` config,
/// whose "metric" object is used (its other keys are not read), or a bare metric object in any
/// of the forms above. Relative mesh/sol paths are relative to the file; `description` gets a
/// one-line summary. Messages read "FILE: metric.<key>: ..." (or "FILE: <key>: ...").
std::unique_ptr<MetricField> loadMetricConfig(const std::string& path, std::string& description);

/// The "domain" object of a config (any of the forms above), for other commands' configs;
/// messages read "FILE: domain.<key>: ...".
Domain parseDomainJson(const nlohmann::json& j, const std::string& file, const std::string& baseDir);

/// Fills `options` from a JSON object {"preset": "mesh"|"remesh"|"adapt", "placement": {...},
/// "connect": {...}, "improve": {...}}: the preset (mesher/mesher.hpp) replaces `options` first
/// (its progress callback kept), then the fields given override it. `where` prefixes messages
/// (e.g. "config.json: options").
void applyMeshOptions(const nlohmann::json& j, mesher::MeshOptions& options, const std::string& where);
/// Every option with its value (defaults included), same layout as applyMeshOptions reads.
nlohmann::json meshOptionsToJson(const mesher::MeshOptions& options);

/// `--print-options`: writes to stdout, indented,
///   {"command": COMMAND, <command's own options>..., "options": {"preset": PRESET, <every
///   mesher field as meshOptionsToJson>}}
/// The "options" object read back by applyMeshOptions (a config's "options") gives `options`.
void printEffectiveOptions(const std::string& command, const std::string& preset, const mesher::MeshOptions& options,
                           const nlohmann::json& commandOptions);

}  // namespace ablmg::cli
