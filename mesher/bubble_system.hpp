#pragma once
/// The bubble system of paper §3.2: state and one forward-Euler step of m ẍ + c ẋ = f (eq. 5).
///
/// Units. The force of eq. (6)–(7) acts in metric-scaled length: the pair force on i is
///   F_ij = −f(w_ij) · l0_ij · (x_j − x_i)/|x_j − x_i|,   w = l / l0,
/// i.e. f(w) metric units of displacement expressed in coordinates through the pair's rest
/// length l0 (one metric unit in that direction). Positions and velocities are stored in
/// coordinates, so Δt, m, c, k0 are dimensionless and the §6 defaults work for any size h.
/// In metric terms eq. (8)'s w = 2 / (1/|d|_{M_i} + 1/|d|_{M_j}), or optionally the eq. (3)
/// length with the averaged tensor (pairDistance, bubble_force.hpp); no trigonometry.
///
/// Constraints: Vertex nodes never move; Segment nodes feel only the bubbles of their own loop piece
/// (the boundary is packed as a 1D chain first, so boundary edges keep unit metric length
/// instead of being dragged by the interior: sliding under interior forces left boundary
/// edges in [0.79, 1.28] on the disk), keep only the tangential part of their
/// velocity and slide along their loop's polyline by arc length, clamped strictly between the
/// two corners around them (corner-less loops wrap); an Interior node's move that would leave
/// the domain is rejected (position kept, velocity zeroed), so no bubble ever leaves it.
///
/// Residual: the largest net force |F_i|_{M_i} (metric units) over movable nodes (tangential
/// part for Segment nodes), before the step; at rest it is c × the largest velocity.
/// Deterministic and thread-count independent: forces are computed per node from the
/// positions at the start of the step (no cross-thread reductions), then all nodes move.
#include "ablmg/core/metric_field.hpp"
#include "ablmg/mesher/bubble_force.hpp"
#include "ablmg/mesher/initial_placement.hpp"
#include "ablmg/mesher/node_set.hpp"

#include <cmath>
#include <span>
#include <vector>

namespace ablmg::mesher {

struct DynamicsParams {
  double k0 = 1.0, mass = 1.0, damping = 0.35,
         dt = 0.45;  ///< defaults of PlacementOptions (see there; paper §6: c = 3.8429, Δt = 0.02)
  PairDistance pairDistance = PairDistance::Harmonic;  ///< w of the pair force (bubble_force.hpp)
};

/// Where the bubbles went: one record for the adjacency upkeep (travel since the lists were
/// last computed, place_nodes.hpp) and for the active set (moves in the current step).
/// Invariant, for every bubble i the record covers:
///  - ref(i): where i was at the last clear() or resetTravel() of i (the reference positions;
///    empty before the first clear());
///  - travel(i) = |x_i − ref(i)|_{M_i}, x_i and M_i as of i's last recorded move (0 after a
///    clear or reset; 0 for an added bubble, whose reference is where it was added);
///  - movedSinceClear()[i] ⇔ i moved, was added or displaced since the last clear();
///  - movedThisStep(i) ⇔ i moved by more than the activity threshold in the current step
///    (a step stamp per bubble: nothing is cleared between steps);
///  - maxTravel() = max_i travel(i) (cached when known).
class MovementRecord {
 public:
  /// A new step over n bubbles: new ones count as moved since the clear, with travel 0.
  void beginStep(int n);
  /// Bubble i moved to x by `step` in this step (metric m at its new position); `active`: the
  /// move exceeds the activity threshold. Safe in parallel over distinct i.
  void recordMove(int i, const Vec2& x, const Metric2& m, bool active) {
    sinceClear_[i] = 1;
    if (i < int(ref_.size())) travel_[i] = std::sqrt(m.squaredLength(x - ref_[i]));
    if (active) stamps_[i] = stamp_;
  }
  /// Stamps for n bubbles; bubbles new since the last step count as moved in it. Returns true
  /// when the count changed (the caller then makes a full pass).
  bool coverStep(int n);
  bool movedThisStep(int i) const { return stamps_[i] == stamp_; }
  double travel(int i) const { return i < int(travel_.size()) ? travel_[i] : 0.0; }
  void setMaxTravel(double m) {
    maxTravel_ = m;
    maxTravelValid_ = true;
  }
  double maxTravel() const;
  std::vector<int> travellers(double threshold) const;
  void resetTravel(std::span<const int> ids, const std::vector<Vec2>& positions);
  void clear(const std::vector<Vec2>& positions);
  const std::vector<char>& movedSinceClear() const { return sinceClear_; }
  const std::vector<Vec2>& referencePositions() const { return ref_; }
  /// After population edits: the stamps restart in full at the next step, the maximum is unknown.
  void structureChanged() {
    resetStamps_ = true;
    maxTravelValid_ = false;
  }
  void invalidateMaxTravel() { maxTravelValid_ = false; }
  /// Removal: bubble `from` becomes `to` (to ≤ from, in increasing order), then truncate(m).
  void keep(int from, int to);
  void truncate(int m);
  /// A bubble added at x as the n-th (its travel counts from x once references exist).
  void append(const Vec2& x, std::size_t n);
  /// Capacity for n bubbles in every per-bubble array (BubbleSystem::reserveInterior).
  void reserve(std::size_t n);
  /// Bubble i was moved to x by hand (metric m).
  void displaced(int i, const Vec2& x, const Metric2& m);

