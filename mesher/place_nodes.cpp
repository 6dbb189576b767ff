#include "ablmg/mesher/place_nodes.hpp"
#include "ablmg/mesher/parallel_threshold.hpp"

#include "ablmg/core/error.hpp"
#include "ablmg/mesher/adjacency.hpp"
#include "ablmg/mesher/bubble_force.hpp"
#include "ablmg/mesher/bubble_system.hpp"
#include "ablmg/mesher/defects.hpp"
#include "ablmg/mesher/initial_placement.hpp"
#include "ablmg/mesher/population.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

namespace ablmg::mesher {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

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
  for (int i = first; i < n; ++i) {
    const Vec2 q = (nodes.positions[i] - lo) / cell;
    const auto cx = std::uint64_t(std::clamp(q.x(), 0.0, 4e9)), cy = std::uint64_t(std::clamp(q.y(), 0.0, 4e9));
    key[std::size_t(i - first)] = {spreadBits(cx) | (spreadBits(cy) << 1), i};
  }
  std::sort(key.begin(), key.end());
  NodeSet old = nodes;
  for (int k = 0; k < n - first; ++k) {
    const int from = key[std::size_t(k)].second, to = first + k;
    nodes.positions[to] = old.positions[from];
    nodes.kinds[to] = old.kinds[from];
    nodes.loops[to] = old.loops[from];
    nodes.arc[to] = old.arc[from];
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

}  // namespace

PlacementResult placeNodes(const Domain& domain, const MetricField& metric, const PlacementOptions& options,
                           const ProgressCallback& progress, int progressEvery) {
  ABLMG_REQUIRE(options.timeStep > 0 && options.mass > 0 && options.damping >= 0,
                "placeNodes: need timeStep > 0, mass > 0, damping >= 0; got "
                    << options.timeStep << ", " << options.mass << ", " << options.damping);
  ABLMG_REQUIRE(options.metricLag >= 0 && options.metricLag <= 0.5,
                "placeNodes: metricLag must be in [0, 0.5] (metric units), got " << options.metricLag);
  ABLMG_REQUIRE(options.finalRelaxSteps >= 0,
                "placeNodes: finalRelaxSteps must be >= 0, got " << options.finalRelaxSteps);
  ABLMG_REQUIRE(options.plateauSteps >= 0 && options.plateauGain >= 0,
                "placeNodes: need plateauSteps >= 0 and plateauGain >= 0; got " << options.plateauSteps << ", "
                                                                                << options.plateauGain);
  ABLMG_REQUIRE(options.adjacencyRadius >= 1.5,
                "placeNodes: adjacencyRadius must be >= 1.5 (force range), got " << options.adjacencyRadius);
  ABLMG_REQUIRE(
      options.defectPasses >= 0 && options.defectEvery >= 1 && options.defectShake >= 0 && options.defectShake <= 0.5,
      "placeNodes: need defectPasses >= 0, defectEvery >= 1, defectShake in [0, 0.5]; got "
          << options.defectPasses << ", " << options.defectEvery << ", " << options.defectShake);
  ThreadScope threads(options.threads);
  PlacementResult result;
  PlacementStats& st = result.stats;

  // 1. Initial placement (§3.1), after checking the predicted size.
  auto t = Clock::now();
  DomainGeometry geo(domain);
  const int holes = int(domain.loops().size()) - 1;
  {
    const double coarse = 2.0 / std::sqrt(3.0) * metricArea(domain, geo, metric, 64);
    ABLMG_REQUIRE(coarse <= double(options.maxNodes), "placeNodes: the metric asks for about "
                                                          << long(coarse)
                                                          << " nodes, more than maxNodes = " << options.maxNodes);
  }
  const double areaM = metricArea(domain, geo, metric, 256);
  NodeSet nodes;
  std::vector<double> arc;
  placeBoundaryNodes(geo, metric, nodes, arc);
  st.predictedNodes = predictedNodeCount(areaM, nodes.size(), holes);
  ABLMG_REQUIRE(st.predictedNodes <= options.maxNodes,
                "placeNodes: predicted node count " << st.predictedNodes << " exceeds maxNodes = " << options.maxNodes);
  const double spacing = std::sqrt(domain.area() / std::max<double>(st.predictedNodes, 1.0));
  const int firstInterior = nodes.size();
  placeInteriorNodes(geo, metric, nodes, spacing, options.lattice, options.warmStart);
  zOrder(nodes, firstInterior);
  arc.resize(nodes.size(), -1.0);
  BubbleSystem sys(geo, std::move(nodes), std::move(arc));
  sys.updateMetrics(metric);
  st.initialNodes = sys.size();
  st.secondsInitial = since(t);

  t = Clock::now();
  AdjacencyLists adj = buildAdjacency(sys.nodes().positions, sys.metrics(), options.adjacencyRadius);
  sys.clearMoved();
  st.secondsAdjacency += since(t);

  // 2. Dynamics (§3.2) interleaved with population control (§3.4).
  const DynamicsParams p{options.k0, options.mass, options.damping, options.timeStep, options.pairDistance};
  PopulationOptions pop;
  pop.target = st.predictedNodes;
  const int popEvery = 10;
  const int popUntil = std::max(popEvery, int(0.6 * options.maxSteps));
  int quietPasses = 0;
  std::vector<int> passCounts;  // node count after each population pass
  double stallMark = 0;
  int stallMarkStep = -1;
  std::vector<double> shares;  // quality-plateau samples, one per 10 steps
  bool populationSettled = false;
  bool plateauMayStart = false;  // the last population pass edited ≤ 0.2 % of the nodes

  const bool constant = metric.isConstant();
  t = Clock::now();
  double residual = sys.computeForces(adj, p);
  st.secondsDynamics += since(t);
  st.initialResidual = residual;
  // Converged: the residual dropped by relativeTolerance (100× by default) or below tolerance.
  // A warm start begins near equilibrium, so its own initial residual is no yardstick (×100
  // below an already small residual is polishing that can stall): it is measured against a
  // fresh lattice's, which is 0.5–0.7 on the paper disks (kLatticeResidual).
  constexpr double kLatticeResidual = 0.5;
  const double reference =
      options.warmStart.empty() ? st.initialResidual : std::max(st.initialResidual, kLatticeResidual);
  const double target = std::max(options.tolerance, options.relativeTolerance * reference);
  const double sleepBelow = 0.5 * target;  // active set: see BubbleSystem::updateActivity
  bool allAwake = true;                    // the last residual covers every bubble
  long fixedCount = 0;                     // Vertex bubbles: never awake
  for (int i = 0; i < sys.size(); ++i) fixedCount += sys.nodes().kinds[i] == NodeKind::Vertex;
  // Defect annealing (defects.hpp): the first pass once the population has settled, the next
  // ones every defectEvery steps (or at convergence, if that comes first); a pass kicks the
  // defects' neighbourhoods and the run goes on (stall marks restarted). Returns false when
  // nothing was kicked (no pass is left then). Starting at the settled population rather than
  // at convergence: the same edge statistics for ~25 % fewer steps (ring 273–404 instead of
  // 433–478).
  int defectPassesLeft = options.defectPasses;
  int lastEdit = -1;  // step after which the last population edit or defect kick was made
  int stopAt = -1;    // ≥ 0: relaxing before an early stop, which comes at this step
  int lastDefectStep = -1;
  auto annealDefects = [&](int step) {
    t = Clock::now();
    --defectPassesLeft;
    lastDefectStep = step;
    // The lists hold every pair within 1.5 (see the refresh rule below); Voronoi neighbours
    // of a packing are within ~1.3.
    const LocalTopology topo = localTopology(sys.nodes().positions, sys.metrics(), sys.nodes().kinds, adj);
    const DefectCounts dc = countDefects(topo);
    if (st.defectsFirst < 0) st.defectsFirst = dc.total();
    st.defectsLast = dc.total();
    long moved = 0;
    if (double(dc.total()) > options.defectMinShare * double(dc.interior)) {
      moved = shakeNodes(sys, geo, defectNeighbourhood(topo, 1), options.defectShake, st.defectPasses);
      ++st.defectPasses;
    }
    if (moved > 0) {
      lastEdit = step;
      adj = buildAdjacency(sys.nodes().positions, sys.metrics(), options.adjacencyRadius);
      sys.clearMoved();
      sys.wakeAll();
      residual = sys.computeForces(adj, p);
      allAwake = true;
      stallMarkStep = -1;
    } else {
      defectPassesLeft = 0;
    }
    st.secondsDefects += since(t);
    return moved > 0;
  };
  // Early stops (stall, plateau) never cut off right after an edit: the nodes just inserted,
  // the holes of the ones just deleted and the kicked neighbourhoods get finalRelaxSteps
  // steps without further edits first (stopAt).
  auto stopEarly = [&](int step) {
    if (lastEdit < 0 || step - lastEdit >= options.finalRelaxSteps) return true;
    stopAt = lastEdit + options.finalRelaxSteps;
    populationSettled = true;  // no more population passes
    defectPassesLeft = 0;
    return false;
  };
  for (int step = 0; step < options.maxSteps; ++step) {
    if (stopAt >= 0 && step >= stopAt) break;
    if (step > 0) {
      t = Clock::now();
      residual = sys.computeForces(adj, p);
      st.secondsDynamics += since(t);
    }
    if (progress && step % std::max(1, progressEvery) == 0)
      progress({.stage = "placement", .step = step, .residual = residual, .target = target, .nodes = long(sys.size())});
    if (residual < target && populationSettled) {
      // The active-set residual skips sleepers (each ≤ sleepBelow when it fell asleep, but
      // small neighbour moves may have loaded it since): stop only when every bubble agrees.
      bool converged = allAwake;
      if (!converged) {
        t = Clock::now();
        sys.wakeAll();
        residual = sys.computeForces(adj, p);
        allAwake = true;
        st.secondsDynamics += since(t);
        converged = residual < target;
      }
      if (converged && !(defectPassesLeft > 0 && annealDefects(step))) break;
    } else if (populationSettled && defectPassesLeft > 0 &&
               (lastDefectStep < 0 || step - lastDefectStep >= options.defectEvery)) {
      annealDefects(step);
    }
    // Stall rule: the residual must halve within stallSteps steps of each mark, else the run
    // stops (some metrics from solvers have no equilibrium within tolerance: a few bubbles
    // where M varies by ~100 % per metric unit keep jolting). Population passes go on meanwhile.
    if (options.stallSteps > 0 && stopAt < 0) {
      if (stallMarkStep < 0 || residual < 0.5 * stallMark) {
        stallMark = residual;
        stallMarkStep = step;
      } else if (step - stallMarkStep >= options.stallSteps) {
        st.stalled = true;
        if (stopEarly(step)) break;
      }
    }
    // Quality plateau (the paper's "less simulation when lower quality is acceptable"): the
    // share of neighbour pairs within ±10 % of unit length is sampled every 10 steps; once the
    // population is (nearly) settled, a share that gained < plateauGain over the last
    // plateauSteps steps, while the residual has not halved either, means more steps would
    // only polish a stuck packing.
    if (options.plateauSteps > 0 && step % 10 == 0 && stopAt < 0) {
      t = Clock::now();
      shares.push_back(unitPairShare(sys, adj, options.pairDistance));
      st.secondsDynamics += since(t);
      const int back = (options.plateauSteps + 9) / 10;  // window in samples
      if ((populationSettled || plateauMayStart) && int(shares.size()) > back &&
          shares.back() - shares[shares.size() - 1 - std::size_t(back)] < options.plateauGain &&
          step - stallMarkStep >= options.plateauSteps) {
        st.qualityPlateau = true;
        if (stopEarly(step)) break;
      }
    }
    t = Clock::now();
    sys.advance(p);
    if (!constant) sys.updateMetrics(metric, false, options.metricLag);
    const long awake = sys.updateActivity(adj, sleepBelow, options.timeStep);
    st.activeBubbleSteps += awake;
    allAwake = awake == sys.size() - fixedCount;
    ++st.steps;
    st.secondsDynamics += since(t);

    const int done = step + 1;
    // The lists are exact for forces and eq. (9) (both reach w = 1.5 only) while no bubble has
    // travelled (radius − 1.5)/2 since the last refresh: checked below after every step, so a
    // population pass needs no refresh of its own.
    if (!populationSettled && done % popEvery == 0) {
      t = Clock::now();
      const PopulationChange c = adjustPopulation(sys, adj, geo, metric, pop);
      st.inserted += c.inserted;
      st.deleted += c.deleted;
      st.secondsPopulation += since(t);
      if (c.inserted + c.deleted > 0) {
        lastEdit = step;
        t = Clock::now();
        adj = patchAdjacency(adj, c.map, c.firstNew, sys.referencePositions(), sys.metrics(), options.adjacencyRadius);
        st.secondsAdjacency += since(t);
      }
      // Settled after two passes in a row that change at most 1 node in 10⁴ (large graded
      // runs otherwise keep editing 1–3 nodes per pass, each edit jolting its neighbourhood,
      // for hundreds of steps).
      // Steering up ends once the count has not grown over steerWindow passes (population.hpp).
      passCounts.push_back(sys.size());
      const std::size_t w = std::size_t(std::max(1, pop.steerWindow));
      if (passCounts.size() > w && passCounts.back() <= passCounts[passCounts.size() - 1 - w]) pop.steerUp = false;
      plateauMayStart = double(c.inserted + c.deleted) <= 2e-3 * sys.size();
      if (double(c.inserted + c.deleted) <= 1e-4 * sys.size()) {
        if (++quietPasses >= 2) populationSettled = true;
      } else {
        quietPasses = 0;
      }
    }
    if (!populationSettled && done >= popUntil) populationSettled = true;
    // Refresh every k steps (§3.3), or earlier once some bubble has travelled more than the
    // margin from its reference position: then only the rows of those bubbles (unless they are
    // many), which get their current positions as new references. Between full refreshes the
    // lists are the radius-lists of the reference positions (every local update and the
    // population patch test pairs at reference positions; a full refresh makes them current),
    // so a pair outside them is now more than radius − 2·margin = 1.5 apart: out of force
    // range, up to the change of the metrics along the way (a few % of a length per 0.1 of
    // travel under hgrad 1.3; f(1.45) = −0.06). Refreshing only the bubbles past the margin,
    // not those past 0.7 of it as before, recomputes 25 % fewer rows on the ring remesh
    // (2.1·10⁵ in 60 steps). Early in a graded run this fires every step.
    const double margin = 0.5 * (options.adjacencyRadius - 1.5);
    const bool periodic = done % std::max(1, options.adjacencyRefresh) == 0;
    if (periodic || sys.maxTravelSinceRefresh() > margin) {
      t = Clock::now();
      std::vector<int> far;
      if (!periodic) far = sys.travellers(margin);
      if (!periodic && 4 * far.size() < std::size_t(sys.size())) {
        sys.resetTravel(far);
        refreshAdjacencyAround(adj, sys.referencePositions(), sys.metrics(), options.adjacencyRadius, far);
      } else {
        refreshAdjacencyInPlace(adj, sys.nodes().positions, sys.metrics(), options.adjacencyRadius,
                                sys.movedSinceRefresh());
        sys.clearMoved();
      }
      st.secondsAdjacency += since(t);
    }
  }
  t = Clock::now();
  sys.wakeAll();  // the final residual covers every bubble
  st.finalResidual = sys.computeForces(adj, p);
  st.secondsDynamics += since(t);
  st.hitStepCap = st.steps >= options.maxSteps && st.finalResidual >= target;

  // 3. Output.
  t = Clock::now();
  sys.updateMetrics(metric);
  // Two-ring refresh when the lists are still close (every pair within the radius is then in
  // it), a full rebuild otherwise.
  if (sys.maxTravelSinceRefresh() < 0.5 * (options.adjacencyRadius - 1.5))
    result.adjacency = refreshAdjacency(adj, sys.nodes().positions, sys.metrics(), options.adjacencyRadius);
  else
    result.adjacency = buildAdjacency(sys.nodes().positions, sys.metrics(), options.adjacencyRadius);
  st.secondsAdjacency += since(t);
  result.boundaryEdges = boundaryEdgesOf(sys, geo);
  result.metrics = sys.metrics();
  result.nodes = sys.nodes();
  st.finalNodes = result.nodes.size();
  st.nearestInRange = nearestNeighbourShare(result);
  return result;
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
