#include "input/ffi.hpp"

#include <sys/stat.h>

#include <algorithm>

#include <cctype>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace mpm3d {

DeckError::DeckError(const std::string& file, int line, const std::string& what)
    : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ": " + what
                                  : file + ": " + what),
      file_(file), line_(line) {}

static constexpr size_t kMaxLine = 4096;

TokenStream TokenStream::from_file(const std::string& path) {
  struct stat st;
  if (stat(path.c_str(), &st) != 0) throw DeckError(path, 0, "cannot open the deck (no such file)");
  if (S_ISDIR(st.st_mode)) throw DeckError(path, 0, "cannot read the deck (is a directory)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DeckError(path, 0, "cannot open the deck");
  if (!S_ISREG(st.st_mode)) {  // a pipe: its size is not known before it is read
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw DeckError(path, 0, "cannot read the deck");
    return from_string(ss.str(), path);
  }
  // One read into a string of the file's size (a deck of particle lines is megabytes; a
  // stream copy grew and copied it twice).
  std::string text(size_t(st.st_size), '\0');
  in.read(&text[0], std::streamsize(text.size()));
  if (in.bad() || size_t(in.gcount()) != text.size()) throw DeckError(path, 0, "cannot read the deck");
  return from_string(std::move(text), path);
}

TokenStream TokenStream::from_string(std::string deck, const std::string& name) {
  TokenStream ts;
  ts.name_ = name;
  ts.text_ = std::make_shared<const std::string>(std::move(deck));
  const std::string& text = *ts.text_;
  int lineno = 0;
  size_t i = 0;
  ts.lines_.reserve(size_t(std::count(text.begin(), text.end(), '\n')) + 1);
  // A token takes at least two bytes (one and a separator), a particle line's some four to
  // ten: room for a quarter of the bytes regrows on no deck of particle lines.
  ts.tokens_.reserve(text.size() / 4 + 16);
  while (i < text.size() || (i == 0 && text.empty())) {
    size_t j = text.find('\n', i);
    if (j == std::string::npos) j = text.size();
    std::string_view line(text.data() + i, j - i);
    i = j + 1;
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.size() > kMaxLine)
      throw DeckError(name, lineno, "line longer than 4096 characters");
    ts.lines_.push_back(line);
    size_t k = 0;
    const size_t n = line.size();
    bool first = true;
    while (k < n) {
      const unsigned char c = static_cast<unsigned char>(line[k]);
      if (c == '!') break;
      if (c == ' ' || c == '\t' || c == ',') { ++k; continue; }
      size_t e = k;
      while (e < n && line[e] != ' ' && line[e] != '\t' && line[e] != ',' && line[e] != '!') {
        const unsigned char b = static_cast<unsigned char>(line[e]);
        if (b < 32 || b > 126)
          throw DeckError(name, lineno, "unexpected binary character (code " + std::to_string(b) + ")");
        ++e;
      }
      ts.tokens_.push_back({TokenText(line.substr(k, e - k)), lineno});
      // The title card (mpm3...) takes the rest of its line as free text, any bytes.
      if (first && key4(ts.tokens_.back().text) == "mpm3") break;
      first = false;
      k = e;
    }
    if (j == text.size()) break;
  }
  return ts;
}

const Token& TokenStream::peek() const {
  if (at_end()) fail(line(), "unexpected end of file (missing 'endi'?)");
  return tokens_[pos_];
}

const Token& TokenStream::next() {
  const Token& t = peek();
  ++pos_;
  return t;
}

int TokenStream::line() const {
  if (pos_ < tokens_.size()) return tokens_[pos_].line;
  return static_cast<int>(lines_.size());
}

std::string TokenStream::rest_of_line(const Token& after) {
  const std::string_view l = lines_.at(after.line - 1);
  size_t p = l.find(after.text);
  std::string rest = p == std::string::npos ? std::string() : std::string(l.substr(p + after.text.size()));
  size_t b = rest.find_first_not_of(" \t");
  rest = b == std::string::npos ? std::string() : rest.substr(b);
  while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t')) rest.pop_back();
  skip_line(after);
  return rest;
}

