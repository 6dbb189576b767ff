#pragma once
/// Progress of long work (meshing, remeshing, the adaptive loop), reported by the libraries to
/// a callback the caller puts in the options (MeshOptions::progress, AdaptOptions::progress).
/// The libraries never print: the `ablmg` program turns the reports into a progress line on a
/// terminal (cli/progress_line.hpp), a GUI may draw a bar, and an empty callback costs nothing.
///
/// Reports come from the calling thread, in order, at stage changes and at most every
/// `progressEvery` placement steps; the callback must not throw (an exception propagates out
/// of the library call, abandoning the work) and must not touch the objects being built.
/// What it is called with does not change the result: outputs are the same with or without.
#include <functional>

namespace ablmg {

struct Progress {
  /// What runs now: "placement", "connection", "improve", "validation" (meshDomain);
  /// "gradation", "background" (remesh); "solve", "recover", "metric" (the adaptive loop).
  const char* stage = "";
  int step = -1;         ///< placement: dynamics steps done (−1 outside placement)
  double residual = -1;  ///< placement: the largest net bubble force, metric units (−1 if unknown)
  double target = -1;    ///< placement: the residual the run stops at (−1 if unknown)
  long nodes = -1;       ///< nodes (placement) or vertices of the mesh at hand (−1 if unknown)
  int cycle = -1;        ///< the adaptive loop's cycle, 0-based (−1 outside the loop)
  int cycles = -1;       ///< the adaptive loop's number of cycles (−1 outside the loop)
};

using ProgressCallback = std::function<void(const Progress&)>;

}  // namespace ablmg
