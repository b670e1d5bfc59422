// The legacy curve files, one line per step: name.out (the run log), name_curv.dat,
// EnergyPlot.dat, MomentumPlot.dat, and ContforcPlot.dat for contact decks.
#include <cstdio>

#include "io/data_out.hpp"
#include "io/output_schedule.hpp"
#include "io/output_writer.hpp"

namespace mpm3d {

namespace {

void record(FILE* f, const std::string& name, std::vector<std::pair<std::string, long long>>& files) {
  std::fflush(f);
  files.emplace_back(name, (long long)std::ftell(f));
}

class CurveWriter : public OutputWriter {
 public:
  CurveWriter(const Model& m, const OutputFiles& files)
      : names_{m.base_name + ".out", m.base_name + "_curv.dat", "EnergyPlot.dat", "MomentumPlot.dat"} {
    bool appended[4];
    for (int i = 0; i < 4; ++i) {
      paths_[i] = files.path(names_[i]);
      f_[i] = files.create(names_[i], appended[i]);
    }
    if (appended[0]) std::fprintf(out(), "(restarted)\n");
    if (!appended[1]) {
      std::fprintf(curv(), "Time %-12s%-12s", "engk1", "engi1");
      for (const auto& c : m.curves) std::fprintf(curv(), "%-12s", (c.var + std::to_string(c.particle + 1)).c_str());
      std::fprintf(curv(), "\n");
    }
  }
  ~CurveWriter() override {
    for (FILE* f : f_) std::fclose(f);
  }

  void log(const std::string& line) override { std::fprintf(out(), "%s\n", line.c_str()); }

  void step(const Model& m, const StepRecord& s) override {
    const std::string t = fortran_e12_4(s.time);
    std::fprintf(energy(), "%s%s%s%s\n", t.c_str(), fortran_e12_4(s.kinetic + s.internal).c_str(),
                 fortran_e12_4(s.kinetic).c_str(), fortran_e12_4(s.internal).c_str());
    std::fprintf(momentum(), "%s%s%s%s\n", t.c_str(), fortran_e12_4(s.momentum[0]).c_str(),
                 fortran_e12_4(s.momentum[1]).c_str(), fortran_e12_4(s.momentum[2]).c_str());
    std::fprintf(curv(), "%s%s%s", t.c_str(), fortran_e12_4(s.kinetic).c_str(), fortran_e12_4(s.internal).c_str());
    for (size_t c = 0; c < m.curves.size(); ++c) std::fprintf(curv(), "%s", fortran_e12_4(s.curve_values[c]).c_str());
    std::fprintf(curv(), "\n");
  }

  void flush() override {
    for (int i = 0; i < 4; ++i) flush_file(f_[i], paths_[i]);
  }

  void record_sizes(std::vector<std::pair<std::string, long long>>& files) override {
    for (int i = 0; i < 4; ++i) record(f_[i], names_[i], files);
  }

 private:
  // name.out (the log), name_curv.dat, EnergyPlot.dat, MomentumPlot.dat: the order of a
  // checkpoint's record.
  FILE* out() const { return f_[0]; }
  FILE* curv() const { return f_[1]; }
  FILE* energy() const { return f_[2]; }
  FILE* momentum() const { return f_[3]; }
  std::string names_[4], paths_[4];
  FILE* f_[4];
};

class ContactWriter : public OutputWriter {
 public:
  explicit ContactWriter(const OutputFiles& files) : path_(files.path("ContforcPlot.dat")) {
    bool appended;
    f_ = files.create("ContforcPlot.dat", appended);
  }
  ~ContactWriter() override { std::fclose(f_); }
  // Columns: time, Fx, Fy, Fz (E12.4, as EnergyPlot.dat), the force that component 2 exerts
  // on component 1, summed over the contact nodes of the step.
  void step(const Model&, const StepRecord& s) override {
    const double* force = s.contact_force;
    std::fprintf(f_, "%s%s%s%s\n", fortran_e12_4(s.time).c_str(), fortran_e12_4(force[0]).c_str(),
                 fortran_e12_4(force[1]).c_str(), fortran_e12_4(force[2]).c_str());
  }
  void record_sizes(std::vector<std::pair<std::string, long long>>& files) override {
    record(f_, "ContforcPlot.dat", files);
  }
  void flush() override { flush_file(f_, path_); }

 private:
  std::string path_;
  FILE* f_;
};

}  // namespace

std::unique_ptr<OutputWriter> make_curve_writer(const Model& m, const OutputFiles& files) {
  return std::make_unique<CurveWriter>(m, files);
}

std::unique_ptr<OutputWriter> make_contact_writer(const OutputFiles& files) {
  return std::make_unique<ContactWriter>(files);
}

}  // namespace mpm3d
