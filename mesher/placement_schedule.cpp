#include "ablmg/mesher/placement_schedule.hpp"

#include <algorithm>

namespace ablmg::mesher {

PopulationSchedule::PopulationSchedule(long target, int maxSteps) : until_(std::max(kEvery, int(0.6 * maxSteps))) {
  pop_.target = target;
}

void PopulationSchedule::afterPass(long edits, int size) {
  counts_.push_back(size);
  const std::size_t w = std::size_t(std::max(1, pop_.steerWindow));
  if (counts_.size() > w && counts_.back() <= (1 + pop_.steerMinGrowth) * counts_[counts_.size() - 1 - w])
    pop_.steerUp = false;
  nearlySettled_ = double(edits) <= 2e-3 * size;
  if (double(edits) <= 1e-4 * size) {
    if (++quietPasses_ >= 2) settled_ = true;
  } else {
    quietPasses_ = 0;
  }
}

bool StallRule::stalled(int step, double residual) {
  if (markStep_ < 0 || residual < 0.5 * mark_) {
    mark_ = residual;
    markStep_ = step;
    return false;
  }
  return step - markStep_ >= steps_;
}

bool QualityPlateau::reached(double share, bool mayStart, int sinceResidualMark) {
  shares_.push_back(share);
  const std::size_t back = std::size_t((steps_ + 9) / 10);  // window in samples
  return mayStart && shares_.size() > back && shares_.back() - shares_[shares_.size() - 1 - back] < gain_ &&
         sinceResidualMark >= steps_;
}

bool RelaxBeforeStop::allowsStop(int step) {
  if (lastEdit_ < 0 || step - lastEdit_ >= steps_) return true;
  stopAt_ = lastEdit_ + steps_;
  return false;
}

}  // namespace ablmg::mesher
