// compare_freefem_plot: the table and the picture of examples/compare_freefem/run.sh.
//
//   compare_freefem_plot --freefem freefem.csv --freefem-mesh freefem_final.mesh --ablmg DIR
//                        --png compare.png --md compare.md [--freefem-wall S] [--ablmg-wall S]
//
// Inputs: FreeFem++'s CSV (wavefront.edp: cycle,vertices,triangles,l2_error,h1_error,t_solve,
// t_mesh; CPU seconds), its last mesh (medit), and the output directory of `ablmg adapt
// --medit on` (convergence.csv with wall seconds per phase, cycle_K.mesh). The whole-run wall
// times measured by run.sh are optional.
//
// Steps: 1. read both CSVs; 2. error ratios ablmg / FreeFem at ablmg's N, FreeFem's adapted
// curve (cycles ≥ 1) interpolated log-log (extrapolated along its end segment outside its
// range, marked *; cycle 0 is both loops' uniform start mesh and is compared directly);
// 3. rates over the last 4 cycles; 4. the Markdown report; 5. the PNG: L2 and H1 against N over
// the two final meshes (io::tilePictures).
#include "ablmg/adapt/convergence.hpp"
#include "ablmg/core/error.hpp"
#include "ablmg/io/atomic_file.hpp"
#include "ablmg/io/medit.hpp"
#include "ablmg/io/picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace ablmg;
namespace fs = std::filesystem;

namespace {

/// A CSV file with a header line: column name → values, one per row.
struct Table {
  std::map<std::string, std::vector<double>> columns;
  std::size_t rows = 0;
  const std::vector<double>& operator[](const std::string& name) const {
    const auto it = columns.find(name);
    ABLMG_REQUIRE(it != columns.end(), "compare_freefem_plot: no column '" << name << "'");
    return it->second;
  }
};

Table readCsv(const std::string& path) {
  std::ifstream in(path);
  ABLMG_REQUIRE(in, path << ": cannot open");
  std::string line, cell;
  ABLMG_REQUIRE(std::getline(in, line), path << ": empty file");
  std::vector<std::string> names;
  for (std::stringstream ss(line); std::getline(ss, cell, ',');) names.push_back(cell);
  Table t;
  for (int lineNo = 2; std::getline(in, line); ++lineNo) {
    if (line.empty()) continue;
    std::size_t k = 0;
    for (std::stringstream ss(line); std::getline(ss, cell, ','); ++k) {
      ABLMG_REQUIRE(k < names.size(), path << ":" << lineNo << ": more cells than the header's " << names.size());
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(cell, &used);
      } catch (const std::exception&) { used = 0; }
      ABLMG_REQUIRE(used == cell.size() && !cell.empty(),
                    path << ":" << lineNo << ": '" << cell << "' is not a number");
      t.columns[names[k]].push_back(v);
    }
    ABLMG_REQUIRE(k == names.size(), path << ":" << lineNo << ": " << k << " cells, header has " << names.size());
    ++t.rows;
  }
  ABLMG_REQUIRE(t.rows > 0, path << ": no data rows");
  return t;
}

/// log e(N) on the piecewise-linear log-log curve through (n[i], e[i]) (sorted by n here);
/// outside [n_min, n_max] along the end segment, and `extrapolated` is set.
double interpolateLogLog(std::vector<std::pair<double, double>> pts, double n, bool& extrapolated) {
  std::sort(pts.begin(), pts.end());
  ABLMG_REQUIRE(pts.size() >= 2, "compare_freefem_plot: need two FreeFem points to interpolate");
  extrapolated = n < pts.front().first || n > pts.back().first;
  std::size_t i = 1;
  while (i + 1 < pts.size() && pts[i].first < n) ++i;
  const double x0 = std::log(pts[i - 1].first), x1 = std::log(pts[i].first);
  const double y0 = std::log(pts[i - 1].second), y1 = std::log(pts[i].second);
  return std::exp(y0 + (y1 - y0) * (std::log(n) - x0) / (x1 - x0));
}

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

}  // namespace

