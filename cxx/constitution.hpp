// MaterialModel (Constitution): stress update of one particle, Jaumann rotation, EOS.
// Pure functions of their arguments: no module state, callable from any thread.
#pragma once
#include "material.hpp"

namespace mpm3d {

// Per-particle state the constitutive update reads and writes.
struct StressState {
  double* sig;    // (6) Voigt xx yy zz yz xz xy
  double* epeff;  // equivalent plastic strain
  double* ie;     // internal energy of the particle
  double* temp;   // temperature (thermal Johnson-Cook only; else nullptr)
};

// de: strain increment (tensor components, Voigt order); dw: spin increment
// (w_yz, w_xz, w_xy) with w_ij = (L_ij - L_ji) dt / 2. vol_old/vol_new: particle volume
// before and after the increment.
void stress_update(const MaterialParams& m, const double de[6], const double dw[3], double dt,
                   double mass, double vol_old, double vol_new, StressState s);

// Rotates sig by the Jaumann rate: sig += W sig - sig W.
void jaumann_rotate(double sig[6], const double dw[3]);

// Pressure of an EOS in the form p = a + b e (e: internal energy per initial volume),
// given mu = rho / rho0 - 1. Returns a and b.
void eos_coefficients(const MaterialParams& m, double mu, double* a, double* b);

// Yield stress and plastic modulus d(sigma_y)/d(epeff) for J2 materials.
void yield_stress(const MaterialParams& m, double epeff, double strain_rate, double temp,
                  double* sy, double* ep);

}  // namespace mpm3d
