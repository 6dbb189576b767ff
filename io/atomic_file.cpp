#include "ablmg/io/atomic_file.hpp"

#include "ablmg/core/error.hpp"

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace ablmg::io {

std::string temporaryPathFor(const std::string& path) {
  static std::atomic<long> counter{0};
  const std::filesystem::path p(path);
  const std::string name = "." + p.stem().string() + ".tmp." + std::to_string(::getpid()) + "." +
                           std::to_string(counter++) + p.extension().string();
  return (p.parent_path() / name).string();
}

void writePathAtomically(const std::string& path, const std::function<void(const std::string&)>& writer) {
  ABLMG_REQUIRE(!path.empty(), "output path is empty");
  const std::string tmp = temporaryPathFor(path);
  try {
    writer(tmp);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  std::error_code ec;
  if (!std::filesystem::exists(tmp, ec)) ABLMG_FAIL(path << ": writer produced no file");
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    ABLMG_FAIL(path << ": cannot rename temporary file into place");
  }
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& writer) {
  writePathAtomically(path, [&](const std::string& tmp) {
    std::ofstream os(tmp, std::ios::binary);
    if (!os) ABLMG_FAIL(path << ": cannot open for writing");
    writer(os);
    os.flush();
    if (!os) ABLMG_FAIL(path << ": write failed");
    os.close();
    if (os.fail()) ABLMG_FAIL(path << ": write failed (close)");
  });
}

}  // namespace ablmg::io
