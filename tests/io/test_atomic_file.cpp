// Tests of io/atomic_file.hpp: a writer that throws leaves the previous file intact and no
// temporary behind.
#include "ablmg/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace ablmg;
namespace fs = std::filesystem;

static std::string slurp(const std::string& p) {
  std::ifstream is(p);
  std::ostringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

static int filesIn(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, FailedWriterLeavesOldFileIntact) {
  const fs::path dir = fs::temp_directory_path() / ("ablmg_atomic_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string p = (dir / "out.txt").string();
  io::writeFileAtomically(p, [](std::ostream& os) { os << "old content\n"; });
  EXPECT_EQ(slurp(p), "old content\n");
  EXPECT_THROW(io::writeFileAtomically(p,
                                       [](std::ostream& os) {
                                         os << "half of the new";
                                         throw std::runtime_error("killed mid-way");
                                       }),
               std::runtime_error);
  EXPECT_EQ(slurp(p), "old content\n");
  EXPECT_EQ(filesIn(dir), 1);  // no temporary left behind
  EXPECT_THROW(io::writePathAtomically(p,
                                       [](const std::string& tmp) {
                                         std::ofstream(tmp) << "partial";
                                         throw std::runtime_error("VTK failed");
                                       }),
               std::runtime_error);
  EXPECT_EQ(slurp(p), "old content\n");
  EXPECT_EQ(filesIn(dir), 1);
  io::writeFileAtomically(p, [](std::ostream& os) { os << "new\n"; });
  EXPECT_EQ(slurp(p), "new\n");
  fs::remove_all(dir);
}

TEST(AtomicFile, UnwritableDirectoryThrows) {
  EXPECT_ANY_THROW(io::writeFileAtomically("/nonexistent-dir-ablmg/x.mesh", [](std::ostream& os) { os << 1; }));
}

TEST(AtomicFile, TemporaryKeepsDirectoryAndExtension) {
  const std::string t = io::temporaryPathFor("/a/b/out.vtu");
  EXPECT_EQ(fs::path(t).parent_path(), fs::path("/a/b"));
  EXPECT_EQ(fs::path(t).extension(), ".vtu");
  EXPECT_NE(t, io::temporaryPathFor("/a/b/out.vtu"));
}
