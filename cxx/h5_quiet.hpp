// Silences HDF5's own error printing for one call (we report our own messages) and
// restores the caller's handler, so a Fortran or C program using HDF5 keeps its own.
#pragma once
#include <hdf5.h>

namespace mpm3d {

struct H5ErrorSilencer {
  H5E_auto2_t func = nullptr;
  void* data = nullptr;
  H5ErrorSilencer() {
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~H5ErrorSilencer() { H5Eset_auto2(H5E_DEFAULT, func, data); }
};

}  // namespace mpm3d
