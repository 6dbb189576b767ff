#pragma once
/// A PNG plot of quantities against time: linear time axis, logarithmic value axis (errors of
/// a time-dependent run), one coloured line per curve with a legend. Written atomically
/// through cairo, like io/picture.hpp.
#include "ablmg/io/picture.hpp"

#include <string>
#include <vector>

namespace ablmg::io {

struct TimeCurve {
  std::string name;
  std::vector<double> t, y;  ///< same size; points with y ≤ 0 or non-finite are skipped
};

/// Throws InputError if a curve's t and y differ in size or there is no positive point.
void drawTimePlot(const std::string& path, const std::vector<TimeCurve>& curves, const std::string& tLabel = "t",
                  const std::string& yLabel = "error", const std::string& title = "",
                  const PictureOptions& options = {});

}  // namespace ablmg::io
