#include "ablmg/cli/stats_json.hpp"

namespace ablmg::cli {

nlohmann::json placementStatsJson(const mesher::PlacementStats& s) {
  return {{"predictedNodes", s.predictedNodes},
          {"initialNodes", s.initialNodes},
          {"finalNodes", s.finalNodes},
          {"nearestInRange", s.nearestInRange},
          {"inserted", s.inserted},
          {"deleted", s.deleted},
          {"steps", s.steps},
          {"hitStepCap", s.hitStepCap},
          {"stalled", s.stalled},
          {"qualityPlateau", s.qualityPlateau},
          {"activeBubbleSteps", s.activeBubbleSteps},
          {"initialResidual", s.initialResidual},
          {"finalResidual", s.finalResidual},
          {"secondsInitial", s.secondsInitial},
          {"secondsDynamics", s.secondsDynamics},
          {"secondsAdjacency", s.secondsAdjacency},
          {"secondsPopulation", s.secondsPopulation},
          {"defectPasses", s.defectPasses},
          {"defectsFirst", s.defectsFirst},
          {"defectsLast", s.defectsLast},
          {"secondsDefects", s.secondsDefects}};
}

nlohmann::json meshStatsJson(const mesher::MeshStats& s) {
  const auto& c = s.connect;
  const auto& i = s.improve;
  return {{"placement", placementStatsJson(s.placement)},
          {"connect",
           {{"links", c.links},
            {"longLinksDropped", c.longLinksDropped},
            {"intersectionTests", c.intersectionTests},
            {"crossingsFound", c.crossingsFound},
            {"deletedEdges", c.deletedEdges},
            {"deletionRounds", c.deletionRounds},
            {"consistentTriangles", c.consistentTriangles},
            {"repairedTriangles", c.repairedTriangles},
            {"failedRecoveries", c.failedRecoveries},
            {"swaps", c.swaps},
            {"swapCapHit", c.swapCapHit},
            {"localRepair", c.localRepair},
            {"droppedNodes", c.droppedNodes},
            {"secondsLocalMeshes", c.secondsLocalMeshes},
            {"secondsRepair", c.secondsRepair}}},
          {"improve",
           {{"badBefore", i.badBefore},
            {"badAfter", i.badAfter},
            {"swaps", i.swaps},
            {"moves", i.moves},
            {"collapses", i.collapses},
            {"passes", i.passes},
            {"qMinBefore", i.qMinBefore},
            {"qMinAfter", i.qMinAfter},
            {"seconds", i.seconds}}},
          {"secondsValidate", s.secondsValidate}};
}

}  // namespace ablmg::cli
