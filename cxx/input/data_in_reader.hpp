// The deck reader's class DeckReader, shared by its files: data_in.cpp (the card loop),
// data_in_cards.cpp (the mate, seos, part, velo and load cards) and data_in_finish.cpp (the
// checks and the derived values at 'endi'). Internal: the reader's interface is data_in.hpp.
#pragma once
#include <string>
#include <utility>

#include "input/data_in.hpp"
#include "input/ffi.hpp"
#include "input/particle_gen.hpp"

namespace mpm3d {

// Reads one deck into a Model (read), card by card; every input error throws a DeckError
// naming the deck and the line (fail).
class DeckReader {
 public:
  DeckReader(TokenStream ts, double memory_budget, RuleRequest rules)
      : ts_(std::move(ts)), memory_budget_(memory_budget), rules_(std::move(rules)), parts_(m_.particles, ts_.name()) {}
  Model read();
  // Bytes as "N MB", for the memory errors.
  static std::string megabytes(double bytes);

 private:
  TokenStream ts_;
  const double memory_budget_;  // bytes (deck_memory_budget)
  const RuleRequest rules_;     // resolved into m_.rules once the deck's version is known
  Model m_;
  ParticleAppender parts_;  // appends the particle cards' particles to m_.particles
  bool ended_ = false;
  int box_line_[3] = {0, 0, 0}, dcell_line_ = 0;  // where the box and the cell size were set
  int gimp_line_ = 0, bimp_line_ = 0, sgmp_line_ = 0;  // where gimp, bimp and sgmp were asked for

  [[noreturn]] void fail(int line, const std::string& what) { ts_.fail(line, what); }
  bool on_off(const Token& key);
  void need_counts(const Token& key, bool particles, bool materials, bool bodies);
  void read_materials(const Token& key);
  void read_particles(const Token& key);
  void read_velocities(const Token& key);
  void read_loads(const Token& key);
  MaterialParams& card_material(const Token& key, const char* card, long& mid);
  void read_eos(const Token& key);
  void read_pressure_floor(const Token& key);
  int body_index(const Token& at, long ib);
  int particle_index(const Token& at, long pid);
  // The particles a 'node' (one particle, already defined) or 'body' line of velo and load
  // applies to, read from the deck: first and count. what: "velocity for", "load on".
  void card_target(const Token& at, const std::string& k, const char* what, int& first, int& count);
  std::string output_var(int line);
  void finish(int line);
  // finish's checks of the grid against the method and the particles:
  // a 27-node stencil (gimp, bimp, asked for at `line`) needs two cells along each axis;
  void two_cells_each_axis(int line, const char* keyword);
  // sgmp's particles between the two node layers of a held lower face (refused by our rules);
  void sgmp_held_cells();
  // particles outside the grid at the start are named (a warning before the first step).
  void outside_grid();
};

}  // namespace mpm3d
