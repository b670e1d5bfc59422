// DataIn: reads a legacy MPM3D deck into a Model (particles generated, dt computed).
#pragma once
#include <string>
#include <vector>

#include "material.hpp"
#include "particle.hpp"
#include "update_step.hpp"

namespace mpm3d {

// A time curve (curv/curx): a variable at one particle.
struct CurveRequest {
  std::string var;
  int particle = 0;  // 0-based
};

struct Model {
  std::string deck_path, base_name, title;
  int nbmp = -1, nbco = 1, nbbo = -1, nmat = -1;
  double endtime = 0.0, outtime = 0.0, rpttime = 0.0, dtscale = 0.9;
  double box_lo[3] = {0, 0, 0}, box_hi[3] = {0, 0, 0};
  bool box_set[3] = {false, false, false};
  double dcell = 0.0;
  int fix[6] = {0, 0, 0, 0, 0, 0};
  int scheme = SCHEME_MUSL;
  bool jaumann = true;
  bool tecplot = false, paraview = false;
  bool has_pt2d = false;
  double pt2d[6] = {0, 0, 0, 0, 0, 0};
  std::vector<uint8_t> tec_skip;  // (np) with pt2d: 1 = left out of TecPlot (initial position)
  bool hdf5 = false;              // extension 'hdf5': HDF5 + XDMF time series of the animation
  std::vector<MaterialParams> mats;
  Particles particles;
  std::vector<Body> bodies;
  bool has_gravity = false, has_loads = false;
  std::vector<std::string> anim_vars;  // outr
  std::vector<CurveRequest> curves;    // curv, curx
  std::vector<double> deto;            // detonation points (3 per point), at most 10
  bool has_bulk = false;               // 'bulk q1 q2': artificial bulk viscosity
  double bulk_q1 = 0.0, bulk_q2 = 0.0;
  double dt = 0.0;                     // initial time step
  double mass_cutoff = 0.0;
  int regrid_every = 0;  // adaptive grid: redefine the grid every N steps (adgr; 0 off)
  bool gimp = false;                   // uGIMP shape functions (particles.psize set)
  bool contact = false;                // cont: multi-velocity contact of components 1, 2
  double contact_mu = 0.0;             // Coulomb friction coefficient
  int contact_normbody = 0;            // normals from component 1, 2, or 0 (both)
  int contact_line = 0;                // deck line of the cont card
  std::vector<std::string> warnings;
};

// Reads the deck; throws DeckError (file, line, problem) on any input error.
Model read_deck(const std::string& path);
Model read_deck_text(const std::string& text, const std::string& name);

// Memory limit of a deck (DECK_FORMAT.md "Limits"): a deck whose particles and grid would
// need more than this many bytes is refused with a line-numbered error before anything is
// allocated. 0 (the default) means the machine's physical memory. The fuzz harness sets a
// small budget.
void set_deck_memory_budget(double bytes);
double deck_memory_budget();
// Estimated bytes per particle and per grid node of a run (reader, grid and solver arrays).
constexpr double kBytesPerParticle = 256.0;
constexpr double kBytesPerNode = 160.0;
// Hard limits (int indexing of the arrays): particles and grid nodes.
constexpr long kMaxParticles = 200000000;
constexpr double kMaxNodes = 2.0e8;

// Names accepted by outr, curv and curx.
bool is_output_variable(const std::string& name);

}  // namespace mpm3d
