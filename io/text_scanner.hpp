#pragma once
/// TextScanner: whitespace-separated tokens of a text file with their line numbers, for the
/// medit and Triangle parsers. '#' starts a comment to the end of the line. Every error it
/// throws is an ablmg::InputError "<name>:<line>: <problem>", never a crash, whatever the bytes.
/// Internal to io/ (not part of the public API).
#include <string>
#include <string_view>

namespace ablmg::io {

/// The whole file as a string; throws InputError "<path>: cannot open for reading".
std::string readTextFile(const std::string& path);

class TextScanner {
 public:
  /// `name` is what messages call the file (usually its path's file name or full path).
  TextScanner(std::string text, std::string name);

  /// True when only whitespace/comments remain.
  bool atEnd();
  /// Next token without consuming it ("" at the end).
  std::string_view peek();
  /// Consumes and returns the next token; at the end throws "<name>:<line>: unexpected end of
  /// file, expected <what>".
  std::string_view next(const char* what);
  /// Next token as a finite double / an int in [lo, hi]; errors name the token and `what`.
  double nextDouble(const char* what);
  long nextInt(const char* what, long lo, long hi);
  /// If the next token starts with '"', consumes the quoted string (it may contain spaces,
  /// '#' and newlines; medit's Identifier/Geometry sections) and returns true.
  bool skipQuotedString();
  /// Line of the last token returned by next() (1-based).
  int line() const { return lastLine_; }
  const std::string& name() const { return name_; }
  /// Size of the text in bytes (for bounding counts read from the file).
  std::size_t size() const { return text_.size(); }
  /// "<name>:<line>: " for messages about the last token.
  std::string where() const;
  /// True if the token parses completely as a number (including nan/inf).
  static bool isNumber(std::string_view tok);

 private:
  void skipSpace();
  std::string text_, name_;
  std::size_t pos_ = 0;
  int curLine_ = 1, lastLine_ = 1;
};

}  // namespace ablmg::io
