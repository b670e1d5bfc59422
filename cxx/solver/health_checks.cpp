// The simulation's checks after every step (cxx/solver/simulation.hpp): non-finite values,
// volumes and densities out of range, runaway energy (HealthError), and the energy bounds
// that a run can break silently (warnings, or an error with --strict-energy).
#include "solver/simulation.hpp"

#include "core/patch_loops.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace mpm3d {

std::string Simulation::body_and_rank(int p) const {
  std::string s = "body " + std::to_string(model.particles.body[size_t(p)] + 1);
  if (ranks) s += ", rank " + std::to_string(ranks->rank());
  return s;
}

template <class F>
std::string Simulation::about_particle(int deck, F&& format) const {
  const Particles& P = model.particles;
  int p = -1;
  if (P.id.empty()) p = deck < P.np ? deck : -1;
  else
    for (int i = 0; i < P.np && p < 0; ++i)
      if (P.id[size_t(i)] == deck) p = i;
  std::string text = p >= 0 ? format(p) : std::string();
  if (!ranks) return text;
  const int from = ranks->min(p >= 0 ? ranks->rank() : std::numeric_limits<int>::max());
  return ranks->broadcast(text, from);
}

// After every step: non-finite values (when an energy sum is not finite), then one pass
// over the particles for a non-positive volume or a density outside
// [kDensityRatioMin, kDensityRatioMax] rho0 (parallel, the lowest such deck number is
// reported, whatever the thread count), then runaway energy. The pass reads two doubles and
// one int per particle: about 1% of a step. On several ranks every decision is a min or a
// max over the ranks, so that all of them stop at the same step with the same message.
// Explosive products expanded past the bound: among heavier material (water, soil) a
// products particle takes the velocity gradient of its neighbourhood in the one velocity
// field, so the charge's particle volumes grow past what the products occupy. The charges'
// volume now against their initial volume, and what to change; "" without hiex. Collective
// on several ranks (every rank calls it).
std::string Simulation::products_advice() const {
  const Particles& P = model.particles;
  double now = 0.0, initial = 0.0;
  for (int p = 0; p < P.np; ++p) {
    const MaterialParams& m = model.mats[size_t(P.mat[p])];
    if (m.type != MAT_HIEX) continue;
    now += P.vol[p];
    initial += P.mass[p] / m.rho0;
  }
  if (ranks) {  // every rank's two sums (a max over slots only one rank fills), added in rank order
    const int n = ranks->size();
    std::vector<double> sums(2 * size_t(n), -std::numeric_limits<double>::infinity());
    sums[2 * size_t(ranks->rank())] = now;
    sums[2 * size_t(ranks->rank()) + 1] = initial;
    ranks->max(sums);
    now = initial = 0.0;
    for (int r = 0; r < n; ++r) {
      now += sums[2 * size_t(r)];
      initial += sums[2 * size_t(r) + 1];
    }
  }
  if (!(initial > 0.0)) return "";
  std::ostringstream os;
  os << "; the explosive's particles add up to " << now / initial << " times its initial volume: ";
  if (model.contact)
    os << "stop the run earlier (endtime) or refine the grid";
  else
    os << "products mixed into heavier material take its expansion in the one velocity field; give the charge "
          "a velocity field of its own (nbco 2, the charge component 1, 'cont lagr 0 0'), stop the run earlier "
          "(endtime), or refine the grid";
  return os.str();
}

std::string Simulation::instability_advice() const {
  std::string advice = "reduce dtscale";
  // sgmp's held first cells: our rules refuse such a deck, the original's (sg_lower=truncate)
  // run it; the stop repeats the reader's warning.
  if (model.sg) {
    const std::string held = sgmp_held_cells_text(model);
    if (!held.empty()) advice += "; " + held;
  }
  if (model.scheme != SCHEME_MUSL) advice += ", or use MUSL ('musl on')";
  return advice;
}

std::string Simulation::energy_causes() const {
  std::string eos;  // the materials with an EOS (the same on every rank)
  for (size_t i = 0; i < model.mats.size(); ++i)
    if (model.mats[i].eos_type != EOS_NONE) eos += (eos.empty() ? "" : ", ") + std::to_string(i + 1);
  const std::string densities = "that the particle cards' densities are the materials'";
  if (eos.empty()) return "check " + densities + ", or reduce dtscale";
  return "check the EOS of material " + eos + " and " + densities;
}

