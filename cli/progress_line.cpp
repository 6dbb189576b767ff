#include "ablmg/cli/progress_line.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdio>
#include <utility>

namespace ablmg::cli {
namespace {

constexpr double kFirstDraw = 0.5;  ///< seconds of work before the line appears
constexpr double kInterval = 0.25;  ///< seconds between two drawings

}  // namespace

ProgressLine::ProgressLine(std::string command, int verbosity)
    : command_(std::move(command)), enabled_(verbosity != 0 && ::isatty(STDERR_FILENO) == 1) {}

ProgressLine::~ProgressLine() { clear(); }

ProgressCallback ProgressLine::callback() {
  if (!enabled_) return {};
  return [this](const Progress& p) { update(p); };
}

std::string ProgressLine::format(const std::string& command, const Progress& p, double seconds) {
  char buf[96];
  std::string s = "ablmg " + command + ":";
  if (p.cycle >= 0) {
    std::snprintf(buf, sizeof buf, " cycle %d/%d,", p.cycle + 1, p.cycles);
    s += buf;
  }
  s += std::string(" ") + p.stage;
  if (p.step >= 0) {
    std::snprintf(buf, sizeof buf, ", step %d", p.step);
    s += buf;
  }
  if (p.residual >= 0) {
    std::snprintf(buf, sizeof buf, p.target >= 0 ? ", residual %.3g / %.3g" : ", residual %.3g", p.residual, p.target);
    s += buf;
  }
  if (p.nodes >= 0) {
    std::snprintf(buf, sizeof buf, ", %ld %s", p.nodes, p.step >= 0 ? "nodes" : "vertices");
    s += buf;
  }
  std::snprintf(buf, sizeof buf, ", %.1f s", seconds);
  return s + buf;
}

void ProgressLine::update(const Progress& p) {
  if (!enabled_) return;
  const double t = watch_.seconds();
  if (t < kFirstDraw || (lastDraw_ >= 0 && t - lastDraw_ < kInterval)) return;
  lastDraw_ = t;
  std::string text = format(command_, p, t);
  winsize ws{};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 1 && text.size() >= ws.ws_col)
    text.resize(ws.ws_col - 1);  // a wrapped line could not be redrawn in place
  std::fprintf(stderr, "\r%s\033[K", text.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressLine::clear() {
  if (!drawn_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  drawn_ = false;
  lastDraw_ = -1;
}

}  // namespace ablmg::cli
