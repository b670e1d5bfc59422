// What an animation frame holds, shared by the ParaView files (writer_vtu.cpp) and the HDF5 +
// XDMF series (writer_h5series.cpp): the particle fields, and the deck's background grid.
//
// The fields are those the original MPM3D-F90 writes in every .vtu frame, whatever the
// deck's outr lines, with its names and in its order, then the deck's outr variables under
// their own names (docs/DECK_FORMAT.md, "Animation files"):
//   the book version:    seqv epeff pressure vx vy vz vol celsius_t damage
//   the current version: seqv epeff pressure Smoothpressure MeanNormalStress
//                        SmoothMeanNormalStress vx vy vz disx disy disz fxpx fxpy fxpz vol
//                        celsius_t damage stressx
// (the current set for decks with a current-version keyword, Model::current_version).
#pragma once
#include <string>
#include <vector>

#include "io/data_out.hpp"

namespace mpm3d {

struct FrameField {
  std::string name;
  ParticleVarFn fn;  // value at stored particle p
  // An outr variable that is one of the original's fields under another name (epef is
  // epeff, velx is vx, ...): the index of that earlier field, whose values it shares (the
  // binary .vtu points both at one block, the HDF5 series links both names to one
  // dataset); -1 for a field of its own.
  int alias_of = -1;
};

// The fields of the frames of m, in file order; every name once.
std::vector<FrameField> frame_fields(const Model& m);

// The deck's background grid: the box of spx/spy/spz (or grid) cut into cubes of dcell,
// as the solver's grid (Grid::define). Nodes numbered x fastest, then y, then z.
struct DeckLattice {
  double lo[3] = {0, 0, 0};
  double h = 0.0;
  long long nc[3] = {0, 0, 0};  // cells per axis
  explicit DeckLattice(const Model& m);
  long long nodes() const { return (nc[0] + 1) * (nc[1] + 1) * (nc[2] + 1); }
  long long cells() const { return nc[0] * nc[1] * nc[2]; }
  // Coordinate a (0..2) of node n.
  double node_coord(long long n, int a) const;
  // Node k (0..7) of cell c: corner (k & 1, (k >> 1) & 1, (k >> 2) & 1) in cells along
  // x, y, z, the order of a VTK voxel (type 11, as the original's grid file).
  long long voxel_node(long long c, int k) const;
};

// The corners of a VTK/XDMF hexahedron (counter-clockwise below, then above) as voxel
// corners: hexahedron corner k is voxel corner kHexFromVoxel[k].
constexpr int kHexFromVoxel[8] = {0, 1, 3, 2, 4, 5, 7, 6};

}  // namespace mpm3d
