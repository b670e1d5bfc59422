// The HDF5 + XDMF animation series (output_writer.hpp: make_h5_series_writer).
#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <stdexcept>

#include "io/frame_fields.hpp"
#include "io/h5_write.hpp"
#include "io/output_writer.hpp"

namespace mpm3d {

namespace {

long long file_size(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0 ? (long long)st.st_size : -1;
}

std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '&') r += "&amp;";
    else if (c == '<') r += "&lt;";
    else if (c == '>') r += "&gt;";
    else if (c == '"') r += "&quot;";
    else r += c;
  }
  return r;
}

// A (rows) dataset (cols 0) or (rows, cols) one of type, its rows filled in blocks by
// fill(first row, rows, out): the grid of a large model is never held whole.
void h5_write_rows(hid_t loc, const char* name, hid_t type, hsize_t rows, hsize_t cols,
                   const std::function<void(hsize_t, hsize_t, void*)>& fill) {
  const hsize_t width = cols ? cols : 1, block = std::max<hsize_t>(1, (hsize_t(1) << 16) / width);
  hsize_t dims[2] = {rows, cols};
  hid_t space = H5Screate_simple(cols ? 2 : 1, dims, nullptr);
  hid_t ds = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5Untimed().dataset, H5P_DEFAULT);
  herr_t st = ds < 0 ? -1 : 0;
  std::vector<unsigned char> buf(size_t(block * width * H5Tget_size(type)));
  for (hsize_t r = 0; st >= 0 && r < rows; r += block) {
    const hsize_t n = std::min(block, rows - r);
    fill(r, n, buf.data());
    hsize_t start[2] = {r, 0}, count[2] = {n, cols};
    hid_t mem = H5Screate_simple(cols ? 2 : 1, count, nullptr);
    st = H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
    if (st >= 0) st = H5Dwrite(ds, type, mem, space, H5P_DEFAULT, buf.data());
    H5Sclose(mem);
  }
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  h5_check(st, name);
}

// The deck's grid, /grid/points and /grid/cells (hexahedra), when the file lacks it.
void write_grid(hid_t file, const DeckLattice& g) {
  if (H5Lexists(file, "/grid", H5P_DEFAULT) > 0) return;
  hid_t grp = H5Gcreate2(file, "/grid", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT);
  if (grp < 0) throw std::runtime_error("HDF5: cannot write /grid");
  try {
    h5_write_rows(grp, "points", H5T_NATIVE_DOUBLE, hsize_t(g.nodes()), 3, [&](hsize_t first, hsize_t n, void* out) {
      double* o = static_cast<double*>(out);
      for (hsize_t i = 0; i < n; ++i)
        for (int a = 0; a < 3; ++a) o[3 * i + hsize_t(a)] = g.node_coord((long long)(first + i), a);
    });
    h5_write_rows(grp, "cells", H5T_NATIVE_INT64, hsize_t(g.cells()), 8, [&](hsize_t first, hsize_t n, void* out) {
      int64_t* o = static_cast<int64_t*>(out);
      for (hsize_t i = 0; i < n; ++i)
        for (int k = 0; k < 8; ++k) o[8 * i + hsize_t(k)] = g.voxel_node((long long)(first + i), kHexFromVoxel[k]);
    });
  } catch (...) {
    H5Gclose(grp);
    throw;
  }
  H5Gclose(grp);
}

// /cells: the vertex of each particle (0 .. np - 1), when the file lacks it or has another count.
void write_vertices(hid_t file, hsize_t np) {
  if (H5Lexists(file, "/cells", H5P_DEFAULT) > 0) {
    hid_t ds = H5Dopen2(file, "/cells", H5P_DEFAULT);
    hid_t sp = ds < 0 ? -1 : H5Dget_space(ds);
    const bool same = sp >= 0 && H5Sget_simple_extent_npoints(sp) == hssize_t(np);
    if (sp >= 0) H5Sclose(sp);
    if (ds >= 0) H5Dclose(ds);
    if (same) return;
    H5Ldelete(file, "/cells", H5P_DEFAULT);
  }
  h5_write_rows(file, "/cells", H5T_NATIVE_INT64, np, 0, [](hsize_t first, hsize_t n, void* out) {
    int64_t* o = static_cast<int64_t*>(out);
    for (hsize_t i = 0; i < n; ++i) o[i] = int64_t(first + i);
  });
}

