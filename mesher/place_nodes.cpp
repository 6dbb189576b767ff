#include "ablmg/mesher/place_nodes.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/core/stopwatch.hpp"
#include "ablmg/mesher/adjacency.hpp"
#include "ablmg/mesher/bubble_force.hpp"
#include "ablmg/mesher/bubble_system.hpp"
#include "ablmg/mesher/defects.hpp"
#include "ablmg/mesher/initial_placement.hpp"
#include "ablmg/mesher/placement_schedule.hpp"
#include "ablmg/mesher/population.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>

namespace ablmg::mesher {
namespace {

/// Nodes read by the share test of a defect pass (annealDefects); every node below twice this.
constexpr int kDefectSample = 1 << 17;

/// Restores the OpenMP thread count on scope exit.
struct ThreadScope {
  int saved;
  explicit ThreadScope(int n) : saved(omp_get_max_threads()) {
    if (n > 0) omp_set_num_threads(n);
  }
  ~ThreadScope() { omp_set_num_threads(saved); }
};

std::vector<BoundaryEdge> boundaryEdgesOf(const BubbleSystem& sys, const DomainGeometry& geo) {
  std::vector<BoundaryEdge> edges;
  const auto& nodes = sys.nodes();
  for (int l = 0; l < int(geo.loops().size()); ++l) {
    std::vector<int> ids;
    for (int i = 0; i < nodes.size(); ++i)
      if (nodes.loops[i] == l) ids.push_back(i);
    std::stable_sort(ids.begin(), ids.end(), [&](int a, int b) { return sys.arcLength(a) < sys.arcLength(b); });
    const auto& poly = geo.loops()[l];
    for (std::size_t k = 0; k < ids.size() && ids.size() >= 2; ++k) {
      const int a = ids[k], b = ids[(k + 1) % ids.size()];
      const double sa = sys.arcLength(a), sb = sys.arcLength(b);
      double span = sb - sa;
      if (span <= 0) span += poly.length;
      const int seg = geo.segmentAt(l, sa + 0.5 * span);
      edges.push_back({a, b, poly.tags[seg]});
    }
  }
  return edges;
}

/// Spreads the low 32 bits of v to the even bits of the result (Morton code helper).
std::uint64_t spreadBits(std::uint64_t v) {
  v &= 0xffffffffULL;
  v = (v | (v << 16)) & 0x0000ffff0000ffffULL;
  v = (v | (v << 8)) & 0x00ff00ff00ff00ffULL;
  v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0fULL;
  v = (v | (v << 2)) & 0x3333333333333333ULL;
  v = (v | (v << 1)) & 0x5555555555555555ULL;
  return v;
}

/// Reorders nodes first … size−1 along a Z-order (Morton) curve of their coordinates quantised
/// to 2²⁰ steps per axis of the bounding box, ties by previous index. The interior lattice is
/// grown breadth-first, which puts neighbours far apart in memory; in Z-order the force and
/// adjacency loops read mostly nearby memory (constant metric, 10⁶ nodes, 1 thread: dynamics
/// 15.1 s → 13.2 s). The fine quantisation keeps graded packings local too (a grid of one
/// node per cell on average left ~10² nodes per cell, in BFS order, where the metric is fine).
void zOrder(NodeSet& nodes, int first) {
  const int n = nodes.size();
  if (n - first < 2) return;
  Vec2 lo = nodes.positions[first], hi = lo;
  for (int i = first; i < n; ++i) {
    lo = lo.cwiseMin(nodes.positions[i]);
    hi = hi.cwiseMax(nodes.positions[i]);
  }
  const double cell = std::max((hi - lo).maxCoeff() / double(1 << 20), 1e-300);
  std::vector<std::pair<std::uint64_t, int>> key(std::size_t(n - first));
  const bool parallel = n - first >= kMinParallelItems;
#pragma omp parallel for schedule(static) if (parallel)
  for (int i = first; i < n; ++i) {
    const Vec2 q = (nodes.positions[i] - lo) / cell;
    const auto cx = std::uint64_t(std::clamp(q.x(), 0.0, 4e9)), cy = std::uint64_t(std::clamp(q.y(), 0.0, 4e9));
    key[std::size_t(i - first)] = {spreadBits(cx) | (spreadBits(cy) << 1), i};
  }
  // The keys are distinct (index ties): two halves sorted side by side and merged give the
  // one sorted order.
  const auto mid = key.begin() + std::ptrdiff_t(key.size() / 2);
#pragma omp parallel sections if (parallel)
  {
#pragma omp section
    std::sort(key.begin(), mid);
#pragma omp section
    std::sort(mid, key.end());
  }
  std::inplace_merge(key.begin(), mid, key.end());
  NodeSet old = nodes;
#pragma omp parallel for schedule(static) if (parallel)
  for (int k = 0; k < n - first; ++k) {
    const int from = key[std::size_t(k)].second, to = first + k;
    nodes.positions[to] = old.positions[from];
    nodes.kinds[to] = old.kinds[from];
    nodes.loops[to] = old.loops[from];
    nodes.arc[to] = old.arc[from];
  }
}

/// splitmix64 (Steele, Lea, Flood 2014): a counter-based generator, so the draw of node k
/// depends on (seed, k) only, not on the order or the thread that asks.
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double unitDraw(std::uint64_t seed, std::uint64_t counter) {
  return double(splitmix64(splitmix64(seed) ^ counter) >> 11) * 0x1.0p-53;  // [0, 1)
}

/// PlacementOptions::seed: each interior node first in [first, size) moves by a draw uniform
/// in the metric disk of radius kSeedJitter around it (node k's draw depends on (seed, k)
/// only); a move that would leave the domain or come within 0.5 metric units of its boundary
/// is not made. Seed 0 leaves the nodes where they are.
void jitterInterior(const DomainGeometry& geo, const MetricField& metric, NodeSet& nodes, int first,
                    std::uint64_t seed) {
  constexpr double kSeedJitter = 0.1;  // metric units: the dynamics relax it in a few steps
  const int n = nodes.size();
  if (seed == 0 || n <= first) return;
  std::vector<Vec2> pts(nodes.positions.begin() + first, nodes.positions.end());
  std::vector<Metric2> ms(pts.size());
  metric.evaluate(pts, ms);
  for (int i = first; i < n; ++i) {
    const std::size_t k = std::size_t(i - first);
    const double r = kSeedJitter * std::sqrt(unitDraw(seed, 2 * k)),
                 phi = 2 * std::numbers::pi * unitDraw(seed, 2 * k + 1);
    const MetricEigen e = ms[k].eigen();
    const Vec2 u(r * std::cos(phi) * e.h1, r * std::sin(phi) * e.h2);
    const double c = std::cos(e.theta), s = std::sin(e.theta);
    const Vec2 p = pts[k] + Vec2(c * u.x() - s * u.y(), s * u.x() + c * u.y());
    if (geo.inside(p) && geo.metricDistanceToBoundary(p, ms[k], reachBox(ms[k], 0.5)) >= 0.5) nodes.positions[i] = p;
  }
}

/// Share of neighbour pairs (w < 1.3, w the force's pair distance, bubble_force.hpp) whose
/// w is within ±10 % of 1: the packing's edge-length statistic, cheap enough every 10 steps.
/// Integer counts: deterministic for any thread count.
double unitPairShare(const BubbleSystem& sys, const AdjacencyLists& adj, PairDistance kind) {
  const auto& x = sys.nodes().positions;
  const auto& m = sys.metrics();
  const int n = sys.size();
  long near = 0, unit = 0;
#pragma omp parallel for schedule(static) reduction(+ : near, unit) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i)
    for (int j : adj.neighbours(i)) {
      if (j <= i) continue;
      const Vec2 d = x[j] - x[i];
      const double a2 = m[i].squaredLength(d), b2 = m[j].squaredLength(d);
      if (!(a2 > 0 && b2 > 0)) continue;
      const double w = pairDistance(a2, b2, kind);
      if (w >= 1.3) continue;
      ++near;
      unit += std::abs(w - 1.0) <= 0.1;
    }
  return near > 0 ? double(unit) / double(near) : 1.0;
}

/// The §3 driver: initial placement, then per step the stop rules, one dynamics step, a
/// population pass when due and the adjacency upkeep; then the output. The schedules and stop
/// rules are placement_schedule.hpp's; this class only holds the state they act on.
class NodePlacer {
 public:
  NodePlacer(const Domain& domain, const MetricField& metric, const PlacementOptions& options,
             const ProgressCallback& progress, int progressEvery);
  PlacementResult run();

