// The output variables that the deck's outr, curv and curx cards name: the deck reader
// accepts their names, the writers (io/) evaluate them. Below both, so that neither
// includes the other.
#pragma once
#include <string>
#include <vector>

#include "input/data_in.hpp"

namespace mpm3d {

// The output variables of outr/curv/curx, one function each, computed from the particle
// arrays and the material's MaterialParams only (a new material needs no change here):
//   seqv von Mises stress sqrt(3/2 s:s)      epef equivalent plastic strain
//   mat  material number (1-based)           pres pressure -(sxx + syy + szz)/3
//   volu volume                              engk kinetic energy m |v|^2 / 2
//   engi internal energy                     velx vely velz velocity components
//   cels temperature (0 without a thermal material)
//   fail 1 when the material has a failure strain eps_f (sjcf, jcf) and epeff >= eps_f
//   damg epeff / eps_f clipped to [0, 1] (0 without eps_f)
//   stsx stress xx (tension positive)
//   disx disy disz displacement from the initial position
//   spre pressure smoothed through the grid ('smoo'; update_smoothed_pressure)
//   sspd longitudinal wave speed sqrt((K + 4G/3) / rho) at the current density, K the
//        EOS's reference bulk modulus (rho0 c0^2 Mie-Gruneisen, C1 polynomial) or
//        lambda + 2G/3 without an EOS; the material's wave speed when K + 4G/3 <= 0
// output_variables() is the one list of them: the deck reader accepts its names
// (is_output_variable), the writers look their functions up in it. A new variable is its
// function and one entry there (output_variables.cpp).
using ParticleVarFn = double (*)(const Model& m, int p);
struct OutputVariable {
  const char* name;
  ParticleVarFn fn;
};
const std::vector<OutputVariable>& output_variables();
ParticleVarFn output_variable(const std::string& name);  // nullptr for an unknown name
double particle_variable(const Model& m, const std::string& var, int p);

}  // namespace mpm3d
