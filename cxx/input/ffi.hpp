// FFI: free-format deck tokenizer (the original's FFI module).
// Rules (DECK_FORMAT.md): lines <= 4096 characters, tabs are blanks, '!' comments,
// tokens separated by blanks and/or commas, keywords recognised by their first four
// characters case-insensitively, Fortran list-directed numbers (d/D exponents).
#pragma once
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mpm3d {

// An input error: names the file, the line (0 when none applies) and the problem.
class DeckError : public std::runtime_error {
 public:
  DeckError(const std::string& file, int line, const std::string& what);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
 private:
  std::string file_;
  int line_;
};

// A token's characters: a view into its stream's deck text, which stays where it is while
// any copy of the stream lives (a deck of particle lines is millions of tokens: a string
// each cost a third of the set-up). Converts to std::string and joins strings with +, as
// the messages that quote a token need; it is not NUL-terminated (no c_str).
struct TokenText : std::string_view {
  TokenText() = default;
  TokenText(std::string_view v) : std::string_view(v) {}
  operator std::string() const { return std::string(data(), size()); }
};
inline std::string operator+(std::string a, TokenText b) { return a.append(b.data(), b.size()); }
inline std::string operator+(const char* a, TokenText b) { return std::string(a).append(b.data(), b.size()); }
inline std::string operator+(TokenText a, const std::string& b) { return std::string(a) + b; }
inline std::string operator+(TokenText a, const char* b) { return std::string(a) + b; }

struct Token {
  TokenText text;
  int line = 0;
};

class TokenStream {
 public:
  // Reads and tokenizes a whole deck; throws DeckError when it cannot be read.
  static TokenStream from_file(const std::string& path);
  static TokenStream from_string(std::string text, const std::string& name = "<string>");

  bool at_end() const { return pos_ >= tokens_.size(); }
  const Token& peek() const;
  const Token& next();  // throws "unexpected end of file" past the end
  // The rest of the current token's line, as written (used for the title).
  std::string rest_of_line(const Token& after);
  void skip_line(const Token& of);
  int line() const;      // line of the next token (or the last line at the end)
  // Whether a token after the title line is one of the keywords keys (key4 form).
  bool has_keyword(const std::vector<std::string>& keys) const;
  const std::string& name() const { return name_; }

  double real(const char* what);   // next token as a real number (rounded to single: set_single_reals)
  // Rule deck_reals=single: every real rounded to the nearest single-precision number, as
  // the original's GetReal (a default real) reads it.
  void set_single_reals(bool on) { single_reals_ = on; }
  long integer(const char* what);  // next token as an integer
  std::string word(const char* what);

  [[noreturn]] void fail(int line, const std::string& what) const;
  // While a card's numbers are read (card: "material 1's 'clay' card", line: the card's): a
  // word on a later line where a number belongs means the card is short, named at its line.
  void begin_card(int line, const std::string& card) { card_line_ = line, card_ = card; }
  void end_card() { card_line_ = 0; }

 private:
  std::string name_;
  std::shared_ptr<const std::string> text_;  // the deck, which tokens_ and lines_ view
  std::vector<Token> tokens_;
  std::vector<std::string_view> lines_;  // without their line ends
  size_t pos_ = 0;
  bool single_reals_ = false;
  int card_line_ = 0;
  std::string card_;
};

// First four characters, lower case: the keyword as the original recognises it.
std::string key4(std::string_view token);
// Fortran list-directed real; false when the token is not a complete number.
bool parse_real(std::string_view token, double& value);
bool parse_integer(std::string_view token, long& value);

}  // namespace mpm3d