 private:
  std::vector<Vec2> ref_;
  std::vector<double> travel_;
  std::vector<char> sinceClear_;
  std::vector<int> stamps_;  ///< step stamp of a bubble's last move (== stamp_: moved in this step)
  int stamp_ = 1;
  bool resetStamps_ = true;
  double maxTravel_ = 0;
  bool maxTravelValid_ = false;
};

class BubbleSystem {
 public:
  /// `arcLength`: Euclidean arc length along its loop of every boundary node (any value for
  /// interior nodes), as from placeBoundaryNodes. The geometry must outlive the system.
  BubbleSystem(const DomainGeometry& geo, NodeSet nodes, std::vector<double> arcLength);

  const NodeSet& nodes() const { return nodes_; }
  const std::vector<Metric2>& metrics() const { return metrics_; }
  const std::vector<Vec2>& velocities() const { return vel_; }
  int size() const { return nodes_.size(); }

  /// Evaluate M at the positions (serially: AnalyticMetricField is not thread-safe; once for
  /// a constant field). Lazy unless `all`: only bubbles that moved more than `lazyDistance`
  /// metric units since their last evaluation are re-evaluated (at most once per step; the
  /// metric then lags by < 0.05 h·|∇h|/h, and the final metrics are always evaluated exactly).
  void updateMetrics(const MetricField& field, bool all = true, double lazyDistance = 0.05);
  /// Net forces (eq. 6) from the lists; returns the residual defined above.
  double computeForces(const AdjacencyLists& adj, const DynamicsParams& p);
  /// |F_i|_{M_i} from the last computeForces() in which bubble i was awake.
  double forceResidual(int i) const { return res_[i]; }
  /// One Euler step using the forces of the last computeForces() (active bubbles only).
  void advance(const DynamicsParams& p);

  /// Active set (optional; all bubbles are active until this is called). After advance():
  /// a bubble stays or becomes active if it or one of its neighbours moved in that step;
  /// an active bubble whose force and velocity are both ≤ sleepBelow (metric units) and whose
  /// neighbours stood still falls asleep (velocity zeroed). Asleep bubbles are skipped by
  /// computeForces()/advance() — their force cannot change until a neighbour moves, which wakes
  /// them — so an already-exact lattice costs nothing. Deterministic. Returns the active count.
  /// A step moving a bubble by ≤ 0.1·sleepBelow·dt (metric) does not count as moving (round-off
  /// motion of an exact lattice must not keep it awake); such moves change a sleeper's force
  /// by ≲ 0.1·sleepBelow. The final residual is computed with everyone awake.
  long updateActivity(const AdjacencyLists& adj, double sleepBelow, double dt);
  void wakeAll();  ///< every bubble awake
  /// Wake bubble i now and its neighbours at the next updateActivity() (population edits).
  void kick(int i);
  /// Bubbles that moved since the last clearMoved() (for a partial adjacency refresh).
  const std::vector<char>& movedSinceRefresh() const { return movement_.movedSinceClear(); }
  void clearMoved();
  /// Largest metric distance of a bubble from where it was at clearMoved(): the two-ring
  /// refresh of the adjacency lists is exact while this stays below (radius − 1.5)/2.
  /// O(1) right after updateActivity() (which takes it in its pass over the bubbles), O(n)
  /// after anything else that moves or resets travel.
  double maxTravelSinceRefresh() const;
  /// Reference positions: where each bubble was at the last clearMoved()/resetTravel(); its
  /// travel is measured from there. Empty before the first clearMoved().
  const std::vector<Vec2>& referencePositions() const { return movement_.referencePositions(); }
  /// Bubbles whose travel since the last clearMoved()/resetTravel() exceeds `threshold` (ascending).
  std::vector<int> travellers(double threshold) const;
  /// Travel of these bubbles counts again from their current positions (after a local refresh).
  void resetTravel(std::span<const int> ids);

