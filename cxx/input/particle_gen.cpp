// The particle generators of the 'part' cards (particle_gen.hpp): appending to the deck's
// arrays, the room checks and the lattice loops of bloc, sphe and cyli.
#include "input/particle_gen.hpp"

#include <algorithm>
#include <cmath>

#include "input/ffi.hpp"

namespace mpm3d {

void ParticleAppender::fail(int line, const std::string& what) const { throw DeckError(file_, line, what); }

void ParticleAppender::check_room(int line, double count, const char* what) const {
  if (double(count_) + count > double(nbmp_))
    fail(line, std::string(what) + " of at least " + std::to_string(long(count)) + " particles exceeds 'nbmp' = " +
                   std::to_string(nbmp_));
}

void ParticleAppender::set_limit(int nbmp) {
  nbmp_ = nbmp;
  const size_t n = size_t(std::max(nbmp, 0));
  for_each_array([n](auto& a, size_t per_particle) { a.reserve(per_particle * n); });
}

void ParticleAppender::add(int line, int body, int mat, double mass, double vol, double x, double y, double z) {
  if (count_ >= nbmp_)
    fail(line, "more particles than 'nbmp' = " + std::to_string(nbmp_));
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) fail(line, "particle position out of range");
  Particles& P = P_;
  if (count_ >= P.np) {  // grow the arrays (contents kept) up to 'nbmp'
    const int n = int(std::min<long>(nbmp_, std::max<long>(1024, 2L * P.np)));
    P.np = n;
    for_each_array([n](auto& a, size_t per_particle) { a.resize(per_particle * size_t(n)); });  // zeros
    if (!P.fext.empty()) P.fext.resize(3 * size_t(n), 0.0);
  }
  const int p = count_++;
  P.mass[p] = mass;
  P.vol[p] = vol;
  P.x[3 * size_t(p)] = x;
  P.x[3 * size_t(p) + 1] = y;
  P.x[3 * size_t(p) + 2] = z;
  P.mat[p] = mat;
  P.body[p] = body;
}

void check_points_room(const ParticleAppender& out, int line, long n) {
  if (out.count() + n > out.limit())
    out.fail(line, "'part poin' with " + std::to_string(n) + " points exceeds 'nbmp' = " + std::to_string(out.limit()));
}

void generate_block(ParticleAppender& out, const LatticeCard& c, const double o[3], const long n[3],
                    bool x_fastest, double hx, double hy, long nr) {
  if (nr == 0 && out.count() + n[0] * n[1] * n[2] > out.limit())  // a hole leaves fewer
    out.fail(c.line, "block of " + std::to_string(n[0] * n[1] * n[2]) + " particles exceeds 'nbmp' = " +
                         std::to_string(out.limit()));
  const double dp = c.dp;
  const double r2 = (double(nr) * dp) * (double(nr) * dp);
  // Particle k of the card: the book numbers z fastest (x outermost), the current version x
  // fastest (z outermost).
  for (long k = 0; k < n[0] * n[1] * n[2]; ++k) {
    const long i = x_fastest ? k % n[0] : k / (n[2] * n[1]);
    const long j = x_fastest ? (k / n[0]) % n[1] : (k / n[2]) % n[1];
    const long l = x_fastest ? k / (n[0] * n[1]) : k % n[2];
    const double x = o[0] + (double(i) + 0.5) * dp, y = o[1] + (double(j) + 0.5) * dp;
    if (nr > 0 && (x - hx) * (x - hx) + (y - hy) * (y - hy) < r2) continue;
    out.add(c.line, c.body, c.mat, c.mass, c.vol, x, y, o[2] + (double(l) + 0.5) * dp);
  }
}

void generate_sphere(ParticleAppender& out, const LatticeCard& c, const double centre[3], long nr) {
  // At least the lattice points within nr - sqrt(3)/2 of the centre lie inside.
  const double rin = double(nr) - 0.8660254;
  if (rin > 0.0) out.check_room(c.line, std::floor(4.18879 * rin * rin * rin), "sphere");
  const double dp = c.dp;
  const double r2 = double(nr * nr);
  for (long i = -nr; i < nr; ++i)
    for (long j = -nr; j < nr; ++j)
      for (long l = -nr; l < nr; ++l) {
        const double a = double(i) + 0.5, bb = double(j) + 0.5, cc = double(l) + 0.5;
        if ((a * a + bb * bb) + cc * cc > r2) continue;
        out.add(c.line, c.body, c.mat, c.mass, c.vol, centre[0] + a * dp, centre[1] + bb * dp, centre[2] + cc * dp);
      }
}

void generate_cylinder(ParticleAppender& out, const LatticeCard& c, double cx, double cy, double z0, double radius,
                       double length) {
  const double dp = c.dp;
  const double rs = radius / dp, zs = std::floor(length / dp + 0.5);
  if (!(rs <= 100000.0) || !(zs <= 1000000.0)) out.fail(c.line, "cylinder too large for its spacing");
  if (!(zs >= 1.0)) out.fail(c.line, "cylinder shorter than half a spacing");
  const long nr = long(std::ceil(rs));
  const long nz = long(zs);
  // At least the columns within R/dp - sqrt(2)/2 of the axis lie inside.
  const double rin = rs - 0.7071068;
  if (rin > 0.0) out.check_room(c.line, std::floor(3.14159 * rin * rin) * double(nz), "cylinder");
  const double r2 = (radius / dp) * (radius / dp) * (1.0 + 1e-12);
  for (long i = -nr; i < nr; ++i)
    for (long j = -nr; j < nr; ++j) {
      const double a = double(i) + 0.5, bb = double(j) + 0.5;
      if (a * a + bb * bb > r2) continue;
      for (long l = 0; l < nz; ++l)
        out.add(c.line, c.body, c.mat, c.mass, c.vol, cx + a * dp, cy + bb * dp, z0 + (double(l) + 0.5) * dp);
    }
}

void generate_disc(ParticleAppender& out, const LatticeCard& c, const double o[3], long nr) {
  const double dp = c.dp;
  const double r2 = (double(nr) * dp) * (double(nr) * dp);
  for (long i = -nr; i < nr; ++i)
    for (long j = -nr; j < nr; ++j) {
      const double x = o[0] + (double(i) + 0.5) * dp, y = o[1] + (double(j) + 0.5) * dp;
      if (!((x - o[0]) * (x - o[0]) + (y - o[1]) * (y - o[1]) < r2)) continue;
      out.add(c.line, c.body, c.mat, c.mass, c.vol, x, y, o[2] + 0.5 * dp);
    }
}

}  // namespace mpm3d
