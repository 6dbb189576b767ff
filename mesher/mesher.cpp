#include "ablmg/mesher/mesher.hpp"

#include <algorithm>
#include <utility>

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/mesher/slit_domain.hpp"

namespace ablmg::mesher {
namespace {

/// Area the mesh must cover: the domain's for polygonal loops; for smooth loops the mesh's
/// boundary is the polygon through the boundary nodes, so that polygon's area is used.
double expectedArea(const Domain& domain, const Mesh2& mesh) {
  bool anySmooth = false;
  for (const auto& loop : domain.loops()) anySmooth = anySmooth || loop.smooth;
  if (!anySmooth) return domain.area();
  double a = 0;
  const Vec2 o = mesh.boundaryEdges.empty() ? Vec2(0, 0) : mesh.vertices[mesh.boundaryEdges[0].a];
  for (const auto& e : mesh.boundaryEdges)
    a += 0.5 * cross(mesh.vertices[e.a] - o, mesh.vertices[e.b] - o);  // about a boundary point: exact far away
  return a;
}

}  // namespace

void addPartStats(MeshStats& whole, const MeshStats& part) {
  auto& p = whole.placement;
  const auto& q = part.placement;
  const long nodes = p.finalNodes + q.finalNodes;
  if (nodes > 0)
    p.nearestInRange =
        (p.nearestInRange * double(p.finalNodes) + q.nearestInRange * double(q.finalNodes)) / double(nodes);
  for (auto [a, b] : {std::pair{&p.predictedNodes, q.predictedNodes},
                      {&p.initialNodes, q.initialNodes},
                      {&p.finalNodes, q.finalNodes},
                      {&p.inserted, q.inserted},
                      {&p.deleted, q.deleted},
                      {&p.activeBubbleSteps, q.activeBubbleSteps},
                      {&p.coincidentDropped, q.coincidentDropped}})
    *a += b;
  for (auto [a, b] : {std::pair{&p.defectsFirst, q.defectsFirst}, {&p.defectsLast, q.defectsLast}})
    if (b >= 0) *a = std::max<long>(*a, 0) + b;
  p.steps = std::max(p.steps, q.steps);
  p.defectPasses = std::max(p.defectPasses, q.defectPasses);
  p.hitStepCap = p.hitStepCap || q.hitStepCap;
  p.stalled = p.stalled || q.stalled;
  p.qualityPlateau = p.qualityPlateau || q.qualityPlateau;
  p.initialResidual = std::max(p.initialResidual, q.initialResidual);
  p.finalResidual = std::max(p.finalResidual, q.finalResidual);
  p.secondsInitial += q.secondsInitial;
  p.secondsDynamics += q.secondsDynamics;
  p.secondsAdjacency += q.secondsAdjacency;
  p.secondsPopulation += q.secondsPopulation;
  p.secondsDefects += q.secondsDefects;

  auto& c = whole.connect;
  const auto& d = part.connect;
  for (auto [a, b] : {std::pair{&c.links, d.links},
                      {&c.intersectionTests, d.intersectionTests},
                      {&c.crossingsFound, d.crossingsFound},
                      {&c.deletedEdges, d.deletedEdges},
                      {&c.consistentTriangles, d.consistentTriangles},
                      {&c.repairedTriangles, d.repairedTriangles},
                      {&c.failedRecoveries, d.failedRecoveries},
                      {&c.swaps, d.swaps},
                      {&c.droppedNodes, d.droppedNodes}})
    *a += b;
  c.deletionRounds = std::max(c.deletionRounds, d.deletionRounds);
  c.swapCapHit = c.swapCapHit || d.swapCapHit;
  c.localRepair = c.localRepair || d.localRepair;
  c.secondsLocalMeshes += d.secondsLocalMeshes;
  c.secondsRepair += d.secondsRepair;

  auto& i = whole.improve;
  const auto& j = part.improve;
  for (auto [a, b] : {std::pair{&i.badBefore, j.badBefore},
                      {&i.badAfter, j.badAfter},
                      {&i.swaps, j.swaps},
                      {&i.moves, j.moves},
                      {&i.collapses, j.collapses}})
    *a += b;
  i.passes = std::max(i.passes, j.passes);
  i.qMinBefore = std::min(i.qMinBefore, j.qMinBefore);
  i.qMinAfter = std::min(i.qMinAfter, j.qMinAfter);
  i.seconds += j.seconds;
  whole.secondsValidate += part.secondsValidate;
}

MeshOptions meshPreset(MeshPreset preset) {
  MeshOptions m;
  if (preset == MeshPreset::Mesh) return m;
  m.placement.plateauSteps = 10;
  m.placement.plateauGain = 0.01;
  if (preset == MeshPreset::Remesh) {
    m.placement.finalRelaxSteps = 0;
  } else {
    m.placement.lattice.orientation = LatticeOrientation::ShortAxis;
    m.placement.defectPasses = 0;
  }
  return m;
}

MeshPreset parseMeshPreset(const std::string& name) {
  if (name == "mesh") return MeshPreset::Mesh;
  if (name == "remesh") return MeshPreset::Remesh;
  if (name == "adapt") return MeshPreset::Adapt;
  ABLMG_REQUIRE(false, "mesher preset: expected mesh, remesh or adapt, got '" << name << "'");
  return MeshPreset::Mesh;
}

const char* meshPresetName(MeshPreset preset) {
  return preset == MeshPreset::Mesh ? "mesh" : preset == MeshPreset::Remesh ? "remesh" : "adapt";
}

MeshResult meshDomain(const Domain& domain, const MetricField& metric, const MeshOptions& options) {
  if (domain.hasSlits()) return meshSlitDomain(domain, metric, options);  // cut, meshed piece by piece
  const auto report = [&](const char* stage, long nodes) {
    if (options.progress) options.progress({.stage = stage, .nodes = nodes});
  };
  report("placement", -1);
  PlacementResult placement = placeNodes(domain, metric, options.placement, options.progress, options.progressEvery);
  report("connection", long(placement.nodes.positions.size()));
  ConnectResult connected = connect(placement, domain, options.connect);

  MeshResult result;
  result.stats.placement = placement.stats;
  result.stats.connect = connected.stats;
  result.metric.reserve(connected.nodeOfVertex.size());
  for (int node : connected.nodeOfVertex) result.metric.push_back(placement.metrics[node]);
  placement = {};  // the nodes, their lists and metrics are in the mesh now: freed before the post-pass
  // The quality post-pass (improve.hpp): moved vertices get the field's metric in result.metric;
  // a collapse removes a vertex from both the mesh and result.metric (they stay in step).
  if (options.improve.enabled) report("improve", connected.mesh.numVertices());
  if (options.improve.enabled)
    result.stats.improve = improveQuality(connected.mesh, result.metric, metric, options.improve);
  const ImproveStats& is = result.stats.improve;
  const bool improved = is.swaps + is.moves + is.collapses > 0;
  // Every mesh returned is valid: checked here unless connect() already checked this very mesh
  // and the post-pass left it as it was.
  const Stopwatch watch;
  if (!connected.validated || improved) report("validation", connected.mesh.numVertices());
  if (!connected.validated || improved)
    connected.mesh.requireValid("meshDomain", expectedArea(domain, connected.mesh), 1e-9);
  result.stats.secondsValidate = connected.secondsValidate + watch.seconds();
  result.mesh = std::move(connected.mesh);
  return result;
}

}  // namespace ablmg::mesher
