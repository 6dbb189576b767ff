#include "ablmg/io/text_scanner.hpp"

#include "ablmg/core/error.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ablmg::io {

TextScanner::TextScanner(std::string text, std::string name) : text_(std::move(text)), name_(std::move(name)) {}

std::string readTextFile(const std::string& path) {
  // One read(2) into a string sized from fstat (a loop covers short reads, pipes and files
  // that grow). A read error other than EISDIR throws; a directory reads as empty, as it did
  // through std::ifstream (its parser then reports "empty file").
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  ABLMG_REQUIRE(fd >= 0, path << ": cannot open for reading");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  std::string text;
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) text.resize(std::size_t(st.st_size) + 1);
  std::size_t used = 0;
  for (;;) {
    if (used == text.size()) text.resize(std::max<std::size_t>(2 * text.size(), 1 << 16));
    const ssize_t got = ::read(fd, text.data() + used, text.size() - used);
    if (got > 0) {
      used += std::size_t(got);
    } else if (got == 0) {
      break;
    } else if (errno == EINTR) {
      continue;
    } else {
      ABLMG_REQUIRE(errno == EISDIR, path << ": read error");
      break;
    }
  }
  text.resize(used);
  return text;
}

void TextScanner::skipSpace() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++curLine_;
      ++pos_;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
    } else if (c == '#') {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

bool TextScanner::atEnd() {
  skipSpace();
  return pos_ >= text_.size();
}

static bool isDelimiter(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' || c == '#';
}

std::string_view TextScanner::peek() {
  skipSpace();
  std::size_t end = pos_;
  while (end < text_.size() && !isDelimiter(text_[end])) ++end;
  return std::string_view(text_).substr(pos_, end - pos_);
}

std::string_view TextScanner::next(const char* what) {
  skipSpace();
  if (pos_ >= text_.size()) {
    ABLMG_REQUIRE(false, name_ << ":" << lastLine_ << ": unexpected end of file (truncated?), expected " << what);
  }
  std::size_t end = pos_;
  while (end < text_.size() && !isDelimiter(text_[end])) ++end;
  auto tok = std::string_view(text_).substr(pos_, end - pos_);
  lastLine_ = curLine_;
  pos_ = end;
  return tok;
}

bool TextScanner::skipQuotedString() {
  skipSpace();
  if (pos_ >= text_.size() || text_[pos_] != '"') return false;
  lastLine_ = curLine_;
  const int startLine = curLine_;
  for (++pos_; pos_ < text_.size() && text_[pos_] != '"'; ++pos_)
    if (text_[pos_] == '\n') ++curLine_;
  ABLMG_REQUIRE(pos_ < text_.size(), name_ << ":" << startLine << ": unterminated quoted string");
  ++pos_;
  return true;
}

std::string TextScanner::where() const { return name_ + ":" + std::to_string(lastLine_) + ": "; }

/// A printable rendering of a token for messages (garbage bytes become '?', long tokens cut).
static std::string printable(std::string_view tok) {
  std::string s;
  for (char c : tok.substr(0, 40)) s += (c >= 32 && c < 127) ? c : '?';
  if (tok.size() > 40) s += "...";
  return s;
}

bool TextScanner::isNumber(std::string_view tok) {
  if (tok.empty() || tok.size() > 400) return false;
  const std::string s(tok);
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

/// The end of the number std::from_chars reads at text[pos], if it is the whole token (a
/// delimiter or the end follows) and at most maxLength characters long; nullptr otherwise.
template <class T>
static const char* wholeNumber(const std::string& text, std::size_t pos, std::size_t maxLength, T& value) {
  const char* first = text.data() + pos;
  const char* last = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr == first || std::size_t(ptr - first) > maxLength || (ptr != last && !isDelimiter(*ptr)))
    return nullptr;
  return ptr;
}

double TextScanner::nextDouble(const char* what) {
  // Fast path: std::from_chars straight from the text, correctly rounded as strtod is. A token
  // it does not take whole ('+' signs, hex, inf/nan, over- and underflow, garbage, over 400
  // characters) goes through strtod below, so the accepted syntax, the values and the
  // messages stay strtod's.
  skipSpace();
  double fast = 0;
  if (const char* end = wholeNumber(text_, pos_, 400, fast); end && std::isfinite(fast)) {
    lastLine_ = curLine_;
    pos_ = std::size_t(end - text_.data());
    return fast;
  }
  const auto tok = next(what);
  const std::string s(tok.substr(0, 400));
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  ABLMG_REQUIRE(!s.empty() && tok.size() <= 400 && end == s.c_str() + s.size(),
                where() << "expected " << what << " (a number), got '" << printable(tok) << "'");
  ABLMG_REQUIRE(std::isfinite(v), where() << what << " is not finite: '" << printable(tok) << "'");
  return v;
}

long TextScanner::nextInt(const char* what, long lo, long hi) {
  // Fast path as in nextDouble; '+' signs, overflow, out-of-range values and garbage take
  // strtol's path and its messages.
  skipSpace();
  long fast = 0;
  if (const char* end = wholeNumber(text_, pos_, 40, fast); end && fast >= lo && fast <= hi) {
    lastLine_ = curLine_;
    pos_ = std::size_t(end - text_.data());
    return fast;
  }
  const auto tok = next(what);
  const std::string s(tok.substr(0, 40));
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  ABLMG_REQUIRE(!s.empty() && tok.size() <= 40 && end == s.c_str() + s.size() && errno == 0,
                where() << "expected " << what << " (an integer), got '" << printable(tok) << "'");
  ABLMG_REQUIRE(v >= lo && v <= hi, where() << what << " " << v << " is out of range [" << lo << ", " << hi << "]");
  return v;
}

}  // namespace ablmg::io
