// ablmg transient --problem NAME [options]: the heat equation on a mesh that follows the
// solution (adapt/transient_loop.hpp): remesh every k steps to the metric of the next interval,
// transfer the state, go on. Writes to --out-dir:
//   intervals.csv / report.json  one row per interval (remesh): time, N, L2 error at that time,
//                                accumulated space-time L2 and L2(H1) errors, transfer mass
//                                defect, remesh / transfer / solve times; the JSON adds the
//                                options and the totals
//   steps.csv                    time, N, L2 and H1 errors of every step (deterministic)
//   error_vs_time.png            L2 error against time, with the runs of --plot-with overlaid
//   series.pvd, frames/*.vtu     the solution, exact solution and error at each interval's end
//   frames/*.png                 the mesh of each interval coloured by u_h (--frames on)
#include "ablmg/adapt/transient_loop.hpp"
#include "ablmg/cli/command.hpp"
#include "ablmg/cli/parse_number.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/io/picture.hpp"
#include "ablmg/io/time_plot.hpp"
#include "ablmg/io/vtu.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace ablmg::cli {
namespace {

namespace fs = std::filesystem;

struct Args {
  std::string problem;
  std::map<std::string, double> params;
  adapt::TransientOptions options;
  std::string outDir = "transient_out";
  bool frames = true;
  std::vector<std::pair<std::string, std::string>> plotWith;  ///< label, directory with steps.csv
  std::string label;
};

constexpr const char* kUsage =
    "usage: ablmg transient --problem NAME [--param KEY=VALUE ...] [--dt DT] [--t-end T] [--remesh-every K]\n"
    "                       [--vertices N] [--fixed-point-iterations F] [--hessian-every S]\n"
    "                       [--metric interval|current] [--uniform]\n"
    "                       [--scheme bdf2|euler] [--transfer projection|interpolation] [--bound-preserving on|off]\n"
    "                       [--hgrad B] [--p P] [--hessian lsq|double] [--seed S] [--frames on|off]\n"
    "                       [--label NAME] [--plot-with LABEL=DIR ...] [--out-dir DIR]\n"
    "  The heat equation u_t - kappa Laplace(u) = f on a mesh that follows the solution: every K steps\n"
    "  (default 20) a metric covering the next interval (the intersection of the Hessian metrics of its\n"
    "  sub-steps, every S-th and the last, default 2; F fixed-point passes, default 1), a remesh to N\n"
    "  vertices (default 4000), the state transferred (conservative L2 projection), and on.\n"
    "  --uniform: one uniform mesh of N vertices.\n"
    "  --metric current: the metric of the current solution only. Problems: movingpeak, front\n"
    "  (their default dt and final time: 0.001, 0.5 / 0.6). Outputs: see cli/cmd_transient.cpp.\n";

void parseOption(Args& a, const std::string& key, const std::function<const std::string&()>& value) {
  auto& o = a.options;
  if (key == "--problem") {
    a.problem = value();
  } else if (key == "--param") {
    const std::string kv = value();
    const auto eq = kv.find('=');
    ABLMG_REQUIRE(eq != std::string::npos && eq > 0, "transient: --param expects KEY=VALUE, got '" << kv << "'");
    a.params[kv.substr(0, eq)] = parseNumber(kv.substr(eq + 1), "transient: --param " + kv.substr(0, eq));
  } else if (key == "--dt") {
    o.dt = parseNumber(value(), "transient: --dt");
    ABLMG_REQUIRE(o.dt > 0 && std::isfinite(o.dt), "transient: --dt must be > 0, got " << o.dt);
  } else if (key == "--t-end") {
    o.tEnd = parseNumber(value(), "transient: --t-end");
  } else if (key == "--remesh-every") {
    o.remeshEvery = int(parseInteger(value(), "transient: --remesh-every", 1, 1000000));
  } else if (key == "--vertices") {
    o.vertices = parseNumber(value(), "transient: --vertices");
  } else if (key == "--fixed-point-iterations") {
    o.fixedPointIterations = int(parseInteger(value(), "transient: --fixed-point-iterations", 1, 20));
  } else if (key == "--hessian-every") {
    o.hessianEvery = int(parseInteger(value(), "transient: --hessian-every", 1, 1000000));
  } else if (key == "--metric") {
    o.metric = adapt::parseTransientMetric(value());
  } else if (key == "--uniform") {
    o.uniform = true;
  } else if (key == "--scheme") {
    o.scheme = fem::parseTimeScheme(value());
  } else if (key == "--transfer") {
    o.transfer.method = adapt::parseTransferMethod(value());
  } else if (key == "--bound-preserving") {
    o.transfer.boundPreserving = parseOnOff(value(), "transient: --bound-preserving");
  } else if (key == "--hgrad") {
    o.adapt.hgrad = parseNumber(value(), "transient: --hgrad");
  } else if (key == "--p") {
    o.adapt.metric.p = parseNumber(value(), "transient: --p");
  } else if (key == "--hessian") {
    o.adapt.hessian = adapt::parseHessianMethod(value());
  } else if (key == "--seed") {
    o.adapt.mesh.placement.seed = std::uint64_t(parseInteger(value(), "transient: --seed", 0, 2000000000));
  } else if (key == "--frames") {
    a.frames = parseOnOff(value(), "transient: --frames");
  } else if (key == "--label") {
    a.label = value();
  } else if (key == "--plot-with") {
    const std::string kv = value();
    const auto eq = kv.find('=');
    ABLMG_REQUIRE(eq != std::string::npos && eq > 0, "transient: --plot-with expects LABEL=DIR, got '" << kv << "'");
    a.plotWith.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
  } else if (key == "--out-dir") {
    a.outDir = value();
  } else {
    ABLMG_REQUIRE(
        false,
        "transient: unknown argument '"
            << key
            << "' (valid: --problem --param --dt --t-end --remesh-every --vertices "
               "--fixed-point-iterations --hessian-every --metric --uniform --scheme --transfer --bound-preserving "
               "--hgrad --p --hessian --seed --frames --label --plot-with --out-dir)");
  }
}

Args parseArgs(const std::vector<std::string>& args) {
  Args a;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& key = args[i];
    parseOption(a, key, [&]() -> const std::string& {
      ABLMG_REQUIRE(i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0, "transient: " << key << " needs a value");
      return args[++i];
    });
  }
  ABLMG_REQUIRE(!a.problem.empty(), "transient: --problem NAME is required (movingpeak, front)");
  if (a.label.empty()) a.label = a.options.uniform ? "uniform" : "adaptive (" + adapt::toString(a.options.metric) + ")";
  return a;
}

