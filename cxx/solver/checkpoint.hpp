// Checkpoint and restart (HDF5): everything a step needs to continue a run bit for bit.
// Not a module of the original MPM3D (it has none); used by the driver (cli.cpp) and
// the C API.
#pragma once
#include <string>

#include "io/output_schedule.hpp"

namespace mpm3d {

class Simulation;
struct Particles;

// Writes the checkpoint atomically (temporary file + rename): format tag and version, the
// simulation counters (step, time, dt, energies, external work), the grid definition, every
// allocated particle array (particle_fields) and the output schedule. particles: the whole
// particle set in one process's storage order when sim holds only a rank's share (its
// root writes for every rank), else null.
void write_checkpoint(const std::string& path, const Simulation& sim, const OutputSchedule& out,
                      const Particles* particles = nullptr);

// Restores a checkpoint into sim, which must have been built from the same deck (the
// particle, body and material counts are checked, and every particle array the model has
// allocated must be in the file with the same size). The grid and the patch size are those
// of the checkpoint. Throws std::runtime_error naming the file and the problem.
void read_checkpoint(const std::string& path, Simulation& sim, OutputSchedule& out);

// The patch size stored in a checkpoint (to build the Simulation before restoring it).
int checkpoint_patch_cells(const std::string& path);

// Whether a checkpoint holds the particle array of that name (particle_fields), e.g. the
// initial positions the driver keeps for the current version's frames.
bool checkpoint_has_particle_array(const std::string& path, const char* name);

}  // namespace mpm3d
