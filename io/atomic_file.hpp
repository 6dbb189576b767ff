#pragma once
/// Atomic output files: write to a temporary name in the same directory, then rename() it
/// over the destination. rename() within one file system is atomic (POSIX), so readers see
/// either the previous file or the complete new one, and a failed run (exception, full disk)
/// never leaves a half-written file; the temporary is removed on failure.
///
/// Temporary name: "<dir>/.<basename>.tmp.<pid>.<counter><ext>" — it keeps the destination's
/// extension, so writers that choose the format by extension (VTK, cairo) still work.
#include <functional>
#include <ostream>
#include <string>

namespace ablmg::io {

/// Opens a temporary file, calls `writer(stream)`, checks the stream, renames into `path`.
/// Throws ablmg::Error ("<path>: cannot open for writing", "...: write failed") and rethrows
/// whatever `writer` throws; in every failure case `path` is left untouched.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& writer);

/// For writers that need a file name (VTK, cairo): calls `writer(tmpPath)`, which must create
/// tmpPath, then renames it into `path`. Same guarantees as writeFileAtomically().
void writePathAtomically(const std::string& path, const std::function<void(const std::string& tmpPath)>& writer);

/// The temporary name used for `path` (exposed for tests).
std::string temporaryPathFor(const std::string& path);

}  // namespace ablmg::io
