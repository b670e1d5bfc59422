// Numbers as text into a buffer written to a file in blocks, with printf's "%.<d>E" and "%d"
// text, made by std::to_chars (the same correctly rounded digits, several times faster: an
// ASCII ParaView frame of a small deck took as long as hundreds of its steps). Values that
// are not finite go through printf itself.
#pragma once
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>

namespace mpm3d {

class AsciiOut {
 public:
  explicit AsciiOut(FILE* f) : f_(f) {}
  ~AsciiOut() { flush(); }
  AsciiOut(const AsciiOut&) = delete;
  AsciiOut& operator=(const AsciiOut&) = delete;

  // printf("%.<digits>E", x), digits <= 17.
  void sci(double x, int digits) {
    room(40);
    char* at = buf_ + used_;
    if (!std::isfinite(x)) {
      used_ += size_t(std::snprintf(at, 40, "%.*E", digits, x));
      return;
    }
    char* end = std::to_chars(at, buf_ + sizeof buf_, x, std::chars_format::scientific, digits).ptr;
    for (char* c = end - 1; c > at; --c)  // the exponent's 'e', at most 5 from the end
      if (*c == 'e') {
        *c = 'E';
        break;
      }
    used_ = size_t(end - buf_);
  }
  void integer(long long x) {
    room(24);
    used_ = size_t(std::to_chars(buf_ + used_, buf_ + sizeof buf_, x).ptr - buf_);
  }
  void put(char c) {
    room(1);
    buf_[used_++] = c;
  }
  void flush() {
    if (used_) std::fwrite(buf_, 1, used_, f_);
    used_ = 0;
  }

 private:
  void room(size_t n) {
    if (used_ + n > sizeof buf_) flush();
  }
  FILE* f_;
  char buf_[1 << 16];
  size_t used_ = 0;
};

}  // namespace mpm3d
