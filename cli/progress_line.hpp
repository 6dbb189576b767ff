#pragma once
/// The live progress line of long commands (mesh, remesh, surface, adapt) on stderr.
///
///   ProgressLine line("remesh", verbosity);
///   options.mesh.progress = line.callback();
///   ... the work ...
///   line.clear();            // before printing results (also done by the destructor)
///
/// On only when stderr is a terminal (isatty) and verbosity != 0; then it redraws one line in
/// place ("\r", erase to end of line) at most four times a second, starting half a second into
/// the work so that quick runs show nothing: stage, placement step, residual against its
/// target, nodes, elapsed seconds. Off, it writes nothing: output piped to a file is the same
/// with and without it.
#include "ablmg/core/progress.hpp"
#include "ablmg/core/stopwatch.hpp"

#include <string>

namespace ablmg::cli {

class ProgressLine {
 public:
  ProgressLine(std::string command, int verbosity);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool enabled() const { return enabled_; }
  /// A callback for the library options; empty when the line is off (no cost in the library).
  ProgressCallback callback();
  /// Draws `p` if the line is on and the last drawing is old enough.
  void update(const Progress& p);
  /// Erases the line if anything is drawn, so that the next output starts on a clean line.
  void clear();

  /// The text of one report (no control characters), e.g.
  /// "ablmg remesh: placement, step 120, residual 0.034 / 0.010, 41944 nodes, 2.3 s".
  static std::string format(const std::string& command, const Progress& p, double seconds);

 private:
  std::string command_;
  bool enabled_ = false;
  bool drawn_ = false;
  double lastDraw_ = -1;
  Stopwatch watch_;
};

}  // namespace ablmg::cli
