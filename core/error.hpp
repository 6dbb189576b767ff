#pragma once
/// Errors of ablmg. Libraries throw; only cli/ and examples/ print and exit.
///
/// - `InputError`: the caller's data is wrong (a file, a field, a tensor). Its message says
///   where (file:line, key path, vertex id) and the offending value, on one line.
/// - `Error`: anything else we detect (a cap hit that cannot be recovered, a failed repair).
///
/// `ABLMG_REQUIRE(cond, msg)` stays on in release builds and throws InputError;
/// `ABLMG_ASSERT(cond, msg)` guards our own invariants and is compiled out with NDEBUG.
#include <sstream>
#include <stdexcept>
#include <string>

namespace ablmg {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InputError : public Error {
 public:
  using Error::Error;
};

}  // namespace ablmg

#define ABLMG_REQUIRE(cond, msg)                  \
  do {                                            \
    if (!(cond)) {                                \
      std::ostringstream ablmg_os_;               \
      ablmg_os_ << msg;                           \
      throw ::ablmg::InputError(ablmg_os_.str()); \
    }                                             \
  } while (0)

#define ABLMG_FAIL(msg)                    \
  do {                                     \
    std::ostringstream ablmg_os_;          \
    ablmg_os_ << msg;                      \
    throw ::ablmg::Error(ablmg_os_.str()); \
  } while (0)

#ifdef NDEBUG
#define ABLMG_ASSERT(cond, msg) ((void)0)
#else
#define ABLMG_ASSERT(cond, msg)                                   \
  do {                                                            \
    if (!(cond)) ABLMG_FAIL("internal error: " #cond " " << msg); \
  } while (0)
#endif
