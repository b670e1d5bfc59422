// The TecPlot animation name_anim.dat: a header naming X, Y, Z and the outr variables, then
// one POINT zone per frame (particles skipped by 'tecp's list left out).
#include <cstdio>

#include "io/ascii_out.hpp"
#include "io/data_out.hpp"
#include "io/output_writer.hpp"

namespace mpm3d {

namespace {

class TecplotWriter : public OutputWriter {
 public:
  TecplotWriter(const Model& m, const OutputFiles& files) : name_(m.base_name + "_anim.dat"), path_(files.path(name_)) {
    for (const auto& v : m.anim_vars) fn_.push_back(output_variable(v));
    bool appended;
    f_ = files.create(name_, appended);
    if (!appended) {
      std::fprintf(f_, "TITLE = \"%s\"\nVARIABLES = \"X\", \"Y\", \"Z\"", m.title.c_str());
      for (const auto& v : m.anim_vars) std::fprintf(f_, ", \"%s\"", v.c_str());
      std::fprintf(f_, "\n");
    }
  }
  ~TecplotWriter() override { std::fclose(f_); }

  void frame(const Model& m, const std::vector<int>& at, double time, long) override {
    const Particles& P = m.particles;
    const bool all = m.tec_skip.empty();  // indexed by deck number
    int n = 0;
    for (int i = 0; i < P.np; ++i) n += all || !m.tec_skip[size_t(i)];
    std::fprintf(f_, "ZONE T=\"%.6E\" I=%d F=POINT\n", time, n);
    AsciiOut out(f_);  // each line "%.6E %.6E %.6E" and " %.6E" per variable
    for (int i = 0; i < P.np; ++i) {
      if (!all && m.tec_skip[size_t(i)]) continue;
      const int p = at[size_t(i)];
      const double* x = &P.x[3 * size_t(p)];
      for (int d = 0; d < 3; ++d) {
        if (d) out.put(' ');
        out.sci(x[d], 6);
      }
      for (const ParticleVarFn fn : fn_) {
        out.put(' ');
        out.sci(fn(m, p), 6);
      }
      out.put('\n');
    }
  }

  void flush() override { flush_file(f_, path_); }

  void record_sizes(std::vector<std::pair<std::string, long long>>& files) override {
    std::fflush(f_);
    files.emplace_back(name_, (long long)std::ftell(f_));
  }

 private:
  std::string name_, path_;
  FILE* f_;
  std::vector<ParticleVarFn> fn_;
};

}  // namespace

std::unique_ptr<OutputWriter> make_tecplot_writer(const Model& m, const OutputFiles& files) {
  return std::make_unique<TecplotWriter>(m, files);
}

}  // namespace mpm3d
