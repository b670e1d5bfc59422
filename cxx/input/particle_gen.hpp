// Particle generators of the deck's 'part' cards (read by data_in.cpp): the lattices of bloc,
// sphe and cyli (particle counts, room checks against 'nbmp', the loops in the book's order)
// and the appending of particles to the deck's arrays, one by one for poin.
#pragma once
#include <string>
#include <utility>

#include "core/particle.hpp"

namespace mpm3d {

// Appends the particles of the particle cards to the deck's arrays. The arrays grow
// (doubling from 1024, contents kept, at most to 'nbmp') as particles come, so a deck that
// asks for many particles and defines few allocates little. Every error throws a DeckError
// naming the deck (file) and the card's line.
class ParticleAppender {
 public:
  ParticleAppender(Particles& P, std::string file) : P_(P), file_(std::move(file)) {}
  // 'nbmp': no particle beyond it. The arrays' room for it is reserved (address space, not
  // touched until used), so that growing them never copies them.
  void set_limit(int nbmp);
  int limit() const { return nbmp_; }
  int count() const { return count_; }  // particles appended so far, all cards together

  // Appends one particle of body `body` and material `mat` (0-based) at (x, y, z).
  void add(int line, int body, int mat, double mass, double vol, double x, double y, double z);
  // Refuses a card that would generate at least `count` more particles than 'nbmp' leaves
  // room for (checked before generating, so that no card loops for long).
  void check_room(int line, double count, const char* what) const;
  [[noreturn]] void fail(int line, const std::string& what) const;

 private:
  // f(array, its values per particle) for each array that add() fills and grows.
  template <class F>
  void for_each_array(F&& f) {
    Particles& P = P_;
    f(P.x, 3), f(P.v, 3), f(P.sig, 6);
    f(P.mass, 1), f(P.vol, 1), f(P.epeff, 1), f(P.ie, 1), f(P.mat, 1), f(P.body, 1);
  }

  Particles& P_;
  std::string file_;
  int nbmp_ = 0;
  int count_ = 0;
};

// The particles of one lattice card (bloc, sphe, cyli): body `body`, material `mat`, each
// of mass `mass` and volume `vol`, on the lattice of spacing `dp`; `line`: the card's line.
struct LatticeCard {
  int line = 0, body = 0, mat = 0;
  double mass = 0.0, vol = 0.0, dp = 0.0;
};

// 'part poin': refuses n points when 'nbmp' leaves no room for them.
void check_points_room(const ParticleAppender& out, int line, long n);
// 'part bloc': n[0] x n[1] x n[2] particles at origin + (i + 1/2) dp; x index outermost, z
// fastest (the book version), or z outermost and x fastest (x_fastest: the current
// version). Counts in 1..100000 (checked by the reader). 'part blod' (the current version):
// nr > 0 leaves out the particles inside the circular hole of radius nr dp around the axis
// through (hx, hy) parallel to z (kept where (x - hx)^2 + (y - hy)^2 >= (nr dp)^2).
void generate_block(ParticleAppender& out, const LatticeCard& c, const double origin[3], const long n[3],
                    bool x_fastest = false, double hx = 0.0, double hy = 0.0, long nr = 0);
// 'part sphe': the lattice points centre + (i + 1/2, j + 1/2, l + 1/2) dp, i, j, l in
// -nr .. nr-1, within nr spacings of the centre. nr in 1..10000 (checked by the reader).
void generate_sphere(ParticleAppender& out, const LatticeCard& c, const double centre[3], long nr);
// 'part cyli' (extension): a cylinder along z, axis through (cx, cy), from z0 to z0 + length,
// of the given radius, on the lattice; radius and length positive (checked by the reader).
void generate_cylinder(ParticleAppender& out, const LatticeCard& c, double cx, double cy, double z0, double radius,
                       double length);

// 'part cicl' (the current version): a disc one particle thick in the plane z0 + dp/2, the
// points (x0 + (i + 1/2) dp, y0 + (j + 1/2) dp) for i, j in -nr .. nr-1 (i outermost) closer
// than nr dp to (x0, y0).
void generate_disc(ParticleAppender& out, const LatticeCard& c, const double origin[3], long nr);

}  // namespace mpm3d
