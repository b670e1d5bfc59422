// Small HDF5 writing helpers shared by the state file and the HDF5 animation series:
// a file handle that closes itself, a dataset and a scalar attribute written in one call
// (untimed, so equal results give equal bytes), and per-particle arrays in deck order.
#pragma once
#include <hdf5.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "io/h5_quiet.hpp"
#include "core/particle.hpp"

namespace mpm3d {

struct H5File {
  hid_t id;
  ~H5File() {
    if (id >= 0) H5Fclose(id);
  }
};

inline void h5_check(herr_t s, const char* what) {
  if (s < 0) throw std::runtime_error(std::string("HDF5: cannot write ") + what);
}

// A (rows) dataset when cols is 0, else (rows, cols).
inline void h5_write_dataset(hid_t group, const char* name, hid_t type, const void* data, hsize_t rows,
                             hsize_t cols) {
  hsize_t dims[2] = {rows, cols};
  hid_t space = H5Screate_simple(cols ? 2 : 1, dims, nullptr);
  hid_t ds = H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5Untimed().dataset, H5P_DEFAULT);
  herr_t st = ds < 0 ? -1 : H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  h5_check(st, name);
}

inline void h5_write_attr(hid_t obj, const char* name, hid_t type, const void* v) {
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  herr_t st = a < 0 ? -1 : H5Awrite(a, type, v);
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  h5_check(st, name);
}

// A per-particle array (ncomp values each) in deck order: the order of every output file,
// whatever the solver's storage order (Particles::id; at = stored_index).
template <class T>
std::vector<T> deck_ordered(const std::vector<T>& a, int ncomp, const std::vector<int>& at) {
  std::vector<T> out(a.size());
  gather_rows(a.data(), ncomp, int(at.size()), [&](int i) { return at[size_t(i)]; }, out.data());
  return out;
}

}  // namespace mpm3d
