// DataOut: the curve values, the HDF5 state file, and Output, which runs the writers of
// the result files (output_writer.hpp: curves, TecPlot, ParaView, HDF5 series).
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "input/data_in.hpp"
#include "input/output_variables.hpp"
#include "io/output_writer.hpp"

namespace mpm3d {

// Fortran E12.4 (e.g. "  0.1326E-03"), as the original writes its plot files.
std::string fortran_e12_4(double v);

// Fills m.spre: the pressure smoothed through the grid (smoothed_pressure.cpp).
void update_smoothed_pressure(const Model& m);

// The curv/curx variables of m.curves for the particles this process holds, -infinity for
// the others (several ranks: the largest over the ranks is every curve's value). held[c]
// caches the row of curve c's particle; a particle not found where it was is looked up again.
void held_curve_values(const Model& m, std::vector<int>& held, std::vector<double>& values);

// Writes the final particle state (docs/DESIGN.md section 6) atomically (temporary + rename).
void write_state_h5(const std::string& path, const Model& m, double time, long step, double dt);

struct OutputSchedule;

// The run's output files: the writers of the formats the run asked for (output_writer.hpp),
// each called in turn at every step, animation time and checkpoint. Files are created in
// open() and appended as the run goes; nothing is opened when output is off. On a restart
// (resume given) the text files are truncated to their sizes at the checkpoint and appended
// to, and the frame count continues.
class Output {
 public:
  Output();
  ~Output();
  // legacy: the curves and the deck's animation formats; series: the HDF5 + XDMF series;
  // vtu_binary: the ParaView files as appended raw binary (--vtu-binary) instead of ASCII.
  void open(const Model& m, const std::string& dir, bool legacy, bool series, const OutputSchedule* resume,
            bool vtu_binary = false);
  void log(const std::string& line);  // name.out
  // Every appended file handed to the system (OutputWriter::flush): at every report and
  // before close; throws std::runtime_error naming a file that cannot be written.
  void flush();
  void step(const Model& m, const StepRecord& s);
  void frame(const Model& m, double time, long step);  // one frame of every animation format
  // Whether open(m, ..., legacy, series) opens an animation (known to every rank, which all
  // take part in gathering the particles of a frame).
  static bool animates(const Model& m, bool legacy, bool series) { return (legacy && (m.tecplot || m.paraview)) || series; }
  // Flushes the text files and records their sizes and the frames written so far.
  void save_state(OutputSchedule& o);
  void close();

 private:
  std::vector<std::unique_ptr<OutputWriter>> writers_;
  std::vector<double> frame_times_;
  bool spre_in_curves_ = false, spre_in_frames_ = false;  // spre is computed when written
};

}  // namespace mpm3d
