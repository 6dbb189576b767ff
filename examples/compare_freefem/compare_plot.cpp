// compare_freefem_plot: the tables and the picture of examples/compare_freefem/run.sh for one problem.
//
//   compare_freefem_plot --problem LABEL --freefem freefem.csv --freefem-mesh freefem_final.mesh --ablmg DIR
//                        --png compare.png --md compare.md --summary summary.md
//                        [--freefem-wall S] [--ablmg-wall S] [--reach-wall S] [--min-vertices N]
//
// Inputs: FreeFem++'s CSV (loop.idp: cycle,vertices,triangles,l2_error,h1_error,t_solve,
// t_mesh; CPU seconds), its last mesh (medit), and the output directory of `ablmg adapt
// --medit on` (convergence.csv with wall seconds per phase, cycle_K.mesh). Wall times measured
// by run.sh: both whole loops, and ablmg's run stopped at FreeFem's final H1 error (--reach-wall).
//
// Steps: 1. read both CSVs; 2. error ratios ablmg / FreeFem at ablmg's N, FreeFem's adapted
// curve (cycles ≥ 1) interpolated log-log (extrapolated along its end segment outside its
// range, marked *); 3. rates over the last 4 sizes (the last cycle of each target size, as
// ablmg adapt fits them); 4. the time of the cycle that builds each loop's final mesh; 5. the
// Markdown report and one summary row (the acceptance figures at N ≥ --min-vertices, default
// 5000); 6. the PNG: L2 and H1 against N over the two final meshes.
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

/// The convergence curve of ablmg's run: the last cycle of each target size.
std::vector<std::size_t> curveRows(const Table& ab) {
  std::vector<std::size_t> rows;
  for (std::size_t k = 0; k < ab.rows; ++k)
    if (k + 1 == ab.rows || ab["target_vertices"][k + 1] != ab["target_vertices"][k]) rows.push_back(k);
  return rows;
}

double slopeOf(const Table& t, const std::vector<std::size_t>& rows, const std::string& col) {
  std::vector<double> n, e;
  for (std::size_t k : rows) {
    n.push_back(t["vertices"][k]);
    e.push_back(t[col][k]);
  }
  return adapt::logLogSlope(n, e, 4);
}

}  // namespace