void TokenStream::skip_line(const Token& of) {
  while (pos_ < tokens_.size() && tokens_[pos_].line == of.line) ++pos_;
}

void TokenStream::fail(int line, const std::string& what) const {
  throw DeckError(name_, line, what);
}

double TokenStream::real(const char* what) {
  if (at_end()) fail(line(), std::string("unexpected end of file while reading ") + what);
  const Token& t = next();
  double v;
  if (!parse_real(t.text, v)) {
    if (card_line_ > 0 && t.line != card_line_)
      fail(card_line_, card_ + " ends before " + what + " ('" + t.text + "' on line " + std::to_string(t.line) +
                           " is not a number): the card is short of numbers (docs/DECK_FORMAT.md lists each card's)");
    fail(t.line, std::string("Non Numeric Field '") + t.text + "' where " + what + " was expected");
  }
  if (single_reals_) {  // the decimal text rounded once to single precision (strtof), as a Fortran read
    std::string e(t.text);
    for (char& ch : e)
      if (ch == 'd' || ch == 'D') ch = 'e';
    v = double(std::strtof(e.c_str(), nullptr));
  }
  return v;
}

long TokenStream::integer(const char* what) {
  if (at_end()) fail(line(), std::string("unexpected end of file while reading ") + what);
  const Token& t = next();
  long v;
  if (!parse_integer(t.text, v))
    fail(t.line, std::string("Non Numeric Field '") + t.text + "' where an integer (" + what +
                     ") was expected");
  return v;
}

std::string TokenStream::word(const char* what) {
  if (at_end()) fail(line(), std::string("unexpected end of file while reading ") + what);
  return next().text;
}

std::string key4(std::string_view token) {
  std::string k(token.substr(0, 4));
  for (char& c : k) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return k;
}

bool parse_real(std::string_view token, double& value) {
  if (token.empty() || token.size() > 64) return false;
  std::string s(token);
  // Fortran exponent letters d/D/q become e; a bare sign-less exponent such as 1.0-3 is not accepted.
  bool seen_digit = false, seen_exp = false, seen_dot = false;
  for (size_t i = 0; i < s.size(); ++i) {
    char& c = s[i];
    if (std::isdigit(static_cast<unsigned char>(c))) { seen_digit = true; continue; }
    if ((c == '+' || c == '-') && (i == 0 || std::tolower(s[i - 1]) == 'e')) continue;
    if (c == '.' && !seen_dot && !seen_exp) { seen_dot = true; continue; }
    if ((c == 'd' || c == 'D' || c == 'e' || c == 'E') && seen_digit && !seen_exp &&
        i + 1 < s.size()) {
      c = 'e';
      seen_exp = true;
      continue;
    }
    return false;
  }
  if (!seen_digit) return false;
  errno = 0;
  char* end = nullptr;
  value = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) return false;
  if (errno == ERANGE && (value > 1.0 || value < -1.0)) return false;  // overflow
  return std::isfinite(value);
}

bool parse_integer(std::string_view token, long& value) {
  if (token.empty() || token.size() > 18) return false;
  size_t i = (token[0] == '+' || token[0] == '-') ? 1 : 0;
  if (i == token.size()) return false;
  // At most 18 characters: the value fits a long, so it is summed digit by digit (exact, as
  // strtol) without a NUL-terminated copy of the view.
  long v = 0;
  for (size_t k = i; k < token.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(token[k]))) return false;
    v = 10 * v + (token[k] - '0');
  }
  value = token[0] == '-' ? -v : v;
  return true;
}

bool TokenStream::has_keyword(const std::vector<std::string>& keys) const {
  size_t i = 0;
  if (!tokens_.empty() && key4(tokens_[0].text) == "mpm3")  // the title line is free text
    while (i < tokens_.size() && tokens_[i].line == tokens_[0].line) ++i;
  for (; i < tokens_.size(); ++i) {
    const char c0 = tokens_[i].text[0];  // a number is no keyword (most of a deck's tokens)
    if ((c0 >= '0' && c0 <= '9') || c0 == '-' || c0 == '+' || c0 == '.') continue;
    const std::string k = key4(tokens_[i].text);
    for (const auto& key : keys)
      if (k == key) return true;
  }
  return false;
}

}  // namespace mpm3d
