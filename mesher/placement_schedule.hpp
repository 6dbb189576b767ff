#pragma once
/// The stop rules and schedules of node placement (place_nodes.hpp), each a small state
/// machine fed once per dynamics step by the driver, so that each can be read and tested alone.
///
///   PopulationSchedule  population passes (§3.4) every 10 steps until the count settles
///   DefectSchedule      defect-annealing passes (defects.hpp) once the population has settled
///   StallRule           stop when the residual has not halved within stallSteps steps
///   QualityPlateau      stop when the share of unit-length pairs has stopped growing
///   RelaxBeforeStop     an early stop waits finalRelaxSteps steps after the last edit
///
/// Steps are counted from 0; "done" is step + 1 (the steps completed after this one).
#include "ablmg/mesher/population.hpp"

#include <vector>

namespace ablmg::mesher {

struct PlacementOptions;

/// Population passes every `every` (10) steps while the population is unsettled. It settles
/// after two passes in a row that change at most 1 node in 10⁴ (large graded runs otherwise
/// keep editing 1–3 nodes per pass, each edit jolting its neighbourhood), at 60 % of maxSteps,
/// or when the driver settles it (an early stop). Steering up (PopulationOptions::steerUp) ends
/// once the count has grown by less than steerMinGrowth over steerWindow passes.
class PopulationSchedule {
 public:
  PopulationSchedule(long target, int maxSteps);
  PopulationOptions& options() { return pop_; }
  bool settled() const { return settled_; }
  /// The last pass edited at most 0.2 % of the nodes (the quality plateau may start sampling).
  bool nearlySettled() const { return nearlySettled_; }
  bool passDue(int done) const { return !settled_ && done % kEvery == 0; }
  /// After a pass that edited `edits` nodes and left `size`.
  void afterPass(long edits, int size);
  /// After every step (passes or not).
  void afterStep(int done) {
    if (!settled_ && done >= until_) settled_ = true;
  }
  void settle() { settled_ = true; }
  static constexpr int kEvery = 10;

 private:
  PopulationOptions pop_;
  int until_;
  int quietPasses_ = 0;
  std::vector<int> counts_;  ///< node count after each pass
  bool settled_ = false, nearlySettled_ = false;
};

/// Up to `passes` defect-annealing passes, the first when due, the next `every` steps apart.
class DefectSchedule {
 public:
  DefectSchedule(int passes, int every) : left_(passes), every_(every) {}
  bool left() const { return left_ > 0; }
  bool due(int step) const { return left_ > 0 && (last_ < 0 || step - last_ >= every_); }
  void started(int step) {
    --left_;
    last_ = step;
  }
  void stop() { left_ = 0; }

 private:
  int left_, every_, last_ = -1;
};

/// The residual must halve within `steps` steps of each mark (the step where it last did).
/// Metrics from solvers may have no equilibrium within tolerance: a few bubbles where M varies
/// by ~100 % per metric unit keep jolting. 0 = off.
class StallRule {
 public:
  explicit StallRule(int steps) : steps_(steps) {}
  bool enabled() const { return steps_ > 0; }
  /// Feeds the residual of `step`: a new mark if it halved (or there is none), else true once
  /// the mark is `steps` steps old.
  bool stalled(int step, double residual);
  void restart() { markStep_ = -1; }
  int markStep() const { return markStep_; }  ///< −1: no mark yet

 private:
  int steps_;
  double mark_ = 0;
  int markStep_ = -1;
};

/// The paper's "less simulation when lower quality is acceptable": the share of neighbour pairs
/// within ±10 % of unit length, sampled every 10 steps, has gained less than `gain` over the
/// last `steps` steps (rounded up to a multiple of 10), while the residual has not halved in as
/// many either. 0 steps = off.
class QualityPlateau {
 public:
  QualityPlateau(int steps, double gain) : steps_(steps), gain_(gain) {}
  bool sampleDue(int step) const { return steps_ > 0 && step % 10 == 0; }
  /// Feeds a sample; true when the plateau is reached. `mayStart`: the population has settled
  /// (or nearly); `sinceResidualMark`: steps since the residual last halved (StallRule).
  bool reached(double share, bool mayStart, int sinceResidualMark);

 private:
  int steps_;
  double gain_;
  std::vector<double> shares_;
};

/// Early stops (stall, plateau) never cut off right after an edit: the nodes just inserted,
/// the holes of the ones just deleted and the kicked neighbourhoods get `steps` steps without
/// further edits first.
class RelaxBeforeStop {
 public:
  explicit RelaxBeforeStop(int steps) : steps_(steps) {}
  void edited(int step) { lastEdit_ = step; }
  /// An early stop asked at `step`: true if it may stop now, else the stop is set for later.
  bool allowsStop(int step);
  bool relaxing() const { return stopAt_ >= 0; }  ///< a stop is set
  bool over(int step) const { return stopAt_ >= 0 && step >= stopAt_; }

 private:
  int steps_, lastEdit_ = -1, stopAt_ = -1;
};

}  // namespace ablmg::mesher