int main(int argc, char** argv) try {
  std::map<std::string, std::string> arg{
      {"--freefem-wall", ""}, {"--ablmg-wall", ""}, {"--reach-wall", ""}, {"--min-vertices", "5000"}};
  const std::vector<std::string> required{"--problem", "--freefem", "--freefem-mesh", "--ablmg",
                                          "--png",     "--md",      "--summary"};
  for (int i = 1; i < argc; i += 2) {
    const std::string key = argv[i];
    ABLMG_REQUIRE(arg.count(key) || std::count(required.begin(), required.end(), key),
                  "compare_freefem_plot: unknown argument '" << key << "'");
    ABLMG_REQUIRE(i + 1 < argc, "compare_freefem_plot: " << key << " needs a value");
    arg[key] = argv[i + 1];
  }
  for (const auto& key : required) ABLMG_REQUIRE(arg.count(key), "compare_freefem_plot: " << key << " is required");
  const std::string label = arg["--problem"];
  const double minN = std::stod(arg["--min-vertices"]);

  // 1. Both loops' rows.
  const Table ff = readCsv(arg["--freefem"]);
  const Table ab = readCsv((fs::path(arg["--ablmg"]) / "convergence.csv").string());
  const std::size_t nff = ff.rows, nab = ab.rows;

  // 2. Ratios at ablmg's N against FreeFem's adapted curve.
  std::vector<std::pair<double, double>> ffL2, ffH1;
  for (std::size_t k = 1; k < nff; ++k) {
    ffL2.emplace_back(ff["vertices"][k], ff["l2_error"][k]);
    ffH1.emplace_back(ff["vertices"][k], ff["h1_error"][k]);
  }
  std::vector<double> atL2(nab), atH1(nab);
  std::vector<bool> extrapolated(nab, false);
  double worstL2 = 0, worstH1 = 0, qMeanMin = 1;
  bool fall = true;
  for (std::size_t k = 0; k < nab; ++k) {
    bool e1 = false, e2 = false;
    atL2[k] = interpolateLogLog(ffL2, ab["vertices"][k], e1);
    atH1[k] = interpolateLogLog(ffH1, ab["vertices"][k], e2);
    extrapolated[k] = e1 || e2;
    if (ab["vertices"][k] >= minN) {
      worstL2 = std::max(worstL2, ab["l2_error"][k] / atL2[k]);
      worstH1 = std::max(worstH1, ab["h1_error"][k] / atH1[k]);
    }
    qMeanMin = std::min(qMeanMin, ab["q_mean"][k]);
    if (k > 0 && ab["target_vertices"][k] > ab["target_vertices"][k - 1])
      fall = fall && ab["l2_error"][k] < ab["l2_error"][k - 1] && ab["h1_error"][k] < ab["h1_error"][k - 1];
  }

  // 3. Rates over the last 4 sizes.
  std::vector<std::size_t> ffRows(nff);
  for (std::size_t k = 0; k < nff; ++k) ffRows[k] = k;
  const auto abRows = curveRows(ab);
  const double ffRateL2 = slopeOf(ff, ffRows, "l2_error"), ffRateH1 = slopeOf(ff, ffRows, "h1_error");
  const double abRateL2 = slopeOf(ab, abRows, "l2_error"), abRateH1 = slopeOf(ab, abRows, "h1_error");

  // 4. The cycle that builds the final mesh (N ≈ FreeFem's final N): ablmg's solve, recovery and
  // metric on the mesh before, then the remesh (wall s); FreeFem's solve and adaptmesh (CPU s of
  // one thread, so wall).
  const double abCycle =
      nab >= 2 ? ab["t_solve"][nab - 2] + ab["t_recover"][nab - 2] + ab["t_metric"][nab - 2] + ab["t_mesh"][nab - 1]
               : NAN;
  const double ffCycle = nff >= 2 ? ff["t_solve"][nff - 2] + ff["t_mesh"][nff - 2] : NAN;
  // 5. The Markdown report: ablmg's cycles against FreeFem's curve, then FreeFem's cycles.
  const double ffWall = arg["--freefem-wall"].empty() ? NAN : std::stod(arg["--freefem-wall"]);
  const double reach = arg["--reach-wall"].empty() ? NAN : std::stod(arg["--reach-wall"]);
  io::writeFileAtomically(arg["--md"], [&](std::ostream& os) {
    os << "### " << label << "\n\n"
       << "![" << label << "](figures/compare_freefem_" << label << ".png)\n\n"
       << "ablmg's cycles; FreeFem's error at the same N interpolated log-log on its adapted curve (* = "
          "extrapolated); times wall s (solve on mesh k; recover + metric and remesh build mesh k+1).\n\n"
       << "| cycle | N | L2 | FreeFem L2 at N | L2 ratio | H1 | FreeFem H1 at N | H1 ratio | q mean | q min | solve "
          "| recover+metric | remesh |\n"
       << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (std::size_t k = 0; k < nab; ++k) {
      const std::string star = extrapolated[k] ? "*" : "";
      const double next = k + 1 < nab ? ab["t_mesh"][k + 1] : 0.0;
      os << "| " << k << " | " << fmt("%.0f", ab["vertices"][k]) << " | " << fmt("%.3e", ab["l2_error"][k]) << " | "
         << fmt("%.3e", atL2[k]) << " | " << fmt("%.2f", ab["l2_error"][k] / atL2[k]) << star << " | "
         << fmt("%.3e", ab["h1_error"][k]) << " | " << fmt("%.3e", atH1[k]) << " | "
         << fmt("%.2f", ab["h1_error"][k] / atH1[k]) << star << " | " << fmt("%.3f", ab["q_mean"][k]) << " | "
         << fmt("%.3f", ab["q_min"][k]) << " | " << fmt("%.2f", ab["t_solve"][k]) << " | "
         << fmt("%.2f", ab["t_recover"][k] + ab["t_metric"][k]) << " | " << fmt("%.2f", next) << " |\n";
    }
    os << "\nFreeFem++'s cycles (CPU s):\n\n| cycle | N | L2 | H1 | solve | adaptmesh "
          "|\n|---:|---:|---:|---:|---:|---:|\n";
    for (std::size_t k = 0; k < nff; ++k)
      os << "| " << k << " | " << fmt("%.0f", ff["vertices"][k]) << " | " << fmt("%.3e", ff["l2_error"][k]) << " | "
         << fmt("%.3e", ff["h1_error"][k]) << " | " << fmt("%.2f", ff["t_solve"][k]) << " | "
         << fmt("%.2f", ff["t_mesh"][k]) << " |\n";
    os << "\nRates (last 4 sizes; optimal P1: L2 -1, H1 -0.5): FreeFem L2 " << fmt("%.3f", ffRateL2) << ", H1 "
       << fmt("%.3f", ffRateH1) << "; ablmg L2 " << fmt("%.3f", abRateL2) << ", H1 " << fmt("%.3f", abRateH1)
       << ". Whole loops, wall: FreeFem++ " << fmt("%.1f", ffWall) << " s, ablmg " << arg["--ablmg-wall"]
       << " s; ablmg stopped at FreeFem's final H1 error (" << fmt("%.3e", ff["h1_error"][nff - 1])
       << "): " << fmt("%.1f", reach) << " s. The cycle building the final mesh (solve, recovery, metric and "
       << "remesh; FreeFem: solve and adaptmesh): ablmg " << fmt("%.2f", abCycle) << " s, FreeFem++ "
       << fmt("%.2f", ffCycle) << " s.\n\n";
  });
  io::writeFileAtomically(arg["--summary"], [&](std::ostream& os) {
    os << "| " << label << " | " << fmt("%.0f", ab["vertices"][nab - 1]) << " | " << fmt("%.2f", worstL2) << " | "
       << fmt("%.2f", worstH1) << " | " << fmt("%.2f", abRateL2) << " / " << fmt("%.2f", abRateH1) << " | "
       << fmt("%.2f", ffRateL2) << " / " << fmt("%.2f", ffRateH1) << " | " << (fall ? "yes" : "**no**") << " | "
       << fmt("%.3f", qMeanMin) << " | " << fmt("%.1f", reach) << " / " << fmt("%.1f", ffWall) << " = "
       << fmt("%.2f", reach / ffWall) << " | " << fmt("%.2f", abCycle) << " / " << fmt("%.2f", ffCycle) << " = "
       << fmt("%.2f", abCycle / ffCycle) << " |\n";
  });

  // 6. The picture: L2 and H1 vs N on top, FreeFem's and ablmg's final meshes below.
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
                     "vertices N", "L2 error", "L2 error (P1), " + label, plot);
  io::drawLogLogPlot(h1png, {curve("FreeFem++ H1", ff, "h1_error"), curve("ablmg H1", ab, "h1_error")}, {-0.5},
                     "vertices N", "H1 error", "H1 seminorm error (P1), " + label, plot);
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
  page.width = 1200;  // docs/figures stays under 2 MB per problem with 10^5-vertex meshes
  io::tilePictures(
      png.string(), {l2png, h1png, ffpng, abpng}, 2,
      {"", "", "FreeFem++ adaptmesh, final mesh: " + std::to_string(ffMeshFinal.numVertices()) + " vertices",
       "ablmg, final mesh: " + std::to_string(abMeshFinal.numVertices()) + " vertices"},
      page);
  fs::remove_all(tmp);
  std::cout << "Wrote " << arg["--md"] << ", " << arg["--summary"] << " and " << png.string() << "\n";
  return 0;
} catch (const std::exception& e) {
  std::cerr << "compare_freefem_plot: " << e.what() << "\n";
  return 1;
}