void Simulation::health_check() {
  const Particles& P = model.particles;
  constexpr int kNone = std::numeric_limits<int>::max();
  auto lowest = [&](int deck) { return ranks ? ranks->min(deck) : deck; };
  if (!(std::isfinite(kinetic) && std::isfinite(internal))) {
    auto non_finite = [&](int p) -> const char* {
      for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(P.x[3 * size_t(p) + a])) return "position";
        if (!std::isfinite(P.v[3 * size_t(p) + a])) return "velocity";
      }
      for (int s = 0; s < 6; ++s)
        if (!std::isfinite(P.sig[6 * size_t(p) + s])) return "stress";
      if (!std::isfinite(P.ie[p])) return "internal energy";
      if (!std::isfinite(P.vol[p])) return "volume";
      return nullptr;
    };
    int first = kNone;
    for (int p = 0; p < P.np; ++p)
      if (non_finite(p)) first = std::min(first, P.deck_number(p));
    first = lowest(first);
    if (first != kNone)
      throw HealthError(about_particle(first, [&](int p) {
        std::ostringstream os;
        os << "numerical breakdown at step " << steps << " (t = " << time << "): particle " << first + 1 << " ("
           << body_and_rank(p) << ") has a non-finite " << non_finite(p) << " (" << instability_advice() << ")";
        return os.str();
      }));
  }
  double ie_min = 0.0;  // the lowest particle internal energy, if negative (a min is exact)
  {
    const double* vol = P.vol.data();
    const double* mass = P.mass.data();
    const int* mat = P.mat.data();
    const MaterialParams* mats = model.mats.data();
    const int np = P.np;
    const double* ie = P.ie.data();
    int bad = kNone;  // the lowest deck number of a particle out of bounds
    // The lowest deck number out of bounds and the least internal energy: the same for any
    // thread count; on one thread without a region (one_thread, patch_loops.hpp).
    auto check = [&](int p, int& bad_here, double& ie_min_here) {
      const double r0v = mats[mat[p]].rho0 * vol[p];
      const bool ok = vol[p] > 0.0 && mass[p] >= kDensityRatioMin * r0v && mass[p] <= kDensityRatioMax * r0v;
      if (!ok && P.deck_number(p) < bad_here) bad_here = P.deck_number(p);
      if (ie[p] < ie_min_here) ie_min_here = ie[p];
    };
    struct Least {
      int bad;
      double ie_min;
    };
    const Least least = team_reduce(
        long(np), Least{bad, ie_min},
        [&](long lo, long hi, Least& l) {
          Least here = l;  // locals: l may alias the particle arrays for all the compiler knows
          for (long p = lo; p < hi; ++p) check(int(p), here.bad, here.ie_min);
          l = here;
        },
        [](Least& a, const Least& b) {
          a.bad = std::min(a.bad, b.bad);
          a.ie_min = std::min(a.ie_min, b.ie_min);
        });
    bad = least.bad;
    ie_min = least.ie_min;
    bad = lowest(bad);
    if (ranks) ie_min = ranks->min(ie_min);
    if (bad != kNone) {
      const std::string products = products_advice();  // every rank: a sum over the ranks
      throw HealthError(about_particle(bad, [&](int p) {
        std::ostringstream os;
        os << "numerical breakdown at step " << steps << " (t = " << time << "): particle " << bad + 1 << " ("
           << body_and_rank(p) << ") has ";
        const double rho0 = mats[mat[p]].rho0;
        if (!(vol[p] > 0.0))
          os << "a non-positive volume " << vol[p]
             << " (crushed: reduce dtscale, or the impact speed is too high for the grid)";
        else
          os << "density " << mass[p] / vol[p] << " = " << (mass[p] / vol[p]) / rho0 << " rho0 (rho0 = " << rho0
             << "), outside the bounds [" << kDensityRatioMin << ", " << kDensityRatioMax << "] rho0"
             << (mats[mat[p]].type == MAT_HIEX && mass[p] < kDensityRatioMin * rho0 * vol[p] ? products : "");
        return os.str();
      }));
    }
  }
  if (std::isfinite(kinetic) && std::isfinite(internal)) {
    // Runaway energy: the total may not exceed twice the initial energy plus the bound of
    // the work of the external forces (sum of |f . v| dt per particle with the end-of-step
    // velocities; the factor two leaves room for that approximation).
    const double total = kinetic + internal;
    if (std::fabs(total) <= 2.0 * (std::fabs(initial_total_energy) + std::fabs(external_work)) + 1e-300) {
      energy_check(ie_min);
      return;
    }
    // The fastest particle, ties to the lowest deck number.
    double vmax = -1.0;
    int worst = kNone;
    for (int p = 0; p < P.np; ++p) {
      const double* v = &P.v[3 * size_t(p)];
      const double s = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
      if (s > vmax || (s == vmax && P.deck_number(p) < worst)) {
        vmax = s;
        worst = P.deck_number(p);
      }
    }
    if (ranks) {
      const double all = ranks->max(vmax);
      worst = ranks->min(vmax == all ? worst : kNone);
      vmax = all;
    }
    throw HealthError(about_particle(worst, [&](int p) {
      std::ostringstream os;
      os << "numerical instability at step " << steps << " (t = " << time << "): total energy " << total
         << " exceeds twice the initial energy " << initial_total_energy << " plus the external work "
         << external_work << "; fastest particle " << worst + 1 << " (" << body_and_rank(p) << ") at speed "
         << std::sqrt(vmax) << " (" << instability_advice() << ")";
      return os.str();
    }));
  }
  throw HealthError("numerical breakdown at step " + std::to_string(steps) + ": non-finite energy");
}