int main(int argc, char** argv) try {
  std::map<std::string, std::string> arg{{"--freefem-wall", ""}, {"--ablmg-wall", ""}};
  const std::vector<std::string> required{"--freefem", "--freefem-mesh", "--ablmg", "--png", "--md"};
  for (int i = 1; i < argc; i += 2) {
    const std::string key = argv[i];
    ABLMG_REQUIRE(arg.count(key) || std::count(required.begin(), required.end(), key),
                  "compare_freefem_plot: unknown argument '" << key
                                                             << "' (valid: --freefem --freefem-mesh --ablmg --png --md "
                                                                "--freefem-wall --ablmg-wall)");
    ABLMG_REQUIRE(i + 1 < argc, "compare_freefem_plot: " << key << " needs a value");
    arg[key] = argv[i + 1];
  }
  for (const auto& key : required) ABLMG_REQUIRE(arg.count(key), "compare_freefem_plot: " << key << " is required");

  // 1. Both loops' rows. FreeFem row k: solve on mesh k (CPU s), adaptmesh of mesh k+1.
  //    ablmg row k: t_mesh built mesh k, then solve, recover + metric for mesh k+1 (wall s).
  const Table ff = readCsv(arg["--freefem"]);
  const Table ab = readCsv((fs::path(arg["--ablmg"]) / "convergence.csv").string());
  const std::size_t nff = ff.rows, nab = ab.rows;

  // 2. Ratios at ablmg's N against FreeFem's adapted curve.
  std::vector<std::pair<double, double>> ffL2, ffH1;
  for (std::size_t k = 1; k < nff; ++k) {
    ffL2.emplace_back(ff["vertices"][k], ff["l2_error"][k]);
    ffH1.emplace_back(ff["vertices"][k], ff["h1_error"][k]);
  }
  std::vector<double> ratioL2(nab), ratioH1(nab);
  std::vector<bool> extrapolated(nab, false);
  for (std::size_t k = 0; k < nab; ++k) {
    const double n = ab["vertices"][k];
    if (k == 0) {  // both uniform start meshes
      ratioL2[k] = ab["l2_error"][k] / ff["l2_error"][0];
      ratioH1[k] = ab["h1_error"][k] / ff["h1_error"][0];
      continue;
    }
    bool e1 = false, e2 = false;
    ratioL2[k] = ab["l2_error"][k] / interpolateLogLog(ffL2, n, e1);
    ratioH1[k] = ab["h1_error"][k] / interpolateLogLog(ffH1, n, e2);
    extrapolated[k] = e1 || e2;
  }

  // 3. Rates over the last 4 cycles (as ablmg adapt reports them).
  const int window = 4;
  const double ffRateL2 = adapt::logLogSlope(ff["vertices"], ff["l2_error"], window);
  const double ffRateH1 = adapt::logLogSlope(ff["vertices"], ff["h1_error"], window);
  const double abRateL2 = adapt::logLogSlope(ab["vertices"], ab["l2_error"], window);
  const double abRateH1 = adapt::logLogSlope(ab["vertices"], ab["h1_error"], window);

  // 4. The Markdown report.
  double ffSolve = 0, ffMesh = 0, abSolve = 0, abMetric = 0, abMesh = 0;
  io::writeFileAtomically(arg["--md"], [&](std::ostream& os) {
    os << "# FreeFem++ adaptmesh vs ablmg adapt: Mitchell's wave front\n\n"
       << "Cycle k of both loops targets the same vertex count (FreeFem's N_k). Ratios are ablmg's error over "
          "FreeFem's adapted curve (cycles >= 1) interpolated log-log at ablmg's N (* = extrapolated along the end "
          "segment; cycle 0 = both uniform start meshes, compared directly). Times per cycle: solve on mesh k, then "
          "build mesh k+1 (FreeFem: adaptmesh, CPU s from clock(); ablmg: recover + metric, then the remesh, wall "
          "s).\n\n"
       << "| cycle | N FreeFem | N ablmg | L2 FreeFem | L2 ablmg | L2 ratio | H1 FreeFem | H1 ablmg | H1 ratio "
          "| FreeFem solve | FreeFem remesh | ablmg solve | ablmg recover+metric | ablmg remesh |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (std::size_t k = 0; k < std::max(nff, nab); ++k) {
      os << "| " << k;
      if (k < nff)
        os << " | " << fmt("%.0f", ff["vertices"][k]);
      else
        os << " | ";
      os << " | " << (k < nab ? fmt("%.0f", ab["vertices"][k]) : "");
      os << " | " << (k < nff ? fmt("%.3e", ff["l2_error"][k]) : "") << " | "
         << (k < nab ? fmt("%.3e", ab["l2_error"][k]) : "") << " | "
         << (k < nab ? fmt("%.2f", ratioL2[k]) + (extrapolated[k] ? "*" : "") : "");
      os << " | " << (k < nff ? fmt("%.4f", ff["h1_error"][k]) : "") << " | "
         << (k < nab ? fmt("%.4f", ab["h1_error"][k]) : "") << " | "
         << (k < nab ? fmt("%.2f", ratioH1[k]) + (extrapolated[k] ? "*" : "") : "");
      if (k < nff) {
        ffSolve += ff["t_solve"][k], ffMesh += ff["t_mesh"][k];
        os << " | " << fmt("%.2f", ff["t_solve"][k]) << " | " << fmt("%.2f", ff["t_mesh"][k]);
      } else {
        os << " |  | ";
      }
      if (k < nab) {
        const double next = k + 1 < nab ? ab["t_mesh"][k + 1] : 0.0, metric = ab["t_recover"][k] + ab["t_metric"][k];
        abSolve += ab["t_solve"][k], abMetric += metric, abMesh += ab["t_mesh"][k];
        os << " | " << fmt("%.2f", ab["t_solve"][k]) << " | " << fmt("%.2f", metric) << " | " << fmt("%.2f", next);
      } else {
        os << " |  |  | ";
      }
      os << " |\n";
    }
    const double abFirstMesh = ab["t_mesh"][0];  // the uniform start mesh, not a remesh
    os << "| sum |  |  |  |  |  |  |  |  | " << fmt("%.2f", ffSolve) << " | " << fmt("%.2f", ffMesh) << " | "
       << fmt("%.2f", abSolve) << " | " << fmt("%.2f", abMetric) << " | " << fmt("%.2f", abMesh - abFirstMesh)
       << " |\n\n";
    os << "ablmg's start mesh (cycle 0, uniform metric) took " << fmt("%.2f", abFirstMesh)
       << " s; FreeFem's is square(20,20).\n\n";
    os << "Rates (log-log least squares over the last " << window << " cycles; optimal P1: L2 -1, H1 -0.5): FreeFem L2 "
       << fmt("%.3f", ffRateL2) << ", H1 " << fmt("%.3f", ffRateH1) << "; ablmg L2 " << fmt("%.3f", abRateL2) << ", H1 "
       << fmt("%.3f", abRateH1) << ".\n\n";
    if (!arg["--freefem-wall"].empty() || !arg["--ablmg-wall"].empty())
      os << "Whole run, wall clock (process start to end, including error integration and output): FreeFem++ "
         << arg["--freefem-wall"] << " s, ablmg " << arg["--ablmg-wall"] << " s.\n";
  });

  // 5. The picture: L2 and H1 vs N on top, FreeFem's and ablmg's final meshes below.
  const fs::path png(arg["--png"]);
  const fs::path tmp = png.parent_path() / (png.stem().string() + "_parts");
  fs::create_directories(tmp);
  const auto curve = [](const std::string& name, const Table& t, const std::string& col) {
    io::Curve c{name, t["vertices"], t[col]};
    return c;
  };
  io::PictureOptions plot;
  plot.width = 900;
  const std::string l2png = (tmp / "l2.png").string(), h1png = (tmp / "h1.png").string();
  io::drawLogLogPlot(l2png, {curve("FreeFem++ L2", ff, "l2_error"), curve("ablmg L2", ab, "l2_error")}, {-1.0},
                     "vertices N", "L2 error", "L2 error (P1), wave front", plot);
  io::drawLogLogPlot(h1png, {curve("FreeFem++ H1", ff, "h1_error"), curve("ablmg H1", ab, "h1_error")}, {-0.5},
                     "vertices N", "H1 error", "H1 seminorm error (P1), wave front", plot);
  const Mesh2 ffMeshFinal = io::readMesh(arg["--freefem-mesh"]);
  const std::string abMeshPath = (fs::path(arg["--ablmg"]) / ("cycle_" + std::to_string(nab - 1) + ".mesh")).string();
  const Mesh2 abMeshFinal = io::readMesh(abMeshPath);
  io::PictureOptions meshOptions;
  meshOptions.width = 1400;  // drawn large, scaled down by half in the tile: thin edges stay visible
  meshOptions.lineWidth = 0.5;
  const std::string ffpng = (tmp / "freefem_mesh.png").string(), abpng = (tmp / "ablmg_mesh.png").string();
  io::drawMesh(ffpng, ffMeshFinal, {}, "", meshOptions);
  io::drawMesh(abpng, abMeshFinal, {}, "", meshOptions);
  io::PictureOptions page;
  page.width = 1800;
  io::tilePictures(
      png.string(), {l2png, h1png, ffpng, abpng}, 2,
      {"", "", "FreeFem++ adaptmesh, final mesh: " + std::to_string(ffMeshFinal.numVertices()) + " vertices",
       "ablmg, final mesh: " + std::to_string(abMeshFinal.numVertices()) + " vertices"},
      page);
  fs::remove_all(tmp);
  std::cout << "Wrote " << arg["--md"] << " and " << png.string() << "\n";
  return 0;
} catch (const std::exception& e) {
  std::cerr << "compare_freefem_plot: " << e.what() << "\n";
  return 1;
}
