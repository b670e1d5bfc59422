// The output formats behind one interface. Each format is one OutputWriter in a file of its
// own (writer_*.cpp); Output (data_out.hpp) owns the writers the run asked for and calls
// each at every step, every animation time and every checkpoint. A new format is a new
// writer file plus one line in Output::open.
#pragma once
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "input/data_in.hpp"

namespace mpm3d {

struct OutputSchedule;

// What the run knows after a step: time, step count, energies, total momentum and the
// contact force on component 1.
struct StepRecord {
  double time = 0.0;
  long step = 0;
  double kinetic = 0.0, internal = 0.0;
  const double* momentum = nullptr;       // 3 components
  const double* contact_force = nullptr;  // 3 components; decks with 'cont' only
  // The curv/curx variables of m.curves (held_curve_values; on several ranks the largest
  // over the ranks).
  const double* curve_values = nullptr;
};

// The output directory and, on a restart, the checkpoint's record of the appended files.
// create() opens a file for writing; a file the checkpoint lists is truncated to its size
// at the checkpoint and appended to (appended = true), any other file starts empty.
class OutputFiles {
 public:
  OutputFiles(std::string dir, const OutputSchedule* resume) : dir_(std::move(dir)), resume_(resume) {}
  FILE* create(const std::string& name, bool& appended) const;
  FILE* create(const std::string& name) const;  // always a new file
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  const OutputSchedule* resume_;
};

class OutputWriter {
 public:
  virtual ~OutputWriter() = default;
  // A line of the run log (name.out).
  virtual void log(const std::string&) {}
  // After every step.
  virtual void step(const Model&, const StepRecord&) {}
  // At every animation time; at[i] is the stored index of deck particle i (files list the
  // particles in deck order).
  virtual void frame(const Model&, const std::vector<int>& /*at*/, double /*time*/, long /*step*/) {}
  // Flushes and adds (file name, bytes) of each appended file, for a checkpoint.
  virtual void record_sizes(std::vector<std::pair<std::string, long long>>&) {}
  // Hands what the appended files hold to the system (at every report and at the end), so
  // that a killed run keeps every reported step; throws std::runtime_error naming a file
  // that cannot be written (a full disk).
  virtual void flush() {}
};

// fflush(f) and its error state; throws std::runtime_error "cannot write PATH: reason".
void flush_file(FILE* f, const std::string& path);

// The legacy curves: name.out (the log), name_curv.dat (curv/curx variables),
// EnergyPlot.dat and MomentumPlot.dat; one line per step, E12.4 as the original.
std::unique_ptr<OutputWriter> make_curve_writer(const Model& m, const OutputFiles& files);
// ContforcPlot.dat (decks with 'cont'): time and the force component 2 exerts on component 1.
std::unique_ptr<OutputWriter> make_contact_writer(const OutputFiles& files);
// TecPlot animation name_anim.dat (deck keyword 'tecp'): one POINT zone per frame.
std::unique_ptr<OutputWriter> make_tecplot_writer(const Model& m, const OutputFiles& files);
// ParaView animation (deck keyword 'para'), as the original's files: name_anim_<k>.vtu per
// frame (k from 1, frame 1 the initial state), name_anim.pvd listing them, and the
// background grid name_Grid.vtu; the fields of frame_fields() (frame_fields.hpp). ASCII, or
// appended raw binary when binary (--vtu-binary).
std::unique_ptr<OutputWriter> make_vtu_writer(const Model& m, const OutputFiles& files,
                                              const std::vector<double>& frame_times, bool binary = false);
// HDF5 + XDMF series (deck keyword 'hdf5', option --hdf5): name_anim.h5 holds one group
// /frames/<k> (k from 0) per output time with attributes time and step, datasets position
// (np,3) and one (np) dataset per field of frame_fields() (an outr variable that is one of
// the original's fields under another name a hard link to that field's dataset), the
// vertex connectivity /cells (np) and the deck's grid, /grid/points (nodes,3) and
// /grid/cells (cells,8) hexahedra; name_anim.xdmf (Xdmf 3) is a temporal collection whose
// every step is a spatial collection of two uniform grids, "particles" (Polyvertex, one
// vertex per particle) and "grid" (Hexahedron), so ParaView opens the animation directly.
// The .h5 file is opened, extended and closed at each frame, and the .xdmf rewritten
// (temporary + rename). On a restart the frames of the checkpoint are kept and later ones
// removed.
std::unique_ptr<OutputWriter> make_h5_series_writer(const Model& m, const OutputFiles& files,
                                                    const std::vector<double>& frame_times);

}  // namespace mpm3d