// Energy bounds that a run can break silently, with its total still conserved: a body's
// internal energy below -kEnergyWarnFraction (|E0| + |W|), or the kinetic energy above
// E0 + |W| by more than that (both seen when a body starts pre-compressed under an EOS, or
// an EOS releases more work than it stored). ie_min, the lowest particle internal energy
// (0 if none is negative), is exact whatever the thread count: the per-body sums (serial,
// in storage order, so their figures do not depend on the threads either) are formed only
// when np * ie_min could reach the bound.
void Simulation::energy_check(double ie_min) {
  const double bound = kEnergyWarnFraction * (std::fabs(initial_total_energy) + std::fabs(external_work));
  const Particles& P = model.particles;
  std::vector<std::string> found;
  if (ie_min < 0.0 && double(global_np()) * ie_min < -bound) {
    std::vector<double> body_ie(model.bodies.size(), 0.0);
    if (ranks) {  // the same serial sums in storage order, on the root
      Particles all;
      ranks->gather(P, all);
      for (int p = 0; p < all.np; ++p) body_ie[size_t(all.body[p])] += all.ie[p];
      ranks->broadcast(body_ie);
    } else {
      for (int p = 0; p < P.np; ++p) body_ie[size_t(P.body[p])] += P.ie[p];
    }
    body_ie_warned_.resize(body_ie.size(), 0);
    for (size_t b = 0; b < body_ie.size(); ++b) {
      if (body_ie_warned_[b] || !(body_ie[b] < -bound)) continue;
      body_ie_warned_[b] = 1;
      std::ostringstream os;
      os << "energy: the internal energy of body " << b + 1 << " is " << body_ie[b] << " at step " << steps
         << " (t = " << time << "), below -" << 100.0 * kEnergyWarnFraction << "% of the initial total energy "
         << initial_total_energy << " plus the external work " << external_work
         << " (its stress work releases more than it stored: " << energy_causes() << ")";
      found.push_back(os.str());
    }
  }
  if (!kinetic_warned_ && kinetic > (initial_total_energy + std::fabs(external_work)) + bound) {
    kinetic_warned_ = true;
    std::ostringstream os;
    os << "energy: the kinetic energy " << kinetic << " at step " << steps << " (t = " << time
       << ") exceeds the initial total energy " << initial_total_energy << " plus the external work " << external_work
       << " by " << kinetic - (initial_total_energy + std::fabs(external_work)) << " (internal energy " << internal
       << ")";
    found.push_back(os.str());
  }
  if (found.empty()) return;
  if (strict_energy) throw HealthError(found.front() + " (stopped: --strict-energy)");
  for (auto& w : found) new_energy_warnings.push_back(std::move(w));
}

}  // namespace mpm3d
