// The material models, one entry each: the deck keyword of the 'mate' card, the type, the
// parameters the card lists (in deck order, with the MaterialParams field each fills), what
// kind of solid or fluid it is, and the checks of its parameters. The deck reader, the
// keyword of a type and the derived constants (material.cpp) all ask this table; the stress
// update of a type is in its family's header (eos_lanes.hpp, j2_plasticity_lanes.hpp,
// drucker_prager_lanes.hpp, neo_hookean_lanes.hpp), which constitution_lanes.hpp dispatches
// to. Adding a model: a MaterialType value (material.hpp, and its Fortran mirror), one entry
// in material_models.cpp, its stress update (a family header and its branch in
// constitution_lanes.hpp), and the same in fortran_ref/material_models.f90 and the family
// module used by constitution.f90.
#pragma once
#include <string>

#include "materials/material.hpp"

namespace mpm3d {

// A number of the card: what the error messages call it and the field it goes to.
struct MaterialParam {
  const char* name;
  double MaterialParams::*field;
};

struct MaterialModel {
  const char* keyword;  // the deck's, four characters at most
  int type;             // MaterialType
  const MaterialParam* params;
  int nparams;
  bool fluid;          // no shear stiffness: pressure from its EOS only (hiex, null)
  bool johnson_cook;   // Johnson-Cook flow stress (n, C, reference strain rate checked)
  bool thermal;        // tracks temperature (room and melting temperature, specific heat)
  // Checks the card's values and sets what the card implies (e.g. the pla2 plastic
  // modulus from the tangent modulus); returns an error text or "". May be null.
  std::string (*finish)(MaterialParams& m);
};

// The model of a deck keyword (already cut to four characters), or null; current_version:
// the current version's card where it differs (null: density, bulk modulus, viscosity).
const MaterialModel* find_material_model(const std::string& keyword, bool current_version = false);
// The model of a MaterialType, or null for an unknown type.
const MaterialModel* material_model(int type);

}  // namespace mpm3d
