#include "io/text_scanner.hpp"

#include "core/error.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace ablmg::io {

TextScanner::TextScanner(std::string text, std::string name) : text_(std::move(text)), name_(std::move(name)) {}

std::string readTextFile(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  ABLMG_REQUIRE(is, path << ": cannot open for reading");
  std::ostringstream ss;
  ss << is.rdbuf();
  ABLMG_REQUIRE(!is.bad(), path << ": read error");
  return ss.str();
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