class H5SeriesWriter : public OutputWriter {
 public:
  H5SeriesWriter(const Model& m, const OutputFiles& files, const std::vector<double>& resume_times)
      : h5_(m.base_name + "_anim.h5"),
        h5_path_(files.path(h5_)),
        xdmf_path_(files.path(m.base_name + "_anim.xdmf")),
        fields_(frame_fields(m)),
        grid_(m) {
    const H5ErrorSilencer quiet;
    if (!resume_times.empty() && file_size(h5_path_) > 0 && resume(resume_times)) return;
    // New file (or a restart whose earlier series is gone: frames before it are not listed).
    first_ = resume_times.size();
    times_ = resume_times;
    H5File f{H5Fcreate(h5_path_.c_str(), H5F_ACC_TRUNC, H5Untimed().file, H5P_DEFAULT)};
    if (f.id < 0) throw std::runtime_error("cannot create " + h5_path_);
    hid_t g = H5Gcreate2(f.id, "/frames", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT);
    if (g < 0) throw std::runtime_error("cannot write " + h5_path_);
    H5Gclose(g);
    write_grid(f.id, grid_);
  }

  void frame(const Model& m, const std::vector<int>& at, double time, long step) override {
    const H5ErrorSilencer quiet;
    const size_t k = times_.size();
    {
      H5File f{H5Fopen(h5_path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)};
      if (f.id < 0) throw std::runtime_error("cannot open " + h5_path_);
      if (H5Lexists(f.id, "/frames", H5P_DEFAULT) <= 0) {
        hid_t g0 = H5Gcreate2(f.id, "/frames", H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT);
        if (g0 < 0) throw std::runtime_error("cannot write " + h5_path_);
        H5Gclose(g0);
      }
      const std::string name = "/frames/" + std::to_string(k);
      if (H5Lexists(f.id, name.c_str(), H5P_DEFAULT) > 0) H5Ldelete(f.id, name.c_str(), H5P_DEFAULT);
      hid_t g = H5Gcreate2(f.id, name.c_str(), H5P_DEFAULT, H5Untimed().group, H5P_DEFAULT);
      if (g < 0) throw std::runtime_error("cannot write " + h5_path_);
      try {
        const Particles& P = m.particles;
        const hsize_t n = hsize_t(P.np);
        h5_write_dataset(g, "position", H5T_NATIVE_DOUBLE, deck_ordered(P.x, 3, at).data(), n, 3);
        std::vector<double> buf(size_t(P.np));
        for (const FrameField& e : fields_) {
          if (e.alias_of >= 0) {
            h5_check(H5Lcreate_hard(g, fields_[size_t(e.alias_of)].name.c_str(), g, e.name.c_str(), H5P_DEFAULT,
                                    H5P_DEFAULT), e.name.c_str());
            continue;
          }
          for (int i = 0; i < P.np; ++i) buf[size_t(i)] = e.fn(m, at[size_t(i)]);
          h5_write_dataset(g, e.name.c_str(), H5T_NATIVE_DOUBLE, buf.data(), n, 0);
        }
        h5_write_attr(g, "time", H5T_NATIVE_DOUBLE, &time);
        h5_write_attr(g, "step", H5T_NATIVE_LONG, &step);
      } catch (...) {
        H5Gclose(g);
        throw;
      }
      H5Gclose(g);
      write_grid(f.id, grid_);
      write_vertices(f.id, hsize_t(m.particles.np));
    }
    times_.push_back(time);
    np_ = m.particles.np;
    write_xdmf();
  }

 private:
  std::string h5_, h5_path_, xdmf_path_;
  std::vector<FrameField> fields_;
  DeckLattice grid_;
  int np_ = 0;  // particles of a frame (all of them, also when the run's ranks hold parts)
  std::vector<double> times_;  // times_[k]: time of /frames/<k>
  size_t first_ = 0;           // first frame present in the .h5 file

