#pragma once
/// The mesher's statistics as JSON, for the `--report` files of `ablmg mesh` and `ablmg remesh`
/// (the keys are the C++ field names of mesher::PlacementStats, ConnectStats, ImproveStats).
#include "ablmg/mesher/mesher.hpp"

#include <nlohmann/json.hpp>

namespace ablmg::cli {

nlohmann::json placementStatsJson(const mesher::PlacementStats& s);
/// {"placement": ..., "connect": ..., "improve": ..., "secondsValidate": ...}
nlohmann::json meshStatsJson(const mesher::MeshStats& s);

}  // namespace ablmg::cli
