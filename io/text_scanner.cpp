#include "io/text_scanner.hpp"

#include "core/error.hpp"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <memory>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace ablmg::io {

TextScanner::TextScanner(std::string text, std::string name) : text_(std::move(text)), name_(std::move(name)) {}

std::string readTextFile(const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  ABLMG_REQUIRE(f, path << ": cannot open for reading");
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const std::size_t got = std::fread(buf, 1, sizeof buf, f.get());
    text.append(buf, got);
    if (got < sizeof buf) break;
  }
  ABLMG_REQUIRE(!std::ferror(f.get()), path << ": read error");
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

static bool isDelimiter(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' || c == '#'; }

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

double TextScanner::nextDouble(const char* what) {
  const auto tok = next(what);
  // Fast path: a plain decimal number, parsed in place (std::from_chars, exact like strtod).
  // Anything else ('+' sign, hex, out of range, garbage) takes strtod's path below, so the
  // accepted syntax and the messages are strtod's.
  double fast = 0;
  const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), fast);
  if (ec == std::errc() && ptr == tok.data() + tok.size() && std::isfinite(fast)) return fast;
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
  const auto tok = next(what);
  long fast = 0;
  const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), fast);
  if (ec == std::errc() && ptr == tok.data() + tok.size() && fast >= lo && fast <= hi) return fast;
  const std::string s(tok.substr(0, 40));
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  ABLMG_REQUIRE(!s.empty() && tok.size() <= 40 && end == s.c_str() + s.size() && errno == 0,
                where() << "expected " << what << " (an integer), got '" << printable(tok) << "'");
  ABLMG_REQUIRE(v >= lo && v <= hi, where() << what << " " << v << " is out of range [" << lo << ", " << hi << "]");
  return v;
}

} // namespace ablmg::io
