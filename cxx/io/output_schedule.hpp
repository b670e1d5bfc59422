// OutputSchedule: where the output files stand, as a checkpoint records it
// (solver/checkpoint.hpp) and Output resumes from it (data_out.hpp).
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace mpm3d {

// The driver's output schedule at the checkpoint: when the next animation frame and
// progress line fall due, the times of the frames written so far (TecPlot zones, ParaView
// files and HDF5 series groups share one schedule), and the sizes of the appended text
// files (a restart truncates them back to these sizes, so rows written after the
// checkpoint by the interrupted run are not repeated).
struct OutputSchedule {
  double next_out = 0.0, next_rpt = 0.0;
  std::vector<double> frame_times;
  std::vector<std::pair<std::string, long long>> files;  // file name (no directory), bytes
};

}  // namespace mpm3d
