// The ParaView animation: one ASCII VTK unstructured grid of vertices per frame
// (name_anim_<k>.vtu) and the collection name_anim.pvd listing them with their times,
// rewritten at each frame (temporary + rename).
#include <cstdio>
#include <stdexcept>

#include "data_out.hpp"
#include "output_writer.hpp"

namespace mpm3d {

namespace {

class VtuWriter : public OutputWriter {
 public:
  VtuWriter(const Model& m, const OutputFiles& files, const std::vector<double>& frame_times)
      : files_(files), base_(m.base_name) {
    for (const auto& v : m.anim_vars) fn_.push_back(output_variable(v));
    for (size_t k = 0; k < frame_times.size(); ++k) pvd_.emplace_back(frame_times[k], vtu_name(k));
  }

  void frame(const Model& m, const std::vector<int>& at, double time, long) override {
    const Particles& P = m.particles;
    const std::string name = vtu_name(pvd_.size());
    FILE* f = files_.create(name);
    std::fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                    "<UnstructuredGrid>\n<Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n<Points>\n"
                    "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n", P.np, P.np);
    for (int i = 0; i < P.np; ++i) {
      const size_t p = size_t(at[size_t(i)]);
      std::fprintf(f, "%.9E %.9E %.9E\n", P.x[3 * p], P.x[3 * p + 1], P.x[3 * p + 2]);
    }
    std::fprintf(f, "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "%d\n", p);
    std::fprintf(f, "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "%d\n", p + 1);
    std::fprintf(f, "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (int p = 0; p < P.np; ++p) std::fprintf(f, "1\n");
    std::fprintf(f, "</DataArray>\n</Cells>\n<PointData>\n");
    for (size_t v = 0; v < fn_.size(); ++v) {
      std::fprintf(f, "<DataArray type=\"Float64\" Name=\"%s\" format=\"ascii\">\n", m.anim_vars[v].c_str());
      for (int i = 0; i < P.np; ++i) std::fprintf(f, "%.9E\n", fn_[v](m, at[size_t(i)]));
      std::fprintf(f, "</DataArray>\n");
    }
    std::fprintf(f, "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    std::fclose(f);
    pvd_.emplace_back(time, name);
    write_pvd();
  }

 private:
  OutputFiles files_;  // new files only: a frame file is never resumed
  std::string base_;
  std::vector<ParticleVarFn> fn_;
  std::vector<std::pair<double, std::string>> pvd_;  // time and file of each frame so far

  std::string vtu_name(size_t k) const { return base_ + "_anim_" + std::to_string(k) + ".vtu"; }

  void write_pvd() const {
    const std::string path = files_.path(base_ + "_anim.pvd");
    FILE* pvd = std::fopen((path + ".tmp").c_str(), "w");
    if (!pvd) throw std::runtime_error("cannot write " + path);
    std::fprintf(pvd, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
    for (const auto& e : pvd_)
      std::fprintf(pvd, "<DataSet timestep=\"%.9E\" part=\"0\" file=\"%s\"/>\n", e.first, e.second.c_str());
    std::fprintf(pvd, "</Collection>\n</VTKFile>\n");
    std::fclose(pvd);
    if (std::rename((path + ".tmp").c_str(), path.c_str()) != 0) throw std::runtime_error("cannot write " + path);
  }
};

}  // namespace

std::unique_ptr<OutputWriter> make_vtu_writer(const Model& m, const OutputFiles& files,
                                              const std::vector<double>& frame_times) {
  return std::make_unique<VtuWriter>(m, files, frame_times);
}

}  // namespace mpm3d
