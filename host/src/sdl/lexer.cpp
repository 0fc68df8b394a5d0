#include "sdl/lexer.hpp"

#include <cctype>
#include <charconv>
#include <cstdio>
#include <system_error>
#include <utility>

#include "sdl/sdl.hpp"

namespace syncap::sdl {

ParseError::ParseError(std::string file, int line, int column, const std::string& message)
    : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ":" +
                                        std::to_string(column) + ": " + message
                                  : file + ": " + message),
      file_(std::move(file)),
      line_(line),
      column_(column),
      message_(message) {}

namespace detail {
namespace {

bool is_identifier_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// A character as an error message shows it: printable as is, others as \xHH.
std::string shown(char c) {
  if (std::isprint(static_cast<unsigned char>(c))) return std::string("'") + c + "'";
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "'\\x%02X'", static_cast<unsigned char>(c));
  return buffer;
}

int hex_value(char c) {
  if (is_digit(c)) return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

constexpr std::string_view kSymbols = "{}<>,=+-*/()";

}  // namespace

std::string describe(const Token& token) {
  switch (token.kind) {
    case TokenKind::kIdentifier:
      return "identifier '" + token.text + "'";
    case TokenKind::kNumber:
      return "number " + token.text;
    case TokenKind::kString:
      return "string \"" + token.text + "\"";
    case TokenKind::kSymbol:
      return "'" + token.text + "'";
    case TokenKind::kEndOfInclude:
    case TokenKind::kEnd:
      break;
  }
  return "end of file";
}

Lexer::Lexer(std::string text, std::shared_ptr<const std::string> file)
    : text_(std::move(text)), file_(std::move(file)) {}

char Lexer::peek(size_t ahead) const {
  return offset_ + ahead < text_.size() ? text_[offset_ + ahead] : '\0';
}

void Lexer::advance() {
  if (text_[offset_] == '\n') {
    ++line_;
    column_ = 1;
  } else {
    ++column_;
  }
  ++offset_;
}

Position Lexer::here() const { return {file_, line_, column_}; }

void Lexer::fail(const Position& at, const std::string& message) const {
  throw ParseError(*at.file, at.line, at.column, message);
}

void Lexer::skip_space_and_comments() {
  while (offset_ < text_.size()) {
    const char c = peek();
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
      advance();
    } else if (c == '#' || (c == '/' && peek(1) == '/')) {
      while (offset_ < text_.size() && peek() != '\n') advance();
    } else if (c == '/' && peek(1) == '*') {
      const Position start = here();
      advance();
      advance();
      while (offset_ < text_.size() && !(peek() == '*' && peek(1) == '/')) advance();
      if (offset_ >= text_.size()) fail(start, "unterminated comment: expected '*/'");
      advance();
      advance();
    } else {
      return;
    }
  }
}

Token Lexer::next() {
  skip_space_and_comments();
  Token token;
  token.position = here();
  if (offset_ >= text_.size()) return token;
  const char c = peek();
  if (is_identifier_start(c)) {
    token.kind = TokenKind::kIdentifier;
    while (offset_ < text_.size() && is_identifier_char(peek())) {
      token.text += peek();
      advance();
    }
    return token;
  }
  if (is_digit(c) || (c == '.' && is_digit(peek(1)))) return number();
  if (c == '"') return string();
  if (kSymbols.find(c) != std::string_view::npos) {
    token.kind = TokenKind::kSymbol;
    token.text = std::string(1, c);
    advance();
    return token;
  }
  fail(token.position, "unexpected character " + shown(c));
}

// digits [ "." digits ] [ ("e" | "E") [ "+" | "-" ] digits ], or "." digits ...
Token Lexer::number() {
  Token token;
  token.kind = TokenKind::kNumber;
  token.position = here();
  const size_t start = offset_;
  while (is_digit(peek())) advance();
  if (peek() == '.') {
    advance();
    while (is_digit(peek())) advance();
  }
  if (peek() == 'e' || peek() == 'E') {
    advance();
    if (peek() == '+' || peek() == '-') advance();
    if (!is_digit(peek())) {
      fail(here(), "malformed number '" + text_.substr(start, offset_ - start) +
                       "': expected the digits of the exponent");
    }
    while (is_digit(peek())) advance();
  }
  token.text = text_.substr(start, offset_ - start);
  if (is_identifier_char(peek()) || peek() == '.') {
    fail(here(), "malformed number: unexpected " + shown(peek()) + " after '" + token.text + "'");
  }
  const auto [end, error] =
      std::from_chars(token.text.data(), token.text.data() + token.text.size(), token.number);
  if (error == std::errc::result_out_of_range) {
    fail(token.position, "number " + token.text + " is out of the range of a double");
  }
  if (error != std::errc() || end != token.text.data() + token.text.size()) {
    fail(token.position, "malformed number '" + token.text + "'");
  }
  return token;
}

// '"' { character | escape } '"'; escapes \" \\ \n \t \r \xHH; no raw control characters.
Token Lexer::string() {
  Token token;
  token.kind = TokenKind::kString;
  token.position = here();
  advance();  // the opening quote
  while (true) {
    if (offset_ >= text_.size() || peek() == '\n') {
      fail(token.position, "unterminated string: expected '\"' before the end of the line");
    }
    const char c = peek();
    if (c == '"') break;
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      fail(here(), "control character " + shown(c) + " in a string: write it as \\xHH");
    }
    if (c != '\\') {
      token.text += c;
      advance();
      continue;
    }
    const Position escape = here();
    advance();
    const char e = peek();
    if (e == '"' || e == '\\') {
      token.text += e;
    } else if (e == 'n') {
      token.text += '\n';
    } else if (e == 't') {
      token.text += '\t';
    } else if (e == 'r') {
      token.text += '\r';
    } else if (e == 'x' && hex_value(peek(1)) >= 0 && hex_value(peek(2)) >= 0) {
      token.text += static_cast<char>(hex_value(peek(1)) * 16 + hex_value(peek(2)));
      advance();
      advance();
    } else {
      fail(escape, "unknown escape in a string: expected \\\" \\\\ \\n \\t \\r or \\xHH");
    }
    advance();
  }
  advance();  // the closing quote
  return token;
}

}  // namespace detail
}  // namespace syncap::sdl
