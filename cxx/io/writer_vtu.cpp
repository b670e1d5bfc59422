// The ParaView animation, as the original writes it: one VTK unstructured grid of vertices
// per frame, name_anim_<k>.vtu with k = 1, 2, ... (frame 1 the initial state), the
// collection name_anim.pvd listing them with their times (rewritten at each frame,
// temporary + rename), and the background grid name_Grid.vtu (hexahedral voxels, written
// when the run starts). The frames hold the fields of frame_fields(): the original's set for
// the deck's version, then the outr variables. ASCII by default, as the original (10
// significant digits); binary on request (--vtu-binary): the same arrays as appended raw
// data, each block behind a UInt64 byte count, an outr variable that is one of the
// original's fields under another name pointing at that field's block.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "io/ascii_out.hpp"
#include "io/frame_fields.hpp"
#include "io/output_writer.hpp"

namespace mpm3d {

namespace {

enum class VtuType { f64, i32, u8 };

const char* type_name(VtuType t) { return t == VtuType::f64 ? "Float64" : t == VtuType::i32 ? "Int32" : "UInt8"; }
size_t type_size(VtuType t) { return t == VtuType::f64 ? 8 : t == VtuType::i32 ? 4 : 1; }

// One DataArray of a piece. fill(first, count, out) puts values first .. first + count - 1
// (components counted singly) into out, as type; the file is written in chunks of them.
struct VtuArray {
  const char* section;  // "PointData", "Points" or "Cells"
  std::string name;     // none for the points
  VtuType type;
  int ncomp;
  long long values;
  int per_line;  // ASCII: values per line
  std::function<void(long long first, long long count, void* out)> fill;
  int alias_of = -1;  // binary: shares the block of that earlier array
};

bool little_endian() {
  const uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

// Writes a whole .vtu file of one piece.
void write_vtu(FILE* f, long long npoints, long long ncells, const std::vector<VtuArray>& arrays, bool binary) {
  constexpr long long kChunk = 1 << 16;
  std::fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"%s\" "
                  "header_type=\"UInt64\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"%lld\" NumberOfCells=\"%lld\">\n",
               little_endian() ? "LittleEndian" : "BigEndian", npoints, ncells);
  std::vector<unsigned long long> offset(arrays.size(), 0);
  unsigned long long next = 0;
  for (size_t a = 0; a < arrays.size(); ++a) {
    if (arrays[a].alias_of >= 0) {
      offset[a] = offset[size_t(arrays[a].alias_of)];
      continue;
    }
    offset[a] = next;
    next += sizeof(uint64_t) + (unsigned long long)(arrays[a].values) * type_size(arrays[a].type);
  }
  std::vector<unsigned char> buf(size_t(kChunk) * 8);
  for (const char* section : {"PointData", "Points", "Cells"}) {
    bool open = false;
    for (size_t a = 0; a < arrays.size(); ++a) {
      const VtuArray& v = arrays[a];
      if (std::strcmp(v.section, section) != 0) continue;
      if (!open) std::fprintf(f, "<%s>\n", section);
      open = true;
      std::fprintf(f, "<DataArray type=\"%s\"", type_name(v.type));
      if (!v.name.empty()) std::fprintf(f, " Name=\"%s\"", v.name.c_str());
      if (v.ncomp > 1) std::fprintf(f, " NumberOfComponents=\"%d\"", v.ncomp);
      if (binary) {
        std::fprintf(f, " format=\"appended\" offset=\"%llu\"/>\n", offset[a]);
        continue;
      }
      std::fprintf(f, " format=\"ascii\">\n");
      AsciiOut out(f);
      for (long long first = 0; first < v.values; first += kChunk) {
        const long long n = std::min(kChunk, v.values - first);
        v.fill(first, n, buf.data());
        for (long long i = 0; i < n; ++i) {
          if (v.type == VtuType::f64) {
            double x;
            std::memcpy(&x, buf.data() + 8 * size_t(i), 8);
            out.sci(x, 9);
          } else if (v.type == VtuType::i32) {
            int32_t x;
            std::memcpy(&x, buf.data() + 4 * size_t(i), 4);
            out.integer(x);
          } else {
            out.integer(buf[size_t(i)]);
          }
          out.put((first + i + 1) % v.per_line == 0 ? '\n' : ' ');
        }
      }
      out.flush();
      if (v.values % v.per_line != 0) std::fputc('\n', f);
      std::fprintf(f, "</DataArray>\n");
    }
    if (open) std::fprintf(f, "</%s>\n", section);
  }
  std::fprintf(f, "</Piece>\n</UnstructuredGrid>\n");
  if (binary) {
    std::fprintf(f, "<AppendedData encoding=\"raw\">\n_");
    for (const VtuArray& v : arrays) {
      if (v.alias_of >= 0) continue;
      const uint64_t bytes = uint64_t(v.values) * type_size(v.type);
      std::fwrite(&bytes, sizeof bytes, 1, f);
      for (long long first = 0; first < v.values; first += kChunk) {
        const long long n = std::min(kChunk, v.values - first);
        v.fill(first, n, buf.data());
        std::fwrite(buf.data(), type_size(v.type), size_t(n), f);
      }
    }
    std::fprintf(f, "\n</AppendedData>\n");
  }
  std::fprintf(f, "</VTKFile>\n");
}

void close_checked(FILE* f, const std::string& path) {
  const bool ok = std::fflush(f) == 0 && !std::ferror(f);
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write " + path);
}

template <class T>
void put(void* out, long long i, T v) {
  std::memcpy(static_cast<unsigned char*>(out) + sizeof(T) * size_t(i), &v, sizeof(T));
}

// The vertex cells of n points: cell p is point p.
void vertex_cells(std::vector<VtuArray>& a, long long n) {
  a.push_back({"Cells", "connectivity", VtuType::i32, 1, n, 1, [](long long first, long long count, void* out) {
                 for (long long i = 0; i < count; ++i) put(out, i, int32_t(first + i));
               }});
  a.push_back({"Cells", "offsets", VtuType::i32, 1, n, 1, [](long long first, long long count, void* out) {
                 for (long long i = 0; i < count; ++i) put(out, i, int32_t(first + i + 1));
               }});
  a.push_back({"Cells", "types", VtuType::u8, 1, n, 1, [](long long, long long count, void* out) {
                 std::memset(out, 1, size_t(count));  // VTK_VERTEX
               }});
}

class VtuWriter : public OutputWriter {
 public:
  VtuWriter(const Model& m, const OutputFiles& files, const std::vector<double>& frame_times, bool binary)
      : files_(files), base_(m.base_name), binary_(binary), fields_(frame_fields(m)) {
    for (size_t k = 0; k < frame_times.size(); ++k) pvd_.emplace_back(frame_times[k], vtu_name(k));
    write_grid(m);
  }

