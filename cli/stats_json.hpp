#pragma once
/// The mesher's statistics as JSON, for the `--report` files of `ablmg mesh` and `ablmg remesh`
/// (the keys are the C++ field names of mesher::PlacementStats, ConnectStats, ImproveStats).
#include "ablmg/mesher/mesher.hpp"
#include "ablmg/mesher/quality.hpp"

#include <nlohmann/json.hpp>

namespace ablmg::cli {

nlohmann::json placementStatsJson(const mesher::PlacementStats& s);
/// {"placement": ..., "connect": ..., "improve": ..., "secondsValidate": ...}
nlohmann::json meshStatsJson(const mesher::MeshStats& s);
/// {"dimension", "vertices", "triangles", "edges", "valid", "first_problem",
///  "edge_length": {min, mean, max, in_sqrt2, within_10pct, deviation: {e, bins: [6]}},
///  "element_quality": {measure, min, mean, max, bins: [5]}, "lee_alpha": {min, mean, max, bins: [5]}}.
nlohmann::json qualityJson(const mesher::MeshQuality& q);

}  // namespace ablmg::cli
