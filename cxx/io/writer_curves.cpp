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
      : base_(m.base_name),
        paths_{files.path(base_ + ".out"), files.path(base_ + "_curv.dat"), files.path("EnergyPlot.dat"),
               files.path("MomentumPlot.dat")} {
    bool appended;
    out_ = files.create(base_ + ".out", appended);
    if (appended) std::fprintf(out_, "(restarted)\n");
    bool curv_appended;
    curv_ = files.create(base_ + "_curv.dat", curv_appended);
    energy_ = files.create("EnergyPlot.dat", appended);
    momentum_ = files.create("MomentumPlot.dat", appended);
    if (!curv_appended) {
      std::fprintf(curv_, "Time %-12s%-12s", "engk1", "engi1");
      for (const auto& c : m.curves) std::fprintf(curv_, "%-12s", (c.var + std::to_string(c.particle + 1)).c_str());
      std::fprintf(curv_, "\n");
    }
  }
  ~CurveWriter() override {
    for (FILE* f : {out_, curv_, energy_, momentum_}) std::fclose(f);
  }

  void log(const std::string& line) override { std::fprintf(out_, "%s\n", line.c_str()); }

  void step(const Model& m, const StepRecord& s) override {
    const std::string t = fortran_e12_4(s.time);
    std::fprintf(energy_, "%s%s%s%s\n", t.c_str(), fortran_e12_4(s.kinetic + s.internal).c_str(),
                 fortran_e12_4(s.kinetic).c_str(), fortran_e12_4(s.internal).c_str());
    std::fprintf(momentum_, "%s%s%s%s\n", t.c_str(), fortran_e12_4(s.momentum[0]).c_str(),
                 fortran_e12_4(s.momentum[1]).c_str(), fortran_e12_4(s.momentum[2]).c_str());
    std::fprintf(curv_, "%s%s%s", t.c_str(), fortran_e12_4(s.kinetic).c_str(), fortran_e12_4(s.internal).c_str());
    for (size_t c = 0; c < m.curves.size(); ++c) std::fprintf(curv_, "%s", fortran_e12_4(s.curve_values[c]).c_str());
    std::fprintf(curv_, "\n");
  }

  void flush() override {
    FILE* const order[4] = {out_, curv_, energy_, momentum_};
    for (int i = 0; i < 4; ++i) flush_file(order[i], paths_[i]);
  }

  void record_sizes(std::vector<std::pair<std::string, long long>>& files) override {
    record(out_, base_ + ".out", files);
    record(curv_, base_ + "_curv.dat", files);
    record(energy_, "EnergyPlot.dat", files);
    record(momentum_, "MomentumPlot.dat", files);
  }

 private:
  std::string base_;
  std::string paths_[4];  // of out_, curv_, energy_, momentum_
  FILE *out_, *curv_, *energy_, *momentum_;
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