 private:
  BubbleSystem initialBubbles(const Domain& domain);
  void startDynamics();
  bool keepGoing(int step);  ///< the stop rules at the start of a step; false: stop now
  bool convergedWithEveryBubbleAwake();
  bool annealDefects(int step);
  bool stopEarly(int step);
  void advance();
  void populationPass(int step);
  void keepAdjacency(int done);
  PlacementResult output();

  const PlacementOptions& o_;
  const MetricField& metric_;
  DomainGeometry geo_;
  PlacementResult result_;
  PlacementStats& st_ = result_.stats;
  BubbleSystem sys_;
  AdjacencyLists adj_;
  DynamicsParams p_;
  PopulationSchedule population_;
  DefectSchedule defects_;
  StallRule stall_;
  QualityPlateau plateau_;
  RelaxBeforeStop relax_;
  bool constant_;
  double residual_ = 0, target_ = 0, sleepBelow_ = 0;
  bool allAwake_ = true;              ///< the last residual covers every bubble
  long fixedCount_ = 0;               ///< Vertex bubbles: never awake
  const ProgressCallback& progress_;  ///< reports every progressEvery_ steps (may be empty)
  int progressEvery_;
};

NodePlacer::NodePlacer(const Domain& domain, const MetricField& metric, const PlacementOptions& options,
                       const ProgressCallback& progress, int progressEvery)
    : o_(options),
      metric_(metric),
      geo_(domain),
      sys_(initialBubbles(domain)),
      p_{options.k0, options.mass, options.damping, options.timeStep, options.pairDistance},
      population_(st_.predictedNodes, options.maxSteps),
      defects_(options.defectPasses, options.defectEvery),
      stall_(options.stallSteps),
      plateau_(options.plateauSteps, options.plateauGain),
      relax_(options.finalRelaxSteps),
      constant_(metric.isConstant()),
      progress_(progress),
      progressEvery_(progressEvery) {
  startDynamics();
}

/// 1. Initial placement (§3.1), after checking the predicted size.
BubbleSystem NodePlacer::initialBubbles(const Domain& domain) {
  ScopedTimer timer{st_.secondsInitial};
  const int holes = int(domain.loops().size()) - 1;
  const double coarse = 2.0 / std::sqrt(3.0) * metricArea(domain, geo_, metric_, 64);
  if (!(coarse <= double(o_.maxNodes))) {  // as an integer only where one holds it (h = 1e-12: ~1e24)
    char count[32];
    if (coarse < 1e18)
      std::snprintf(count, sizeof count, "%lld", std::llround(coarse));
    else
      std::snprintf(count, sizeof count, "%.3g", coarse);
    ABLMG_REQUIRE(false,
                  "placeNodes: the metric asks for about " << count << " nodes, more than maxNodes = " << o_.maxNodes);
  }
  const double areaM = metricArea(domain, geo_, metric_, 256);
  NodeSet nodes;
  std::vector<double> arc;
  placeBoundaryNodes(geo_, metric_, nodes, arc);
  st_.predictedNodes = predictedNodeCount(areaM, nodes.size(), holes);
  ABLMG_REQUIRE(st_.predictedNodes <= o_.maxNodes,
                "placeNodes: predicted node count " << st_.predictedNodes << " exceeds maxNodes = " << o_.maxNodes);
  const double spacing = std::sqrt(domain.area() / std::max<double>(st_.predictedNodes, 1.0));
  const int firstInterior = nodes.size();
  placeInteriorNodes(geo_, metric_, nodes, spacing, o_.lattice, o_.warmStart);
  jitterInterior(geo_, metric_, nodes, firstInterior, o_.seed);
  zOrder(nodes, firstInterior);
  arc.resize(nodes.size(), -1.0);
  BubbleSystem sys(geo_, std::move(nodes), std::move(arc));
  sys.updateMetrics(metric_);
  st_.initialNodes = sys.size();
  return sys;
}

/// The lists, the first forces and the convergence target.
void NodePlacer::startDynamics() {
  {
    ScopedTimer timer{st_.secondsAdjacency};
    adj_ = buildAdjacency(sys_.nodes().positions, sys_.metrics(), o_.adjacencyRadius);
    sys_.clearMoved();
  }
  {
    ScopedTimer timer{st_.secondsDynamics};
    residual_ = sys_.computeForces(adj_, p_);
  }
  st_.initialResidual = residual_;
  // Converged: the residual dropped by relativeTolerance (100× by default) or below tolerance.
  // A warm start begins near equilibrium, so its own initial residual is no yardstick (×100
  // below an already small residual is polishing that can stall): it is measured against a
  // fresh lattice's, which is 0.5–0.7 on the paper disks (kLatticeResidual).
  constexpr double kLatticeResidual = 0.5;
  const double reference = o_.warmStart.empty() ? st_.initialResidual : std::max(st_.initialResidual, kLatticeResidual);
  target_ = std::max(o_.tolerance, o_.relativeTolerance * reference);
  sleepBelow_ = 0.5 * target_;  // active set: see BubbleSystem::updateActivity
  for (int i = 0; i < sys_.size(); ++i) fixedCount_ += sys_.nodes().kinds[i] == NodeKind::Vertex;
}

/// 2. Dynamics (§3.2) interleaved with population control (§3.4), then 3. the output.
PlacementResult NodePlacer::run() {
  for (int step = 0; step < o_.maxSteps; ++step) {
    if (relax_.over(step)) break;
    if (step > 0) {
      ScopedTimer timer{st_.secondsDynamics};
      residual_ = sys_.computeForces(adj_, p_);
    }
    if (progress_ && step % progressEvery_ == 0)
      progress_(
          {.stage = "placement", .step = step, .residual = residual_, .target = target_, .nodes = long(sys_.size())});
    if (!keepGoing(step)) break;
    advance();
    populationPass(step);
    keepAdjacency(step + 1);
  }
  return output();
}

/// Convergence (with the defect passes it may start), then the stall and plateau rules.
bool NodePlacer::keepGoing(int step) {
  if (residual_ < target_ && population_.settled()) {
    if (convergedWithEveryBubbleAwake() && !(defects_.left() && annealDefects(step))) return false;
  } else if (population_.settled() && defects_.due(step)) {
    annealDefects(step);
  }
  if (stall_.enabled() && !relax_.relaxing() && stall_.stalled(step, residual_)) {
    st_.stalled = true;
    if (stopEarly(step)) return false;
  }
  if (plateau_.sampleDue(step) && !relax_.relaxing()) {
    double share;
    {
      ScopedTimer timer{st_.secondsDynamics};
      share = unitPairShare(sys_, adj_, o_.pairDistance);
    }
    if (plateau_.reached(share, population_.settled() || population_.nearlySettled(), step - stall_.markStep())) {
      st_.qualityPlateau = true;
      if (stopEarly(step)) return false;
    }
  }
  return true;
}

/// The active-set residual skips sleepers (each ≤ sleepBelow when it fell asleep, but small
/// neighbour moves may have loaded it since): converged only when every bubble agrees.
bool NodePlacer::convergedWithEveryBubbleAwake() {
  if (allAwake_) return true;
  ScopedTimer timer{st_.secondsDynamics};
  sys_.wakeAll();
  residual_ = sys_.computeForces(adj_, p_);
  allAwake_ = true;
  return residual_ < target_;
}

/// One defect-annealing pass (defects.hpp): kicks the defects' neighbourhoods, after which the
/// run goes on (stall mark restarted). False when nothing was kicked (no pass is left then).
bool NodePlacer::annealDefects(int step) {
  ScopedTimer timer{st_.secondsDefects};
  defects_.started(step);
  // The lists hold every pair within 1.5 (see keepAdjacency); Voronoi neighbours of a packing
  // are within ~1.3. Above 2·kDefectSample nodes the share test reads a sample of them (every
  // stride-th in Z-order, spread over the domain) and the whole topology is built only for a
  // pass: a settled 5·10⁶-node packing spent 10 % of its remesh on a test that kicked nothing.
  const NodeSet& nodes = sys_.nodes();
  const int stride = std::max(1, nodes.size() / kDefectSample);
  LocalTopology topo = localTopology(nodes.positions, sys_.metrics(), nodes.kinds, adj_, 0.05, stride);
  DefectCounts dc = countDefects(topo);
  bool kick = double(dc.total()) > o_.defectMinShare * double(dc.interior);
  long defects = dc.total() * stride;  // the sample's estimate
  if (kick && stride > 1) {
    topo = localTopology(nodes.positions, sys_.metrics(), nodes.kinds, adj_);
    dc = countDefects(topo);
    kick = double(dc.total()) > o_.defectMinShare * double(dc.interior);
    defects = dc.total();
  }
  if (st_.defectsFirst < 0) st_.defectsFirst = defects;
  st_.defectsLast = defects;
  long moved = 0;
  if (kick) {
    moved = shakeNodes(sys_, geo_, defectNeighbourhood(topo, 1), o_.defectShake, st_.defectPasses);
    ++st_.defectPasses;
  }
  if (moved == 0) {
    defects_.stop();
    return false;
  }
  relax_.edited(step);
  adj_ = buildAdjacency(sys_.nodes().positions, sys_.metrics(), o_.adjacencyRadius);
  sys_.clearMoved();
  sys_.wakeAll();
  residual_ = sys_.computeForces(adj_, p_);
  allAwake_ = true;
  stall_.restart();
  return true;
}

/// An early stop (stall, plateau) asked at `step`: now, or after the relaxation since the last
/// edit, with no population or defect pass in between.
bool NodePlacer::stopEarly(int step) {
  if (relax_.allowsStop(step)) return true;
  population_.settle();
  defects_.stop();
  return false;
}

void NodePlacer::advance() {
  ScopedTimer timer{st_.secondsDynamics};
  sys_.advance(p_);
  if (!constant_) sys_.updateMetrics(metric_, false, o_.metricLag);
  const long awake = sys_.updateActivity(adj_, sleepBelow_, o_.timeStep);
  st_.activeBubbleSteps += awake;
  allAwake_ = awake == sys_.size() - fixedCount_;
  ++st_.steps;
}

/// The lists are exact for forces and eq. (9) (both reach w = 1.5 only) while no bubble has
/// travelled (radius − 1.5)/2 since the last refresh: keepAdjacency checks that after every
/// step, so a population pass needs no refresh of its own, only the patch of its edits.
void NodePlacer::populationPass(int step) {
  const int done = step + 1;
  if (population_.passDue(done)) {
    PopulationChange c;
    {
      ScopedTimer timer{st_.secondsPopulation};
      c = adjustPopulation(sys_, adj_, geo_, metric_, population_.options());
    }
    st_.inserted += c.inserted;
    st_.deleted += c.deleted;
    if (c.inserted + c.deleted > 0) {
      relax_.edited(step);
      ScopedTimer timer{st_.secondsAdjacency};
      adj_ = patchAdjacency(adj_, c.map, c.firstNew, sys_.referencePositions(), sys_.metrics(), o_.adjacencyRadius);
    }
    population_.afterPass(c.inserted + c.deleted, sys_.size());
  }
  population_.afterStep(done);
}

/// Refresh every adjacencyRefresh steps (§3.3), or earlier once some bubble has travelled more
/// than the margin from its reference position: then only the rows of those bubbles (unless
/// they are many), which get their current positions as new references. Between full
/// refreshes the lists are the radius-lists of the reference positions (every local update and
/// the population patch test pairs at reference positions; a full refresh makes them current),
/// so a pair outside them is now more than radius − 2·margin = 1.5 apart: out of force range,
/// up to the change of the metrics along the way (a few % of a length per 0.1 of travel under
/// hgrad 1.3; f(1.45) = −0.06).
void NodePlacer::keepAdjacency(int done) {
  const double margin = 0.5 * (o_.adjacencyRadius - 1.5);
  const bool periodic = done % std::max(1, o_.adjacencyRefresh) == 0;
  if (!periodic && sys_.maxTravelSinceRefresh() <= margin) return;
  ScopedTimer timer{st_.secondsAdjacency};
  std::vector<int> far;
  if (!periodic) far = sys_.travellers(margin);
  if (!periodic && 4 * far.size() < std::size_t(sys_.size())) {
    sys_.resetTravel(far);
    refreshAdjacencyAround(adj_, sys_.referencePositions(), sys_.metrics(), o_.adjacencyRadius, far);
  } else {
    refreshAdjacencyInPlace(adj_, sys_.nodes().positions, sys_.metrics(), o_.adjacencyRadius, sys_.movedSinceRefresh());
    sys_.clearMoved();
  }
}

/// 3. The exact metrics, the final lists (a two-ring refresh when the lists are still close:
/// every pair within the radius is then in it; a full rebuild otherwise), distinct nodes, the
/// boundary edges.
PlacementResult NodePlacer::output() {
  {
    ScopedTimer timer{st_.secondsDynamics};
    sys_.wakeAll();  // the final residual covers every bubble
    st_.finalResidual = sys_.computeForces(adj_, p_);
  }
  st_.hitStepCap = st_.steps >= o_.maxSteps && st_.finalResidual >= target_;
  {
    ScopedTimer timer{st_.secondsAdjacency};
    sys_.updateMetrics(metric_);
    // In place: the dynamics' lists are not needed after this, and a copy of them was the
    // placement's peak memory at 10⁶ triangles.
    if (sys_.maxTravelSinceRefresh() < 0.5 * (o_.adjacencyRadius - 1.5)) {
      refreshAdjacencyInPlace(adj_, sys_.nodes().positions, sys_.metrics(), o_.adjacencyRadius);
      adj_.compact();
      result_.adjacency = std::move(adj_);
    } else {
      adj_ = {};
      result_.adjacency = buildAdjacency(sys_.nodes().positions, sys_.metrics(), o_.adjacencyRadius);
    }
    // No two nodes share a point (node_set.hpp): the chains keep their boundary nodes apart by
    // construction (bubble_system.hpp); bubbles that came to rest on one point are merged here.
    std::vector<char> drop;
    st_.coincidentDropped = coincidentNodes(sys_.nodes(), result_.adjacency, drop);
    if (st_.coincidentDropped > 0) {
      sys_.remove(drop, true);
      result_.adjacency = buildAdjacency(sys_.nodes().positions, sys_.metrics(), o_.adjacencyRadius);
    }
  }
  result_.boundaryEdges = boundaryEdgesOf(sys_, geo_);
  result_.metrics = sys_.metrics();
  result_.nodes = sys_.nodes();
  st_.finalNodes = result_.nodes.size();
  st_.nearestInRange = nearestNeighbourShare(result_);
  return std::move(result_);
}

}  // namespace

void validate(const PlacementOptions& o) {
  auto need = [](bool ok, const char* field, const char* rule, double value) {
    ABLMG_REQUIRE(ok, "placement options: " << field << " must be " << rule << ", got " << value);
  };
  need(o.k0 > 0, "k0", "> 0", o.k0);
  need(o.mass > 0, "mass", "> 0", o.mass);
  need(o.damping >= 0, "damping", ">= 0", o.damping);
  need(o.timeStep > 0, "timeStep", "> 0", o.timeStep);
  need(o.adjacencyRadius >= 1.5, "adjacencyRadius", ">= 1.5 (the force's range)", o.adjacencyRadius);
  need(o.adjacencyRefresh >= 1, "adjacencyRefresh", ">= 1", o.adjacencyRefresh);
  need(o.maxSteps >= 0, "maxSteps", ">= 0", o.maxSteps);
  need(o.tolerance >= 0, "tolerance", ">= 0", o.tolerance);
  need(o.relativeTolerance >= 0, "relativeTolerance", ">= 0", o.relativeTolerance);
  need(o.stallSteps >= 0, "stallSteps", ">= 0 (0 = off)", o.stallSteps);
  need(o.plateauSteps >= 0, "plateauSteps", ">= 0 (0 = off)", o.plateauSteps);
  need(o.plateauGain >= 0, "plateauGain", ">= 0", o.plateauGain);
  need(o.finalRelaxSteps >= 0, "finalRelaxSteps", ">= 0", o.finalRelaxSteps);
  need(o.metricLag >= 0 && o.metricLag <= 0.5, "metricLag", "in [0, 0.5] (metric units)", o.metricLag);
  need(o.defectPasses >= 0, "defectPasses", ">= 0 (0 = off)", o.defectPasses);
  need(o.defectEvery >= 1, "defectEvery", ">= 1", o.defectEvery);
  need(o.defectShake >= 0 && o.defectShake <= 0.5, "defectShake", "in [0, 0.5] (metric units)", o.defectShake);
  need(o.defectMinShare >= 0, "defectMinShare", ">= 0", o.defectMinShare);
  need(o.maxNodes >= 1, "maxNodes", ">= 1", double(o.maxNodes));
  need(o.threads >= 0, "threads", ">= 0 (0 = OpenMP's default)", o.threads);
}

PlacementResult placeNodes(const Domain& domain, const MetricField& metric, const PlacementOptions& options,
                           const ProgressCallback& progress, int progressEvery) {
  validate(options);
  ThreadScope threads(options.threads);
  return NodePlacer(domain, metric, options, progress, std::max(1, progressEvery)).run();
}

double nearestNeighbourShare(const PlacementResult& r, double lo, double hi) {
  long interior = 0, inRange = 0;
  const int n = r.nodes.size();
#pragma omp parallel for schedule(static) reduction(+ : interior, inRange) if (n >= kMinParallelItems)
  for (int i = 0; i < n; ++i) {
    if (r.nodes.kinds[i] != NodeKind::Interior) continue;
    double best = std::numeric_limits<double>::infinity();
    for (int j : r.adjacency.neighbours(i)) {
      const Vec2 d = r.nodes.positions[j] - r.nodes.positions[i];
      best = std::min(best, r.metrics[i].squaredLength(d) + r.metrics[j].squaredLength(d));
    }
    const double l = std::sqrt(0.5 * best);
    ++interior;
    inRange += l >= lo && l <= hi;
  }
  return interior == 0 ? 1.0 : double(inRange) / double(interior);
}

}  // namespace ablmg::mesher