  /// Population edits (§3.4). Removal keeps the relative order of the survivors; returns
  /// old → new index map (−1 for removed). Only Interior nodes are removed, and Segment nodes
  /// too when `segmentsToo` (the chains are linked again); Vertex nodes never. Added bubbles
  /// are awake and kicked; the caller kicks the neighbours of removed ones.
  std::vector<int> remove(const std::vector<char>& kill, bool segmentsToo = false);
  void addInterior(const Vec2& x, const Metric2& m);
  /// Room for `extra` more bubbles in every per-bubble array before a batch of addInterior():
  /// the arrays grow by 1/16 beyond what is asked instead of doubling (a few hundred insertions
  /// into 5·10⁵ bubbles would otherwise double two dozen arrays, and copy them while both
  /// the old and the new buffers live).
  void reserveInterior(std::size_t extra);
  /// Moves Interior bubble i to x (defect kicks, defects.hpp) if x is strictly inside:
  /// velocity zeroed, bubble kicked. Returns false (nothing changed) otherwise.
  bool displace(int i, const Vec2& x);

  /// The arc length of boundary node i along its loop (wrapped to [0, L)).
  double arcLength(int i) const;

 private:
  void setBounds();
  /// Chain links of the boundary nodes (chainPrev_, chainNext_, chainShift_, segmentIds_) from
  /// their arcs; wraps the arcs of corner-less loops into one turn.
  void linkChains();
  /// Segment node i may move to arc s in this step: strictly before the next node of its chain
  /// and strictly after the previous one, where a corner counts as itself and a moving neighbour
  /// as the midpoint of the pair's arcs before the step (chainMidpoint, the same value on both
  /// sides). Both nodes of a pair may move at once, so the chain keeps its order and its nodes
  /// stay distinct: an invariant of construction, not a repair.
  bool canSlideTo(int i, double s) const;
  /// Segment node i and node j on the same piece of loop between two corners (j a Segment
  /// node of that piece or one of its two corners).
  bool sameChain(int i, int j) const;
  /// The pair force on the bubble at xi (metric mi) from bubble j, as the vector `term` with
  /// F_i −= term (eq. 6–8); false if there is none (out of range, coincident).
  bool pairTerm(const Vec2& xi, const Metric2& mi, int j, const DynamicsParams& p, Vec2& term) const;
  bool feels(int i, int j) const;         ///< i takes the force of j (Segment nodes: own loop piece only)
  Vec2 finishForce(int i, Vec2 f) const;  ///< Segment nodes keep the tangential part
  Vec2 netForce(int i, const AdjacencyLists& adj, const DynamicsParams& p) const;
  /// computeForces() when most bubbles are awake: every pair term is computed once and added
  /// to both bubbles (contiguous id blocks per thread), in the same order as netForce() adds
  /// them, so the forces are bit-identical (and independent of the thread count).
  double computeForcesPairwise(const AdjacencyLists& adj, const DynamicsParams& p);
  std::vector<char> need_;               ///< computeForcesPairwise's scratch: bubble awake this step
  void structureChanged();               ///< after population edits: the next step clears its per-node flags in full
  std::vector<int> list_;                ///< bubbles computed/moved this step (awake, not Vertex), ascending
  std::vector<char> next_;               ///< updateActivity's scratch
  std::vector<std::vector<int>> parts_;  ///< updateActivity's per-thread id lists
  struct {
    std::vector<int> ids;  ///< awake bubbles after updateActivity (ascending), for the next computeForces
    bool valid = false;
  } nextList_;
  bool resetForces_ = true, resetActivity_ = true;
  const DomainGeometry* geo_;
  NodeSet nodes_;
  std::vector<double> s_, sLo_,
      sHi_;  ///< unwrapped arc length; arc of the corners around it (Segment nodes, ±inf if none)
  /// Boundary nodes: the previous and next boundary node along the loop (−1 for Interior), and
  /// the arc added to the next node's arc to compare it with this one's (the loop length for the
  /// pair that closes a corner-less loop, else 0). Invariant: s_[i] < s_[next] + shift.
  std::vector<int> chainPrev_, chainNext_;
  std::vector<double> chainShift_;
  std::vector<int> segmentIds_;  ///< Segment nodes, ascending
  std::vector<double> sStart_;   ///< s_ at the start of the current step (Segment nodes)
  std::vector<Vec2> vel_, force_;
  std::vector<double> res_;
  std::vector<double> clear_;  ///< Interior nodes: lower bound of the Euclidean distance to the boundary (0 = unknown)
  std::vector<char> active_, kicked_;
  MovementRecord movement_;  ///< travel since the last clearMoved(), moves in this step
  double moveEps2_ = 0;      ///< squared metric displacement below which a step is not a move
  std::vector<Metric2> metrics_;
  std::vector<Vec2> evalPos_;  ///< where metrics_[i] was evaluated
  std::vector<int> hint_;      ///< location hint of bubble i in the metric field (MetricField::evaluate)
  bool metricsConstant_ = false;
};

}  // namespace ablmg::mesher