  // Restart: keeps the frames written before the checkpoint and drops any written after
  // it, when the file's frames are those of the checkpoint (not a stale file of another
  // run); false otherwise.
  bool resume(const std::vector<double>& resume_times) {
    H5File f{H5Fopen(h5_path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)};
    bool same = f.id >= 0;
    for (size_t k = 0; same && k < resume_times.size(); ++k) {
      const std::string g = "/frames/" + std::to_string(k);
      double t = -1.0;
      same = H5Lexists(f.id, "/frames", H5P_DEFAULT) > 0 && H5Lexists(f.id, g.c_str(), H5P_DEFAULT) > 0 &&
             H5Aexists_by_name(f.id, g.c_str(), "time", H5P_DEFAULT) > 0;
      if (same) {
        hid_t a = H5Aopen_by_name(f.id, g.c_str(), "time", H5P_DEFAULT, H5P_DEFAULT);
        same = a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, &t) >= 0 && t == resume_times[k];
        if (a >= 0) H5Aclose(a);
      }
    }
    if (!same) return false;
    times_ = resume_times;
    if (H5Lexists(f.id, "/frames", H5P_DEFAULT) > 0) {
      for (size_t k = times_.size();; ++k) {
        const std::string g = "/frames/" + std::to_string(k);
        if (H5Lexists(f.id, g.c_str(), H5P_DEFAULT) <= 0) break;
        H5Ldelete(f.id, g.c_str(), H5P_DEFAULT);
      }
    }
    return true;
  }

  void write_xdmf() const {
    const std::string tmp = xdmf_path_ + ".tmp";
    FILE* f = std::fopen(tmp.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + xdmf_path_);
    const std::string h5 = xml_escape(h5_);
    std::fprintf(f, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
                    "  <Grid Name=\"series\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
    const std::string grid = h5 + ":/grid/";
    for (size_t k = first_; k < times_.size(); ++k) {
      const std::string g = h5 + ":/frames/" + std::to_string(k);
      std::fprintf(f, "   <Grid Name=\"frame_%zu\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
                      "    <Time Value=\"%.17g\"/>\n", k, times_[k]);
      // The particles: one vertex each (without the connectivity ParaView draws nothing).
      std::fprintf(f, "    <Grid Name=\"particles\" GridType=\"Uniform\">\n"
                      "     <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\" NodesPerElement=\"1\">\n"
                      "      <DataItem Dimensions=\"%d\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/cells</DataItem>\n"
                      "     </Topology>\n", np_, np_, h5.c_str());
      std::fprintf(f, "     <Geometry GeometryType=\"XYZ\">\n      <DataItem Dimensions=\"%d 3\" NumberType=\"Float\" "
                      "Precision=\"8\" Format=\"HDF\">%s/position</DataItem>\n     </Geometry>\n", np_, g.c_str());
      for (const FrameField& e : fields_) {
        const std::string v = xml_escape(e.name);
        std::fprintf(f, "     <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n      <DataItem "
                        "Dimensions=\"%d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s/%s</DataItem>\n"
                        "     </Attribute>\n", v.c_str(), np_, g.c_str(), v.c_str());
      }
      std::fprintf(f, "    </Grid>\n");
      // The background grid, the same in every step.
      std::fprintf(f, "    <Grid Name=\"grid\" GridType=\"Uniform\">\n"
                      "     <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"%lld\">\n"
                      "      <DataItem Dimensions=\"%lld 8\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%scells</DataItem>\n"
                      "     </Topology>\n     <Geometry GeometryType=\"XYZ\">\n      <DataItem Dimensions=\"%lld 3\" "
                      "NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%spoints</DataItem>\n     </Geometry>\n"
                      "    </Grid>\n   </Grid>\n",
                   grid_.cells(), grid_.cells(), grid.c_str(), grid_.nodes(), grid.c_str());
    }
    std::fprintf(f, "  </Grid>\n </Domain>\n</Xdmf>\n");
    const bool ok = std::fflush(f) == 0 && !std::ferror(f);
    std::fclose(f);
    if (!ok || std::rename(tmp.c_str(), xdmf_path_.c_str()) != 0) {
      std::remove(tmp.c_str());
      throw std::runtime_error("cannot write " + xdmf_path_);
    }
  }
};

}  // namespace

std::unique_ptr<OutputWriter> make_h5_series_writer(const Model& m, const OutputFiles& files,
                                                    const std::vector<double>& frame_times) {
  return std::make_unique<H5SeriesWriter>(m, files, frame_times);
}

}  // namespace mpm3d
