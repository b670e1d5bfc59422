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

// Creation property lists without the objects' modification times, which HDF5 stores by
// default: the same results then give the same bytes, so output files can be compared
// with cmp and a rerun changes nothing. For the file (its root group), groups and datasets.
struct H5Untimed {
  hid_t file = H5Pcreate(H5P_FILE_CREATE);
  hid_t group = H5Pcreate(H5P_GROUP_CREATE);
  hid_t dataset = H5Pcreate(H5P_DATASET_CREATE);
  H5Untimed() {
    H5Pset_obj_track_times(file, 0);
    H5Pset_obj_track_times(group, 0);
    H5Pset_obj_track_times(dataset, 0);
  }
  ~H5Untimed() {
    H5Pclose(file);
    H5Pclose(group);
    H5Pclose(dataset);
  }
  H5Untimed(const H5Untimed&) = delete;
  H5Untimed& operator=(const H5Untimed&) = delete;
};

}  // namespace mpm3d