  void frame(const Model& m, const std::vector<int>& at, double time, long) override {
    const long long np = m.particles.np;
    std::vector<VtuArray> arrays;
    for (const FrameField& e : fields_) {
      const ParticleVarFn fn = e.fn;
      arrays.push_back({"PointData", e.name, VtuType::f64, 1, np, 1,
                        [&m, &at, fn](long long first, long long count, void* out) {
                          for (long long i = 0; i < count; ++i) put(out, i, fn(m, at[size_t(first + i)]));
                        },
                        e.alias_of});
    }
    const double* x = m.particles.x.data();
    arrays.push_back({"Points", "", VtuType::f64, 3, 3 * np, 3, [x, &at](long long first, long long count, void* out) {
                        for (long long i = 0; i < count; ++i) {
                          const long long v = first + i;
                          put(out, i, x[3 * size_t(at[size_t(v / 3)]) + size_t(v % 3)]);
                        }
                      }});
    vertex_cells(arrays, np);
    const std::string name = vtu_name(pvd_.size());
    FILE* f = files_.create(name);
    write_vtu(f, np, np, arrays, binary_);
    close_checked(f, files_.path(name));
    pvd_.emplace_back(time, name);
    write_pvd();
  }

 private:
  OutputFiles files_;  // new files only: a frame file is never resumed
  std::string base_;
  bool binary_;
  std::vector<FrameField> fields_;
  std::vector<std::pair<double, std::string>> pvd_;  // time and file of each frame so far

  // Frame k (from 0) is file k + 1, as the original numbers them.
  std::string vtu_name(size_t k) const { return base_ + "_anim_" + std::to_string(k + 1) + ".vtu"; }

  // name_Grid.vtu: the nodes of the deck's grid and its cells as voxels (VTK type 11).
  void write_grid(const Model& m) const {
    const DeckLattice g(m);
    std::vector<VtuArray> arrays;
    arrays.push_back({"Points", "", VtuType::f64, 3, 3 * g.nodes(), 3, [&g](long long first, long long count, void* out) {
                        for (long long i = 0; i < count; ++i) put(out, i, g.node_coord((first + i) / 3, int((first + i) % 3)));
                      }});
    arrays.push_back({"Cells", "connectivity", VtuType::i32, 1, 8 * g.cells(), 8,
                      [&g](long long first, long long count, void* out) {
                        for (long long i = 0; i < count; ++i)
                          put(out, i, int32_t(g.voxel_node((first + i) / 8, int((first + i) % 8))));
                      }});
    arrays.push_back({"Cells", "offsets", VtuType::i32, 1, g.cells(), 1, [](long long first, long long count, void* out) {
                        for (long long i = 0; i < count; ++i) put(out, i, int32_t(8 * (first + i + 1)));
                      }});
    arrays.push_back({"Cells", "types", VtuType::u8, 1, g.cells(), 1, [](long long, long long count, void* out) {
                        std::memset(out, 11, size_t(count));  // VTK_VOXEL
                      }});
    if (8 * g.cells() > 2147483647LL) throw std::runtime_error("the grid is too large for " + base_ + "_Grid.vtu");
    const std::string name = base_ + "_Grid.vtu";
    FILE* f = files_.create(name);
    write_vtu(f, g.nodes(), g.cells(), arrays, binary_);
    close_checked(f, files_.path(name));
  }

  void write_pvd() const {
    const std::string path = files_.path(base_ + "_anim.pvd");
    FILE* pvd = std::fopen((path + ".tmp").c_str(), "w");
    if (!pvd) throw std::runtime_error("cannot write " + path);
    std::fprintf(pvd, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n");
    for (const auto& e : pvd_)
      std::fprintf(pvd, "<DataSet timestep=\"%.17g\" part=\"0\" file=\"%s\"/>\n", e.first, e.second.c_str());
    std::fprintf(pvd, "</Collection>\n</VTKFile>\n");
    close_checked(pvd, path);
    if (std::rename((path + ".tmp").c_str(), path.c_str()) != 0) throw std::runtime_error("cannot write " + path);
  }
};

}  // namespace

std::unique_ptr<OutputWriter> make_vtu_writer(const Model& m, const OutputFiles& files,
                                              const std::vector<double>& frame_times, bool binary) {
  return std::make_unique<VtuWriter>(m, files, frame_times, binary);
}

}  // namespace mpm3d
