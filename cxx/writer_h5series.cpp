// The HDF5 + XDMF animation series (output_writer.hpp: make_h5_series_writer).
#include <sys/stat.h>

#include <cstdio>
#include <stdexcept>

#include "data_out.hpp"
#include "h5_write.hpp"
#include "output_writer.hpp"

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

class H5SeriesWriter : public OutputWriter {
 public:
  H5SeriesWriter(const Model& m, const OutputFiles& files, const std::vector<double>& resume_times)
      : h5_(m.base_name + "_anim.h5"),
        h5_path_(files.path(h5_)),
        xdmf_path_(files.path(m.base_name + "_anim.xdmf")),
        vars_(m.anim_vars) {
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
        for (const auto& v : vars_) {
          const ParticleVarFn fn = output_variable(v);
          for (int i = 0; i < P.np; ++i) buf[size_t(i)] = fn(m, at[size_t(i)]);
          h5_write_dataset(g, v.c_str(), H5T_NATIVE_DOUBLE, buf.data(), n, 0);
        }
        h5_write_attr(g, "time", H5T_NATIVE_DOUBLE, &time);
        h5_write_attr(g, "step", H5T_NATIVE_LONG, &step);
      } catch (...) {
        H5Gclose(g);
        throw;
      }
      H5Gclose(g);
    }
    times_.push_back(time);
    np_ = m.particles.np;
    write_xdmf();
  }

 private:
  std::string h5_, h5_path_, xdmf_path_;
  std::vector<std::string> vars_;
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
                    "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
    for (size_t k = first_; k < times_.size(); ++k) {
      const std::string g = h5 + ":/frames/" + std::to_string(k);
      std::fprintf(f, "   <Grid Name=\"frame_%zu\" GridType=\"Uniform\">\n    <Time Value=\"%.17g\"/>\n", k, times_[k]);
      std::fprintf(f, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%d\" NodesPerElement=\"1\"/>\n", np_);
      std::fprintf(f, "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"%d 3\" NumberType=\"Float\" "
                      "Precision=\"8\" Format=\"HDF\">%s/position</DataItem>\n    </Geometry>\n", np_, g.c_str());
      for (const auto& v : vars_)
        std::fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n     <DataItem "
                        "Dimensions=\"%d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s/%s</DataItem>\n"
                        "    </Attribute>\n", v.c_str(), np_, g.c_str(), v.c_str());
      std::fprintf(f, "   </Grid>\n");
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
