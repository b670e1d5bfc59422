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

// The output variables of outr/curv/curx, one function each, computed from the particle
// arrays and the material's MaterialParams only (a new material needs no change here):
//   seqv von Mises stress sqrt(3/2 s:s)      epef equivalent plastic strain
//   mat  material number (1-based)           pres pressure -(sxx + syy + szz)/3
//   volu volume                              engk kinetic energy m |v|^2 / 2
//   engi internal energy                     velx vely velz velocity components
//   cels temperature (0 without a thermal material)
//   fail 1 when the material has a failure strain eps_f (sjcf, jcf) and epeff >= eps_f
//   damg epeff / eps_f clipped to [0, 1] (0 without eps_f)
//   sspd longitudinal wave speed sqrt((K + 4G/3) / rho) at the current density, K the
//        EOS's reference bulk modulus (rho0 c0^2 Mie-Gruneisen, C1 polynomial) or
//        lambda + 2G/3 without an EOS; the material's wave speed when K + 4G/3 <= 0
using ParticleVarFn = double (*)(const Model& m, int p);
struct OutputVariable {
  const char* name;
  ParticleVarFn fn;
};
const std::vector<OutputVariable>& output_variables();
ParticleVarFn output_variable(const std::string& name);  // nullptr for an unknown name
double particle_variable(const Model& m, const std::string& var, int p);

// Writes the final particle state (docs/DESIGN.md section 6) atomically (temporary + rename).
void write_state_h5(const std::string& path, const Model& m, double time, long step, double dt);

struct OutputSchedule;

// HDF5 + XDMF time series of the animation (deck keyword 'hdf5', option --hdf5):
// name_anim.h5 holds one group /frames/<k> per output time with attributes time and step,
// datasets position (np,3) and one (np) dataset per outr variable; name_anim.xdmf (Xdmf 3,
// a temporal collection of uniform Polyvertex grids) points at them, so ParaView opens the
// animation directly. The .h5 file is opened, extended and closed at each frame, and the
// .xdmf rewritten (temporary + rename).
class H5Series {
 public:
  // resume_frames: frames kept from an earlier run (restart); later groups are removed.
  void open(const Model& m, const std::string& dir, const std::vector<double>& resume_times);
  void frame(const Model& m, double time, long step);
  bool is_open() const { return !h5_.empty(); }
  std::string h5_path() const { return dir_ + "/" + h5_; }
  std::string xdmf_path() const { return dir_ + "/" + xdmf_; }

 private:
  std::string dir_, h5_, xdmf_;
  std::vector<std::string> vars_;
  std::vector<double> times_;  // times_[k]: time of /frames/<k>
  int np_ = 0;
  size_t first_ = 0;           // first frame present in the .h5 file
  void write_xdmf();
};

// Legacy per-step and animation files (plus the HDF5 series when asked). Files are created
// in open() and appended as the run goes; nothing is opened when output is off. On a
// restart (resume given) the text files are truncated to their sizes at the checkpoint and
// appended to.
class LegacyOutput {
 public:
  ~LegacyOutput();
  void open(const Model& m, const std::string& dir, bool legacy, bool series, const OutputSchedule* resume);
  void log(const std::string& line);       // name.out
  void step(const Model& m, double time, double ke, double ie, const double mom[3]);
  void frame(const Model& m, double time, long step);  // TecPlot zone, ParaView file, HDF5 group
  bool animates() const { return tec_ || paraview_ || series_.is_open(); }
  // Flushes the text files and records their sizes and the frames written so far.
  void save_state(OutputSchedule& o);
  // ContforcPlot.dat (decks with 'cont'): time and the contact force on component 1.
  void contact(double time, const double force[3]);
  void close();
  std::vector<std::string> written;
  const H5Series& series() const { return series_; }

 private:
  std::string dir_, base_;
  FILE *out_ = nullptr, *curv_ = nullptr, *energy_ = nullptr, *momentum_ = nullptr, *tec_ = nullptr;
  bool paraview_ = false;
  FILE* contact_ = nullptr;
  std::vector<std::pair<double, std::string>> pvd_;
  std::vector<double> frame_times_;
  H5Series series_;
  std::vector<ParticleVarFn> anim_fn_, curve_fn_;
  std::vector<int> curve_at_;  // stored index of each curve's particle
  FILE* create(const std::string& name, const OutputSchedule* resume, bool& appended);
};

}  // namespace mpm3d