/// steps.csv of another run: (time, l2) pairs. InputError naming the file when unreadable.
io::TimeCurve readSteps(const std::string& label, const std::string& dir) {
  const std::string path = (fs::path(dir) / "steps.csv").string();
  std::ifstream in(path);
  ABLMG_REQUIRE(in, "transient: --plot-with " << label << ": cannot read " << path);
  io::TimeCurve c{label, {}, {}};
  std::string line;
  std::getline(in, line);
  ABLMG_REQUIRE(line.rfind("step,time,vertices,l2_error,h1_error", 0) == 0, path << ":1: not a steps.csv header");
  for (int row = 2; std::getline(in, line); ++row) {
    double step = 0, t = 0, n = 0, l2 = 0, h1 = 0;
    ABLMG_REQUIRE(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &step, &t, &n, &l2, &h1) == 5,
                  path << ":" << row << ": expected 5 numbers");
    c.t.push_back(t);
    c.y.push_back(l2);
  }
  return c;
}

void writeFrame(const Args& a, const fem::TransientProblem& p, const adapt::TransientFrame& f) {
  const Mesh2& mesh = f.mesh;
  std::vector<double> u(f.u.data(), f.u.data() + f.u.size()), exact(u.size()), err(u.size());
  for (std::size_t v = 0; v < u.size(); ++v) {
    exact[v] = p.u(mesh.vertices[v].x(), mesh.vertices[v].y(), f.record.timeEnd);
    err[v] = u[v] - exact[v];
  }
  char name[64];
  std::snprintf(name, sizeof name, "interval_%04d", f.record.interval);
  const fs::path dir = fs::path(a.outDir) / "frames";
  io::writeVtu((dir / (std::string(name) + ".vtu")).string(), mesh,
               {{"u", 1, u}, {"exact", 1, exact}, {"error", 1, err}});
  std::vector<double> cell(std::size_t(mesh.numTriangles()));
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    const auto& tr = mesh.triangles[std::size_t(t)];
    cell[std::size_t(t)] = (u[tr[0]] + u[tr[1]] + u[tr[2]]) / 3;
  }
  io::PictureOptions po;
  po.width = 800;
  io::drawMesh((dir / (std::string(name) + ".png")).string(), mesh, cell, "u_h", po);
}

void writePvd(const Args& a, const adapt::TransientReport& r) {
  io::writeFileAtomically((fs::path(a.outDir) / "series.pvd").string(), [&](std::ostream& os) {
    os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& rec : r.intervals) {
      char name[64];
      std::snprintf(name, sizeof name, "frames/interval_%04d.vtu", rec.interval);
      os << "    <DataSet timestep=\"" << std::setprecision(12) << rec.timeEnd << "\" file=\"" << name << "\"/>\n";
    }
    os << "  </Collection>\n</VTKFile>\n";
  });
}

