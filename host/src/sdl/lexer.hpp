// The SDL's tokens (docs/reference/sdl.md, "Lexical structure"): identifiers, numbers, strings,
// symbols; comments and white space are skipped. Internal to host/src/sdl.
#pragma once

#include <memory>
#include <string>
#include <string_view>

namespace syncap::sdl::detail {

// Where a token starts: 1-based line and column (columns count bytes).
struct Position {
  std::shared_ptr<const std::string> file;
  int line = 1;
  int column = 1;
};

// kEndOfInclude: where an included file ended (the parser accepts it only between statements
// and between the items of a block, so that an included file holds whole ones).
enum class TokenKind { kIdentifier, kNumber, kString, kSymbol, kEndOfInclude, kEnd };

struct Token {
  TokenKind kind = TokenKind::kEnd;
  std::string text;     // identifier, string contents (escapes resolved), symbol, number as written
  double number = 0.0;  // kNumber
  Position position;
};

// How a token is named in an error message: identifier 'x', number 1.5, string "x", '{'.
std::string describe(const Token& token);

// Splits one file's text into tokens. Throws ParseError at the offending character for a
// character no token starts with, an unterminated string or comment, a malformed number.
class Lexer {
 public:
  Lexer(std::string text, std::shared_ptr<const std::string> file);

  Token next();

 private:
  void skip_space_and_comments();
  Token number();
  Token string();
  char peek(size_t ahead = 0) const;
  void advance();
  Position here() const;
  [[noreturn]] void fail(const Position& at, const std::string& message) const;

  std::string text_;
  std::shared_ptr<const std::string> file_;
  size_t offset_ = 0;
  int line_ = 1;
  int column_ = 1;
};

}  // namespace syncap::sdl::detail
