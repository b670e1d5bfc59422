// DataOut: legacy result files (log, curves, energy and momentum plots, TecPlot and
// ParaView animations), the HDF5 state file and the summary JSON.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "data_in.hpp"

namespace mpm3d {

// Fortran E12.4 (e.g. "  0.1326E-03"), as the original writes its plot files.
std::string fortran_e12_4(double v);

// A particle variable by its output name (outr/curv): seqv epef mat pres ...
double particle_variable(const Model& m, const std::string& var, int p);

// Writes the final particle state (DESIGN.md section 6) atomically (temporary + rename).
void write_state_h5(const std::string& path, const Model& m, double time, long step, double dt);

// Legacy per-step and animation files. Files are created in open() and appended
// as the run goes; nothing is opened when output is off.
class LegacyOutput {
 public:
  ~LegacyOutput();
  void open(const Model& m, const std::string& dir);
  void log(const std::string& line);       // name.out
  void step(const Model& m, double time, double ke, double ie, const double mom[3]);
  void frame(const Model& m, double time);  // TecPlot zone and/or ParaView file
  // ContforcPlot.dat (decks with 'cont'): time and the contact force on component 1.
  void contact(double time, const double force[3]);
  void close();
  std::vector<std::string> written;

 private:
  std::string dir_, base_;
  FILE *out_ = nullptr, *curv_ = nullptr, *energy_ = nullptr, *momentum_ = nullptr, *tec_ = nullptr;
  FILE* contact_ = nullptr;
  std::vector<std::pair<double, std::string>> pvd_;
  int frames_ = 0;
  FILE* create(const std::string& name);
};

}  // namespace mpm3d
