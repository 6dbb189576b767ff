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

nlohmann::json qualityJson(const mesher::MeshQuality& q) {
  const auto& l = q.edgeLengths;
  const auto& el = q.elements;
  return {{"dimension", q.dimension},
          {"vertices", q.vertices},
          {"triangles", q.triangles},
          {"edges", q.edges},
          {"valid", q.valid},
          {"first_problem", q.firstProblem},
          {"edge_length",
           {{"min", l.min},
            {"mean", l.mean},
            {"max", l.max},
            {"in_sqrt2", l.inSqrt2},
            {"within_10pct", l.within10},
            {"deviation", {{"e", l.e}, {"bins", l.deviation}}}}},
          {"element_quality",
           {{"measure", q.dimension == 2 ? "q = 4*sqrt(3)*A_M/(l1^2+l2^2+l3^2)" : "Lee alpha, eqs. (19)-(20)"},
            {"min", el.min},
            {"mean", el.mean},
            {"max", el.max},
            {"bins", el.bins}}},
          {"lee_alpha",
           {{"min", q.leeAlpha.min}, {"mean", q.leeAlpha.mean}, {"max", q.leeAlpha.max}, {"bins", q.leeAlpha.bins}}}};
}

}  // namespace ablmg::cli
