// MaterialModel (Constitution): stress update of one particle, Jaumann rotation, EOS.
// Pure functions of their arguments: no module state, callable from any thread.
#pragma once
#include "core/step_state.hpp"
#include "materials/material.hpp"

namespace mpm3d {

// Per-particle state the constitutive update reads and writes.
struct StressState {
  double* sig;    // (6) Voigt xx yy zz yz xz xy
  double* epeff;  // equivalent plastic strain
  double* ie;     // internal energy of the particle
  double* temp;   // temperature (thermal Johnson-Cook only; else nullptr)
  double* q;      // artificial bulk viscosity pressure of the last update (only with
                  // 'bulk'; else nullptr). The stored stress includes it: sig = s - (p + q).
  double* vol = nullptr;  // if given: the new volume, vol_new less a dpm particle's opening
                          // beyond its tension cut-off (space between particles)
};

// de: strain increment (tensor components, Voigt order); dw: spin increment
// (w_yz, w_xz, w_xy) with w_ij = (L_ij - L_ji) dt / 2. vol_old/vol_new: particle volume
// before and after the increment.
// burn: programmed-burn fraction F in [0, 1] (hiex only, see burn_fraction); it multiplies
// the EOS pressure. q1, q2, qlen: bulk viscosity coefficients and length (used when s.q).
// rules: the rules in force (core/rules.hpp; the stress update reads bulk_switch,
// bulk_linear, dp_return, fluid_viscous and bulk_work).
void stress_update(const MaterialParams& m, const double de[6], const double dw[3], double dt,
                   double mass, double vol_old, double vol_new, StressState s, double burn = 1.0,
                   double q1 = 0.0, double q2 = 0.0, double qlen = 0.0, const StepRules& rules = StepRules{});

// The stress stage's batch of particles of one material, one array per quantity with a
// lane per particle (the layout the vector code loads directly).
constexpr int kStressLanes = 4;
struct StressBlock {
  double L[9][kStressLanes];  // velocity gradient L[3a+b] = d v_a / d x_b
  double mass[kStressLanes];
  double vol[kStressLanes];  // in: volume before the increment; out: after
  double sig[6][kStressLanes];
  double epeff[kStressLanes], ie[kStressLanes];
  double temp[kStressLanes];  // read and written only with has_temp
  double qv[kStressLanes];    // read and written only with has_q
  double burn[kStressLanes];  // programmed-burn fraction (1 except hiex)
  double H[9][kStressLanes];  // F - I: read and written only for neoh (StepContext::defgrad)
  double pk1[9][kStressLanes];  // V0 P: read and written only under TLmp (StepContext::pk1)
};
struct StressBlockArgs {
  double dt;
  bool has_temp, has_q;
  double q1, q2, qlen;  // bulk viscosity coefficients and length
  // Volume from the deformation: V_new = V_old det(I + L dt) instead of
  // V_old (1 + tr(L) dt) (deck keyword UVFp; always for neoh).
  bool uvf;
  // Total Lagrangian (TLmp, neoh only): L is the velocity gradient in the reference
  // configuration, F += L dt, and the stress comes with V0 P (pk1).
  bool tl;
  StepRules rules;  // the rules in force (core/rules.hpp)
};
// Strain and spin increments dt sym(L), dt skew(L), new volume and stress update of all
// kStressLanes particles of b (vector code; every lane computes what stress_update
// computes for its particle, bit for bit), or of lane i alone (stress_block_lane).
void stress_block(const MaterialParams& m, StressBlock& b, const StressBlockArgs& a);
void stress_block_lane(const MaterialParams& m, StressBlock& b, int i, const StressBlockArgs& a);
// True when stress_block and the lane kernels of the step stages (transfer_lanes.hpp) run
// their AVX2 code (the CPU has it and MPM3D_ISA is not "baseline"); either way the
// results are the same bits.
bool lanes_use_avx2();

// Programmed burn of hiex: F = min(1, max(0, (time - t_light) D / (1.5 h))), with
// m.burn_width = 1.5 h; with step (rule burn=step) the original's F = 1 once time (the end
// of the step) is past the lighting time, which it holds in single precision, else 0.
// 1 for every other material. Inline: the stress stage and the rest check call it for
// every explosive particle each step. The ramp's quotient f = x / w (w = 1.5 h > 0) is
// above 0 only where x is, and at least 1 where x >= w (division rounds monotonically):
// those ends skip the division with the same result; between them f may still round to 0
// or 1, which the tests after it keep.
inline double burn_fraction(const MaterialParams& m, double t_light, double time, bool step = false) {
  if (m.type != MAT_HIEX) return 1.0;
  if (step) return time > double(float(t_light)) ? 1.0 : 0.0;
  const double x = (time - t_light) * m.det_vel;
  if (!(x > 0.0)) return 0.0;
  if (x >= m.burn_width) return 1.0;
  const double f = x / m.burn_width;
  if (!(f > 0.0)) return 0.0;
  return f < 1.0 ? f : 1.0;
}

// Artificial bulk viscosity q = rho l (q1 l d^2 - q2 c d) for a volumetric strain rate
// d = tr(D) < 0 (compression), 0 otherwise.
double bulk_viscosity(double rho, double len, double c, double rate, double q1, double q2);

// Drucker-Prager return (dpm) of a trial stress given as deviator s (6) and mean stress
// sm (tension positive), with bulk modulus K and shear modulus G. Returns the equivalent
// plastic strain increment (0 when elastic). Formulas: constitution.cpp, docs/DECK_FORMAT.md.
double dp_return(const MaterialParams& m, double s[6], double* sm, double K, double G);

// Rotates sig by the Jaumann rate: sig += W sig - sig W.
void jaumann_rotate(double sig[6], const double dw[3]);

// Pressure of an EOS in the form p = a + b e (e: internal energy per initial volume),
// given mu = rho / rho0 - 1. Returns a and b. JWL: V = 1 / (1 + mu),
// a = A (1 - w/(R1 V)) e^(-R1 V) + B (1 - w/(R2 V)) e^(-R2 V), b = w / V.
void eos_coefficients(const MaterialParams& m, double mu, double* a, double* b);

// clay's return of the deviator s (6) at *epeff (updated); returns the equivalent plastic
// strain increment (0 when elastic). original: the newest program's one linearised step (rule
// clay_return=linear); else Newton's method on the consistency condition, at most
// kClayIterations steps, until the residual is below kClayTolerance q_trial.
constexpr int kClayIterations = 30;
constexpr double kClayTolerance = 1e-13;
double clay_return(const MaterialParams& m, double s[6], double* epeff, bool original);

// Yield stress and plastic modulus d(sigma_y)/d(epeff) for J2 materials.
void yield_stress(const MaterialParams& m, double epeff, double strain_rate, double temp,
                  double* sy, double* ep);

}  // namespace mpm3d
