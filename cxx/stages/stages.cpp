// The stage table: the names of the stages, the C++ and the Fortran implementations, and
// the choice between them per stage (--kernel, --kernels).
#include <stdexcept>
#include <string>

#include "stages/update_step.hpp"

namespace mpm3d {

const char* const kStageNames[ST_COUNT] = {"bin", "p2g", "forces", "integrate",
                                           "g2p", "stress", "energy", "contact", "recontact"};

StageTable cxx_stages() {
  return StageTable{{mpm3d_cxx_bin, mpm3d_cxx_p2g, mpm3d_cxx_forces, mpm3d_cxx_integrate,
                     mpm3d_cxx_g2p, mpm3d_cxx_stress, mpm3d_cxx_energy, mpm3d_cxx_contact,
                     mpm3d_cxx_recontact}};
}

bool have_fortran_stages() {
#ifdef MPM3D_HAVE_FORTRAN
  return true;
#else
  return false;
#endif
}

StageTable fortran_stages() {
#ifdef MPM3D_HAVE_FORTRAN
  return StageTable{{mpm3d_f_bin, mpm3d_f_p2g, mpm3d_f_forces, mpm3d_f_integrate, mpm3d_f_g2p,
                     mpm3d_f_stress, mpm3d_f_energy, mpm3d_f_contact, mpm3d_f_recontact}};
#else
  throw std::runtime_error("this build has no Fortran reference kernels");
#endif
}

void select_stages(StageTable& t, const std::string& spec, bool per_stage) {
  auto table_for = [](const std::string& lang) {
    if (lang == "cxx") return cxx_stages();
    if (lang == "fortran") return fortran_stages();
    throw std::invalid_argument("unknown kernel language '" + lang + "' (cxx or fortran)");
  };
  if (!per_stage) {
    t = table_for(spec);
    return;
  }
  size_t pos = 0;
  while (pos <= spec.size()) {
    size_t end = spec.find(',', pos);
    if (end == std::string::npos) end = spec.size();
    const std::string item = spec.substr(pos, end - pos);
    const size_t eq = item.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("expected STAGE=LANG, got '" + item + "'");
    const std::string stage = item.substr(0, eq), lang = item.substr(eq + 1);
    int s = -1;
    for (int i = 0; i < ST_COUNT; ++i)
      if (stage == kStageNames[i]) s = i;
    if (s < 0) throw std::invalid_argument("unknown stage '" + stage + "' (see --list-stages)");
    t.fn[s] = table_for(lang).fn[s];
    pos = end + 1;
  }
}

}  // namespace mpm3d
