// The end of a deck ('endi', DeckReader::finish, data_in_reader.hpp): the checks of the whole
// deck (counts, grid size and memory, explosives), then the derived values: lighting times,
// initial internal energies and temperatures, GIMP sizes, dt, mass cut-off, base name.
#include <algorithm>
#include <cmath>
#include <string>

#include "input/data_in_reader.hpp"
#include "materials/material_models.hpp"

namespace mpm3d {

void DeckReader::finish(int line) {
  if (m_.nbmp < 0) fail(line, "no 'nbmp' (number of particles) before 'endi'");
  if (m_.nmat < 0) fail(line, "no 'nmat' (number of materials) before 'endi'");
  if (parts_.count() != m_.nbmp)
    fail(line, "'nbmp' = " + std::to_string(m_.nbmp) + " but the particle cards define " + std::to_string(parts_.count()));
  if (m_.nbbo >= 0 && int(m_.bodies.size()) != m_.nbbo)
    fail(line, "'nbbo' = " + std::to_string(m_.nbbo) + " but " + std::to_string(m_.bodies.size()) + " particle cards were read");
  for (int i = 0; i < m_.nmat; ++i)
    if (m_.mats[size_t(i)].type == 0) fail(line, "material " + std::to_string(i + 1) + " has no 'mate' card");
  for (int a = 0; a < 3; ++a)
    if (!m_.box_set[a]) fail(line, std::string("no grid box along ") + char('x' + a) + " (spx/spy/spz or grid)");
  if (!(m_.dcell > 0.0)) fail(line, "no cell size ('dcel')");
  if (!(m_.endtime > 0.0)) fail(line, "no end time ('endt')");
  if (m_.contact && m_.nbco != 2) fail(m_.contact_line, "'cont' needs two components ('nbco 2')");
  if (m_.contact && m_.scheme == SCHEME_USL)
    m_.warnings.push_back("cont with USL: bodies rebounding from a contact vibrate in free flight, and USL "
                          "(light nodes in the strain rate) tends to diverge there; MUSL or USF are safer");
  if (m_.rpttime <= 0.0) m_.rpttime = m_.outtime;
  // Grid size: whole cells per axis, the node count and the memory of the run.
  double nodes = 1.0;
  for (int a = 0; a < 3; ++a) {
    const int at = std::max(box_line_[a], dcell_line_);
    const double n = std::floor((m_.box_hi[a] - m_.box_lo[a]) / m_.dcell + 0.5);
    if (!(n >= 1.0)) fail(at, std::string("grid box along ") + char('x' + a) + " is shorter than half a cell");
    if (!(n <= 1.0e6)) fail(at, std::string("grid box along ") + char('x' + a) + " has more than 1000000 cells");
    nodes *= n + 1.0;
  }
  {
    const int at = std::max({box_line_[0], box_line_[1], box_line_[2], dcell_line_});
    if (nodes > kMaxNodes)
      fail(at, "grid of " + std::to_string(long(nodes)) + " nodes exceeds the limit of " + std::to_string(long(kMaxNodes)));
    const double need = nodes * kBytesPerNode + double(m_.nbmp) * kBytesPerParticle, budget = memory_budget_;
    if (need > budget)
      fail(at, "grid of " + std::to_string(long(nodes)) + " nodes and " + std::to_string(m_.nbmp) +
                   " particles need about " + megabytes(need) + ", more than the " + megabytes(budget) +
                   " of memory available");
  }
  for (int a = 0; a < 3; ++a) {
    const double n = (m_.box_hi[a] - m_.box_lo[a]) / m_.dcell;
    if (std::fabs(n - std::floor(n + 0.5)) > 1e-6 * n)
      m_.warnings.push_back(std::string("box length along ") + char('x' + a) +
                            " is not a whole number of cells; rounded to " + std::to_string(long(std::floor(n + 0.5))));
  }
  // Explosives: every hiex and null material needs an EOS, hiex a detonation point.
  bool hiex = false;
  for (int i = 0; i < m_.nmat; ++i) {
    MaterialParams& mp = m_.mats[size_t(i)];
    if ((mp.type == MAT_HIEX || mp.type == MAT_NULL) && mp.eos_type == EOS_NONE)
      fail(line, "material " + std::to_string(i + 1) + " (" + material_keyword(mp.type) +
                     ") needs an equation of state ('seos')");
    if (mp.type == MAT_HIEX) {
      if (m_.deto.empty()) fail(line, "material " + std::to_string(i + 1) + " (hiex) needs a detonation point ('deto')");
      mp.burn_width = 1.5 * m_.dcell;
      hiex = true;
    }
  }
  if (!m_.deto.empty() && !hiex) m_.warnings.push_back("'deto' points given but no hiex material: ignored");
  // Initial internal energy from E0 (per unit initial volume).
  Particles& P = m_.particles;
  if (hiex) {
    // Lighting time: distance from the initial position to the nearest detonation point / D.
    P.tlight.assign(size_t(P.np), 0.0);
    const size_t nd = m_.deto.size() / 3;
    for (int p = 0; p < P.np; ++p) {
      const MaterialParams& mp = m_.mats[size_t(P.mat[p])];
      if (mp.type != MAT_HIEX) continue;
      const double* x = &P.x[3 * size_t(p)];
      double dmin = 0.0;
      for (size_t k = 0; k < nd; ++k) {
        const double dx = x[0] - m_.deto[3 * k], dy = x[1] - m_.deto[3 * k + 1], dz = x[2] - m_.deto[3 * k + 2];
        const double d = std::sqrt((dx * dx + dy * dy) + dz * dz);
        if (k == 0 || d < dmin) dmin = d;
      }
      P.tlight[size_t(p)] = dmin / mp.det_vel;
    }
  }
  // The current version has artificial bulk viscosity on by default (1.5, 0.06), applied to
  // the stress (the book computes it only where 'bulk' asks).
  // Rule bulk_book=ignore: the book program reads 'bulk' and does not apply it.
  if (m_.has_bulk && !m_.current_version && m_.rules.bulk_book == 1) {
    m_.has_bulk = false;
    m_.bulk_q1 = m_.bulk_q2 = 0.0;
  }
  if (m_.current_version && !m_.has_bulk) {
    m_.has_bulk = true;
    m_.bulk_q1 = 1.5;
    m_.bulk_q2 = 0.06;
  }
  if (m_.has_bulk) P.qv.assign(size_t(P.np), 0.0);
  // Rule null_eos=wave_speed: the current program's set-up overwrites the first EOS coefficient
  // of every null material (c0, C0, A; in Mie-Gruneisen rho0 c0^2, which its linear term alone
  // reads) with the null's wave speed sqrt(K / rho0).
  if (m_.rules.null_eos == 1)
    for (auto& mp : m_.mats)
      if (mp.type == MAT_NULL && mp.eos_type != EOS_NONE) {
        if (mp.eos_type == EOS_MIE_GRUNEISEN)
          mp.eos_k1 = mp.wave_speed;
        else
          mp.eos[0] = mp.wave_speed;
      }
  // neoh: each particle carries F - I (zero at the start); the volume follows det F.
  bool neoh = false;
  for (const auto& mp : m_.mats) neoh = neoh || mp.type == MAT_NEOH;
  if (neoh) {
    m_.uvf = true;
    P.defgrad.assign(9 * size_t(P.np), 0.0);
  }
  // disx, disy, disz: displacements from the initial positions.
  bool displacement = false;
  for (const auto& v : m_.anim_vars) displacement = displacement || v.compare(0, 3, "dis") == 0;
  for (const auto& c : m_.curves) displacement = displacement || c.var.compare(0, 3, "dis") == 0;
  if (m_.tl) {
    // The combinations the current version's TLmp does not have are refused.
    for (const auto& mp : m_.mats)
      if (mp.type != MAT_NEOH)
        fail(m_.tl_line, std::string("'TLmp' with a ") + material_keyword(mp.type) +
                             " material: total Lagrangian MPM takes neoh materials only");
    if (m_.gimp) fail(m_.tl_line, "'TLmp' with 'gimp': total Lagrangian MPM takes the trilinear shape functions only");
    if (m_.bspline) fail(m_.tl_line, "'TLmp' with 'bimp': total Lagrangian MPM takes the trilinear shape functions only");
    if (m_.contact) fail(m_.tl_line, "'TLmp' with 'cont': total Lagrangian MPM has one velocity field");
    if (m_.regrid_every > 0) fail(m_.tl_line, "'TLmp' with 'adgr': the reference grid of TLmp cannot move");
    P.pk1.assign(9 * size_t(P.np), 0.0);
  }
  if (displacement || m_.tl) P.x0 = P.x;
  // pt2d: TecPlot output only for the particles whose initial position lies in the box
  // (the original marks them as they are generated).
  if (m_.has_pt2d) {
    m_.tec_skip.assign(size_t(P.np), 0);
    for (int p = 0; p < P.np; ++p) {
      const double* x = &P.x[3 * size_t(p)];
      bool in = true;
      for (int a = 0; a < 3; ++a) in = in && x[a] >= m_.pt2d[2 * a] && x[a] <= m_.pt2d[2 * a + 1];
      m_.tec_skip[size_t(p)] = in ? 0 : 1;
    }
  }
  bool thermal = false;
  for (const auto& mp : m_.mats) thermal = thermal || (material_model(mp.type) && material_model(mp.type)->thermal);
  if (thermal) P.temp.assign(size_t(P.np), 0.0);
  double c_max = 0.0, rho_sum = 0.0;
  for (const auto& mp : m_.mats) {
    c_max = std::max(c_max, mp.wave_speed);
    rho_sum += mp.rho0;
  }
  for (int p = 0; p < P.np; ++p) {
    const MaterialParams& mp = m_.mats[size_t(P.mat[p])];
    if (mp.eos_type != EOS_NONE) P.ie[p] = mp.eos_e0 * (P.mass[p] / mp.rho0);
    if (thermal) P.temp[p] = m_.rules.start_temp ? 293.0 : mp.t_room;  // rule start_temp
  }
  if (m_.gimp && m_.bspline)
    fail(std::max(gimp_line_, bimp_line_), "'gimp' with 'bimp': a deck takes one kind of shape functions");
  if (m_.sg) {
    // What the current version's sgmp does not combine with, or we have not built, is refused.
    if (m_.gimp) fail(std::max(gimp_line_, sgmp_line_), "'sgmp' with 'gimp': smoothed-gradient MPM takes the trilinear shape functions only");
    if (m_.bspline) fail(std::max(bimp_line_, sgmp_line_), "'sgmp' with 'bimp': smoothed-gradient MPM takes the trilinear shape functions only");
    if (m_.contact) fail(std::max(m_.contact_line, sgmp_line_), "'sgmp' with 'cont': smoothed-gradient MPM has one velocity field here");
    if (m_.regrid_every > 0) fail(sgmp_line_, "'sgmp' with 'adgr': the cell-centre grid of sgmp does not move");
  }
  if (m_.bspline) two_cells_each_axis(bimp_line_, "bimp");
  // GIMP particle half-size lp. Current-version decks: a quarter cell for every particle,
  // as the current program, whose GIMP weights are written for particles half a cell wide
  // whatever their volume. Book decks: half the spacing of bloc/sphe/cyli particles, half
  // the cube root of the volume of poin particles; at most h/2 (the 27-node stencil).
  if (m_.gimp) {
    P.psize.assign(size_t(P.np), 0.0);
    bool clamped = false;
    for (const Body& b : m_.bodies)
      for (int p = b.first; p < b.first + b.count; ++p) {
        double lp = m_.current_version ? 0.25 * m_.dcell
                    : b.spacing > 0.0  ? 0.5 * b.spacing
                                       : 0.5 * std::pow(P.vol[p], 1.0 / 3.0);
        if (lp > 0.5 * m_.dcell) {
          lp = 0.5 * m_.dcell;
          clamped = true;
        }
        P.psize[p] = lp;
      }
    if (clamped) m_.warnings.push_back("gimp: particles larger than the cell size take half a cell as their half-size");
    two_cells_each_axis(gimp_line_, "gimp");
  }
  if (m_.sg) sgmp_held_cells();
  outside_grid();
  // dt = dtscale * h / c_max (the dilatational wave speed, D for hiex, c for null), fixed
  // for the run as in the original. With bulk viscosity the stable step of a material at
  // rest is h / (Q + sqrt(Q^2 + c^2)) with Q = q2 c: dt = dtscale h / (c_max (q2 + sqrt(1 + q2^2))).
  // The current version's dt has no bulk viscosity term.
  if (m_.has_bulk && !m_.current_version)
    m_.dt = (m_.dtscale * m_.dcell) / (c_max * (m_.bulk_q2 + std::sqrt(1.0 + m_.bulk_q2 * m_.bulk_q2)));
  else
    m_.dt = m_.dtscale * m_.dcell / c_max;
  if (!(m_.dt > 0.0) || !std::isfinite(m_.dt))
    fail(std::max(dcell_line_, line), "time step dtscale * dcel / wave speed is not a positive finite number");
  m_.mass_cutoff = 1.0e-5 * (rho_sum / double(m_.nmat)) * ((m_.dcell * m_.dcell) * m_.dcell);
  // Base name: the deck's file name up to its first '.'.
  std::string base = m_.deck_path;
  const size_t slash = base.find_last_of('/');
  if (slash != std::string::npos) base = base.substr(slash + 1);
  const size_t dot = base.find('.');
  if (dot != std::string::npos && dot > 0) base = base.substr(0, dot);
  m_.base_name = base.empty() ? "mpm3d" : base;
}

// The cells of the grid along axis a (the box length rounded to whole cells).
static double cells_along(const Model& m, int a) { return std::floor((m.box_hi[a] - m.box_lo[a]) / m.dcell + 0.5); }

void DeckReader::two_cells_each_axis(int line, const char* keyword) {
  for (int a = 0; a < 3; ++a) {
    const double n = cells_along(m_, a);
    if (n >= 2.0) continue;
    const std::string axis(1, char('x' + a));
    fail(line, std::string("'") + keyword + "' needs at least two cells along each axis (its 27-node stencil reaches " +
                   "the cells beside a particle's own): the grid has " + std::to_string(long(n)) + " cell along " +
                   axis + "; make sp" + axis + " span two cells or more (a plane-strain model keeps its symmetric faces)");
  }
}

std::string sgmp_held_cells_text(const Model& m) {
  const Particles& P = m.particles;
  std::string what;
  for (int a = 0; a < 3; ++a) {
    if (m.fix[2 * a] == 0 || cells_along(m, a) < 2.0) continue;
    long count = 0;
    for (int p = 0; p < P.np; ++p) {
      const double s = (P.x[3 * size_t(p) + a] - m.box_lo[a]) / m.dcell;
      if (s >= 0.0 && s < 1.0) ++count;
    }
    if (count == 0) continue;
    const std::string axis(1, char('x' + a));
    const bool fixed = m.fix[2 * a] == 1;
    what += (what.empty() ? "" : "; ") + std::to_string(count) + " particles lie in the first cell along " + axis +
            ", between the two node layers sgmp holds at the " + (fixed ? "fixed" : "symmetric") + " lower " + axis +
            " face, which keep them " + (fixed ? "still" : "from moving along " + axis) +
            ": add one cell outside that face (lower the first value of sp" + axis + " by dcel)";
  }
  return what.empty() ? what : what + ", as the current MPM3D-F90's ChangeLog asks for sgmp";
}

std::vector<std::string> not_copied_text(const Model& m) {
  std::vector<std::string> out;
  int thin = 0;  // the first axis of one cell
  while (thin < 3 && cells_along(m, thin) >= 2.0) ++thin;
  if (m.sg && thin < 3) {
    const std::string axis(1, char('x' + thin));
    out.push_back("sgmp on a grid one cell thick along " + axis +
                  ": the current MPM3D-F90 gives the weight of a cell centre beyond that axis to the first cell of "
                  "the next row of its cell numbering (a read within its arrays) and drops it only past its last "
                  "cell; mpm3d gives it to the nearest centre, and drops it where that program does under "
                  "sg_beyond=drop. No rule copies the next row: the public Slopefail with sgmp differs from that "
                  "program by 13.5 % of its kinetic energy to t = 2 s under --rules original");
  }
  return out;
}

std::vector<std::string> sensitive_text(const Model& m) {
  std::vector<std::string> out;
  for (size_t i = 0; i < m.mats.size(); ++i) {
    const MaterialParams& mat = m.mats[i];
    // The book's Mie-Gruneisen (ours and both programs') has its energy term g0 e only in
    // compression: the pressure jumps by g0 e where mu crosses 0.
    if (mat.eos_type != EOS_MIE_GRUNEISEN || mat.eos[2] == 0.0) continue;
    out.push_back("Mie-Gruneisen (material " + std::to_string(i + 1) +
                  "): the pressure has its energy term g0 e in compression only, so it jumps by g0 e where mu "
                  "crosses 0, and a heated particle near its initial density takes either side on a difference "
                  "in the 7th digit of its volume. The original's own results then spread: the book program on "
                  "Taylor.mpm, run again with mu changed by 1e-7, differs from itself at t = 0.08 by 42 % of the "
                  "largest seqv in its last frame (median 3.9 %) and 36 % of the largest pressure, its energies "
                  "by under 0.3 %. Particle fields late in such a run differ as much between mpm3d and the original");
    break;
  }
  return out;
}

// sgmp's held first cells (sgmp_held_cells_text): the smoothed gradient there grows the
// energy until the run stops. Our rules refuse the deck; the original's (sg_lower=truncate)
// run it as the current program does, with a warning.
void DeckReader::sgmp_held_cells() {
  const std::string what = sgmp_held_cells_text(m_);
  if (what.empty()) return;
  if (m_.rules.sg_lower == 0) fail(sgmp_line_, what + "; --rule sg_lower=truncate (in --rules original) runs the deck as that program does");
  m_.warnings.push_back(what);
}

void DeckReader::outside_grid() {
  const Particles& P = m_.particles;
  long count = 0;
  int first = -1;
  for (int p = 0; p < P.np; ++p) {
    bool in = true;
    for (int a = 0; a < 3; ++a) {
      const double v = (P.x[3 * size_t(p) + a] - m_.box_lo[a]) / m_.dcell;
      in = in && v >= 0.0 && v < cells_along(m_, a);
    }
    if (in) continue;
    if (count++ == 0) first = p;
  }
  if (count > 0)
    m_.warnings.push_back(std::to_string(count) + " particles lie outside the grid at the start (the first: particle " +
                          std::to_string(first + 1) +
                          "): they stay frozen where they are for the whole run; widen the box (spx, spy, spz) to "
                          "hold them");
}

}  // namespace mpm3d