void writeTables(const Args& a, const fem::TransientProblem& p, const adapt::TransientReport& r) {
  io::writeFileAtomically((fs::path(a.outDir) / "steps.csv").string(), [&](std::ostream& os) {
    os << "step,time,vertices,l2_error,h1_error\n" << std::setprecision(10);
    for (const auto& s : r.steps)
      os << s.step << "," << s.time << "," << s.vertices << "," << s.l2 << "," << s.h1 << "\n";
  });
  io::writeFileAtomically((fs::path(a.outDir) / "intervals.csv").string(), [&](std::ostream& os) {
    os << "interval,time,vertices,l2_at_remesh,l2_at_end,space_time_l2,space_time_h1,mass_defect,"
          "t_remesh,t_transfer,t_solve,t_metric\n"
       << std::setprecision(8);
    for (const auto& i : r.intervals)
      os << i.interval << "," << i.time << "," << i.vertices << "," << i.l2AtStart << "," << i.l2AtEnd << ","
         << i.spaceTimeL2 << "," << i.spaceTimeH1 << "," << i.massDefect << "," << i.tRemesh << "," << i.tTransfer
         << "," << i.tSolve << "," << i.tMetric << "\n";
  });
  nlohmann::json j;
  const auto& o = a.options;
  j["problem"] = {{"name", p.name}, {"params", p.params}, {"formula", p.formula}, {"kappa", p.kappa}};
  j["options"] = {{"dt", r.dt},
                  {"t_start", r.tStart},
                  {"t_end", r.tEnd},
                  {"remesh_every", o.remeshEvery},
                  {"vertices", o.vertices},
                  {"fixed_point_iterations", o.fixedPointIterations},
                  {"hessian_every", o.hessianEvery},
                  {"metric", adapt::toString(o.metric)},
                  {"uniform", o.uniform},
                  {"scheme", fem::toString(o.scheme)},
                  {"transfer", adapt::toString(o.transfer.method)},
                  {"bound_preserving", o.transfer.boundPreserving}};
  j["space_time_l2"] = r.spaceTimeL2;
  j["space_time_h1"] = r.spaceTimeH1;
  j["average_vertices"] = r.averageVertices;
  j["max_l2"] = r.maxL2;
  j["max_mass_defect"] = r.maxMassDefect;
  j["meshes"] = r.meshes;
  j["seconds"] = r.seconds;
  for (const auto& i : r.intervals)
    j["intervals"].push_back({{"interval", i.interval},
                              {"time", i.time},
                              {"vertices", i.vertices},
                              {"l2_at_remesh", i.l2AtStart},
                              {"l2_at_end", i.l2AtEnd},
                              {"space_time_l2", i.spaceTimeL2},
                              {"space_time_h1", i.spaceTimeH1},
                              {"mass_defect", i.massDefect},
                              {"t_remesh", i.tRemesh},
                              {"t_transfer", i.tTransfer},
                              {"t_solve", i.tSolve},
                              {"t_metric", i.tMetric}});
  io::writeFileAtomically((fs::path(a.outDir) / "report.json").string(),
                          [&](std::ostream& os) { os << j.dump(2) << "\n"; });
}

void writePlot(const Args& a, const adapt::TransientReport& r, const std::vector<io::TimeCurve>& others) {
  std::vector<io::TimeCurve> curves{{a.label, {}, {}}};
  for (const auto& s : r.steps) {
    curves[0].t.push_back(s.time);
    curves[0].y.push_back(s.l2);
  }
  curves.insert(curves.end(), others.begin(), others.end());
  io::drawTimePlot((fs::path(a.outDir) / "error_vs_time.png").string(), curves, "t", "L2 error",
                   "L2 error against time");
}

int runTransient(const std::vector<std::string>& args) {
  if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h")) {
    std::cout << kUsage;
    return 0;
  }
  const Args a = parseArgs(args);
  const fem::TransientProblem problem = fem::makeTransientProblem(a.problem, a.params);
  adapt::validate(a.options, problem.tStart);  // every bad option is reported before any output
  std::vector<io::TimeCurve> others;
  for (const auto& [label, dir] : a.plotWith) others.push_back(readSteps(label, dir));
  fs::create_directories(fs::path(a.outDir) / "frames");
  const auto report = adapt::runTransientLoop(problem, a.options, [&](const adapt::TransientFrame& f) {
    const auto& i = f.record;
    std::cout << "Interval " << i.interval << ": t=" << i.time << ".." << i.timeEnd << " N=" << i.vertices
              << " L2(t)=" << i.l2AtStart << " L2(end)=" << i.l2AtEnd << " L2(0,t;L2)=" << i.spaceTimeL2
              << " mass defect=" << i.massDefect << " t_remesh=" << i.tRemesh << " t_transfer=" << i.tTransfer
              << " t_solve=" << i.tSolve << "\n";
    if (a.frames) writeFrame(a, problem, f);
  });
  writeTables(a, problem, report);
  if (a.frames) writePvd(a, report);
  writePlot(a, report, others);
  std::cout << "space-time L2 error " << report.spaceTimeL2 << ", L2(H1) " << report.spaceTimeH1
            << ", average vertices " << report.averageVertices << ", max mass defect " << report.maxMassDefect << ", "
            << report.meshes << " meshes, " << report.seconds << " s\n";
  return 0;
}

}  // namespace

ABLMG_COMMAND("transient", "heat equation on a mesh that follows the solution", runTransient)

}  // namespace ablmg::cli
