// The ranks of a distributed run over MPI (cxx/parallel/ranks.hpp), and the program's MPI entry
// run_main_mpi. Linked into the mpm3d program only when CMake finds MPI (MPM3D_MPI).
//
// Ownership: rank r owns the patches [first_[r], first_[r+1]) (runs of consecutive patch
// indices with equal shares of the particles, the rule OpenMP threads use inside a rank),
// the particles inside them, and those outside the grid if it is the last rank. Every
// rank keeps the whole grid window's node arrays; it assembles the nodes its particles read
// from its own patch buffers and copies of its neighbours' (ghost patches), of which only
// those nodes travel.
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "mpm3d.hpp"
#include "stages/patch_index.hpp"
#include "parallel/ranks.hpp"
#include "solver/simulation.hpp"
#include "transfer/transfer_lanes.hpp"

namespace mpm3d {
namespace {

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

class MpiRanks final : public Ranks {
 public:
  explicit MpiRanks(MPI_Comm comm) : comm_(comm) {
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int global_np() const override { return np_global_; }
  double imbalance() const override { return imbalance_; }
  double bytes_sent() const override { return bytes_sent_; }
  long rebalances() const override { return rebalances_; }
  void set_rebalance_above(double ratio) override { rebalance_above_ = ratio; }

  void distribute(Simulation& sim) override;
  void migrate(Simulation& sim) override;
  void add_ghost_slots(Simulation& sim) override;

  long sum(long v) override { return reduce(v, MPI_LONG, MPI_SUM); }
  int min(int v) override { return reduce(v, MPI_INT, MPI_MIN); }
  double min(double v) override { return reduce(v, MPI_DOUBLE, MPI_MIN); }
  double max(double v) override { return reduce(v, MPI_DOUBLE, MPI_MAX); }
  void max(std::vector<double>& values) override {
    if (!values.empty())
      check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_MAX, comm_), "reduction");
  }
  std::string broadcast(const std::string& s, int from) override {
    int n = int(s.size());
    check(MPI_Bcast(&n, 1, MPI_INT, from, comm_), "broadcast");
    std::string r = s;
    r.resize(size_t(n));
    if (n > 0) check(MPI_Bcast(&r[0], n, MPI_CHAR, from, comm_), "broadcast");
    return r;
  }
  void broadcast(std::vector<double>& values) override {
    long n = long(values.size());
    check(MPI_Bcast(&n, 1, MPI_LONG, 0, comm_), "broadcast");
    values.resize(size_t(n));
    if (n > 0) check(MPI_Bcast(values.data(), int(n), MPI_DOUBLE, 0, comm_), "broadcast");
  }
  void gather(const Particles& local, Particles& all) override;
  void share_owned_nodes(const StepContext& c, double* field, int ncomp) override;
  [[noreturn]] void abort(int code) override {
    MPI_Abort(comm_, code);
    std::exit(code);
  }

  // StepContext::exchange.
  static void exchange(const StepContext* c, int kind, int first, int count) {
    auto* self = static_cast<MpiRanks*>(c->exchange_data);
    if (kind == EXCHANGE_BUFFERS) self->exchange_buffers(c, first, count);
    else if (kind == EXCHANGE_PARTIALS) self->exchange_columns(c->partials, kReduceFields, true);
    else self->exchange_columns(c->cpartials, kContactFields, false);
  }

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  int np_global_ = 0;
  double imbalance_ = 1.0;
  double bytes_sent_ = 0.0;  // put into messages to other ranks (a collective: this rank's part once)
  std::vector<int> gidx_;    // storage index of each local particle on one rank
  std::vector<int> first_;   // (size + 1) first patch of each rank
  std::vector<int> owner_;   // (npatch) rank of each patch
  int window_[6] = {};       // the grid window (offset, cells per axis) owner_ was drawn for
  std::vector<int> counts_;  // (npatch + 1) particles of each patch on all ranks, then the
                             // particles that change rank in this step; with contact then
                             // (npatch) component 2's particles of each patch
  bool contact_ = false;
  std::vector<int> dest_;  // rank of each local particle (migrate's scratch)
  // The local rows in ascending storage index (StepContext::order), its next version, and
  // each old row's new index (migrate's scratch).
  std::vector<int> perm_, perm_next_, newidx_;
  long rebalances_ = 0;
  // The largest rank's share of the particles over the mean above which the ranks' patch
  // runs are redrawn before a step (--rebalance-above; docs/PERFORMANCE.md, "MPI ranks").
  double rebalance_above_ = 1.03;
  // Per neighbouring rank: this rank's patches next to one of its patches (what it is
  // sent) and its patches next to one of this rank's (what comes back), ascending.
  // Of each of those patches' buffers only the nodes inside the node span of one of the
  // receiving rank's patches travel (the nodes its particles read and it assembles; the
  // rest of a ghost buffer is never read): local buffer indices, ascending, per patch
  // (send_nodes[send_start[i] ..] for send[i]; the same for recv). Both ranks draw them
  // from owner_ by the same rule, so the lists agree.
  struct Neighbour {
    int rank;
    std::vector<int> send, recv;
    std::vector<int> send_nodes, send_start, recv_nodes, recv_start;
    std::vector<double> out, in;  // the packed values of the non-empty ones
  };
  std::vector<Neighbour> neighbours_;
  std::vector<int> fields_;  // indices in particle_fields() of the arrays this run has

  template <class T>
  T reduce(T v, MPI_Datatype type, MPI_Op op) {
    T r{};
    check(MPI_Allreduce(&v, &r, 1, type, op, comm_), "reduction");
    return r;
  }
  // The bin stage's binning of particles [lo, hi) of either component: cell, lx and patch
  // (pscratch) rows, which the bin stage then takes as they are (StepContext::prebinned).
  static void bin_rows(const StepContext& c, int lo, int hi);
  // Particles of patch q on all ranks: of the context's component (1 or 2 with contact).
  int count(int q, int comp) const {
    const size_t np1 = owner_.size() + 1;
    if (comp == 0) return counts_[size_t(q)];
    return comp == 2 ? counts_[np1 + size_t(q)] : counts_[size_t(q)] - counts_[np1 + size_t(q)];
  }
  // True when particle p is of contact component 2.
  bool second(const StepContext& c, int p) const { return contact_ && c.body_comp[c.body[p]] == 2; }
  bool same_window(const StepContext& c) const {
    for (int a = 0; a < 3; ++a)
      if (window_[a] != c.cell_off[a] || window_[3 + a] != c.nc[a]) return false;
    return true;
  }
  // The ranks' first patches by the rule above, from counts_.
  std::vector<int> draw(int npatch) const;
  void partition(const Simulation& sim, std::vector<int> first);
  // Appends to out the local indices of the nodes of patch q's buffer that lie inside the
  // node span of a patch of rank reader (mark: scratch).
  void shared_nodes(const StepContext& c, int q, int reader, std::vector<unsigned char>& mark,
                    std::vector<int>& out) const;
  size_t row_bytes(Particles& P) const;
  void pack_row(Particles& P, int p, int gidx, char* out) const;
  void exchange_buffers(const StepContext* c, int first, int nfield);
  // A stage's per-patch columns of nf fields: every rank's own (and, with outside, the
  // last rank's column of the particles outside the grid) to every rank; with outside
  // (the energy stage's particle sums) only the non-empty patches' columns.
  void exchange_columns(double* cols, int nf, bool outside);
};

// The bin stage's own kernel (transfer_lanes.hpp, bin_range), so both always agree.
void MpiRanks::bin_rows(const StepContext& c, int lo, int hi) {
  StepContext all = c;
  all.only_comp = 0;  // the patches of both contact components
  if (lanes_use_avx2()) bin_range_avx2(&all, lo, hi, all.pscratch);
  else bin_range<VectorLane<kLanes>>(&all, lo, hi, all.pscratch);
}

// The ranks' patch runs from counts_ (thread_patches' rule over ranks: rank u starts at
// the first patch whose prefix count reaches u/size of the particles), then the patches
// each neighbouring rank needs.
std::vector<int> MpiRanks::draw(int npatch) const {
  std::vector<long> prefix(size_t(npatch) + 1, 0);
  for (int q = 0; q < npatch; ++q) prefix[size_t(q) + 1] = prefix[size_t(q)] + counts_[size_t(q)];
  const long total = prefix[size_t(npatch)];
  std::vector<int> first(size_t(size_) + 1, npatch);
  for (int u = 0; u < size_; ++u) {
    const long target = total * u / size_;
    first[size_t(u)] = int(std::lower_bound(prefix.begin(), prefix.end() - 1, target) - prefix.begin());
  }
  first[0] = 0;
  return first;
}

void MpiRanks::partition(const Simulation& sim, std::vector<int> first) {
  const StepContext& c = sim.ctx;
  const int npatch = c.npatch;
  first_ = std::move(first);
  for (int a = 0; a < 3; ++a) {
    window_[a] = c.cell_off[a];
    window_[3 + a] = c.nc[a];
  }
  owner_.assign(size_t(npatch), 0);
  for (int u = 0; u < size_; ++u)
    for (int q = first_[size_t(u)]; q < first_[size_t(u) + 1]; ++q) owner_[size_t(q)] = u;
  std::vector<std::vector<int>> send(static_cast<size_t>(size_)), recv(static_cast<size_t>(size_));
  const int n0 = c.npd[0], n1 = c.npd[1], n2 = c.npd[2];
  // The patches whose buffers add into a node this rank's particles read, along one axis:
  // a particle of patch q reads nodes q P - H .. (q + 1) P + H (H the halo of the wide
  // stencils), and patch r's buffer holds nodes r P - H .. (r + 1) P + H, so r lies within
  // q -+ (1 + floor(2 H / P)): one patch each way for the trilinear stencil, and for the
  // 27-node ones when P >= 3.
  const int R = 1 + (2 * c.patch_halo) / c.patch_cells;
  for (int q = first_[size_t(rank_)]; q < first_[size_t(rank_) + 1]; ++q) {
    const int qx = q % n0, qy = (q / n0) % n1, qz = q / (n0 * n1);
    for (int dz = -R; dz <= R; ++dz)
      for (int dy = -R; dy <= R; ++dy)
        for (int dx = -R; dx <= R; ++dx) {
          const int x = qx + dx, y = qy + dy, z = qz + dz;
          if (x < 0 || y < 0 || z < 0 || x >= n0 || y >= n1 || z >= n2) continue;
          const int o = x + n0 * (y + n1 * z), s = owner_[size_t(o)];
          if (s == rank_) continue;
          send[size_t(s)].push_back(q);
          recv[size_t(s)].push_back(o);
        }
  }
  neighbours_.clear();
  for (int s = 0; s < size_; ++s) {
    if (send[size_t(s)].empty()) continue;
    Neighbour n;
    n.rank = s;
    for (auto* v : {&send[size_t(s)], &recv[size_t(s)]}) {
      std::sort(v->begin(), v->end());
      v->erase(std::unique(v->begin(), v->end()), v->end());
    }
    n.send = std::move(send[size_t(s)]);
    n.recv = std::move(recv[size_t(s)]);
    std::vector<unsigned char> mark;
    n.send_start.assign(1, 0);
    for (int q : n.send) {
      shared_nodes(c, q, s, mark, n.send_nodes);
      n.send_start.push_back(int(n.send_nodes.size()));
    }
    n.recv_start.assign(1, 0);
    for (int q : n.recv) {
      shared_nodes(c, q, rank_, mark, n.recv_nodes);
      n.recv_start.push_back(int(n.recv_nodes.size()));
    }
    neighbours_.push_back(std::move(n));
  }
}

// Patch o's particles read the nodes o P - H .. (o + 1) P + H per axis, which is also the
// span of o's buffer; in the local coordinates of q's buffer (first node q P - H) that is
// (o - q) P .. (o - q) P + P + 2 H. The patches whose span meets q's lie within R of it.
void MpiRanks::shared_nodes(const StepContext& c, int q, int reader, std::vector<unsigned char>& mark,
                            std::vector<int>& out) const {
  const int P = c.patch_cells, H = c.patch_halo, Q = P + 1 + 2 * H, R = 1 + (2 * H) / P;
  const int n0 = c.npd[0], n1 = c.npd[1], n2 = c.npd[2];
  const int q3[3] = {q % n0, (q / n0) % n1, q / (n0 * n1)};
  mark.assign(size_t(Q) * size_t(Q) * size_t(Q), 0);
  for (int dz = -R; dz <= R; ++dz)
    for (int dy = -R; dy <= R; ++dy)
      for (int dx = -R; dx <= R; ++dx) {
        const int d[3] = {dx, dy, dz};
        const int x = q3[0] + dx, y = q3[1] + dy, z = q3[2] + dz;
        if (x < 0 || y < 0 || z < 0 || x >= n0 || y >= n1 || z >= n2) continue;
        if (owner_[size_t(x + n0 * (y + n1 * z))] != reader) continue;
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::max(0, d[a] * P);
          hi[a] = std::min(Q - 1, d[a] * P + P + 2 * H);
        }
        for (int k = lo[2]; k <= hi[2]; ++k)
          for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; ++i) mark[size_t(i + Q * (j + Q * k))] = 1;
      }
  for (size_t i = 0; i < mark.size(); ++i)
    if (mark[i]) out.push_back(int(i));
}

size_t MpiRanks::row_bytes(Particles& P) const {
  const std::vector<ParticleField> f = particle_fields(P);
  size_t b = sizeof(int);
  for (int k : fields_) b += size_t(f[size_t(k)].ncomp) * (f[size_t(k)].d ? sizeof(double) : sizeof(int32_t));
  return b;
}

void MpiRanks::pack_row(Particles& P, int p, int gidx, char* out) const {
  const std::vector<ParticleField> f = particle_fields(P);
  std::memcpy(out, &gidx, sizeof(int));
  out += sizeof(int);
  for (int k : fields_) {
    const ParticleField& fk = f[size_t(k)];
    const size_t n = size_t(fk.ncomp);
    if (fk.d) {
      std::memcpy(out, fk.d->data() + n * size_t(p), n * sizeof(double));
      out += n * sizeof(double);
    } else {
      std::memcpy(out, fk.i->data() + n * size_t(p), n * sizeof(int32_t));
      out += n * sizeof(int32_t);
    }
  }
}

void MpiRanks::distribute(Simulation& sim) {
  Particles& P = sim.model.particles;
  np_global_ = P.np;
  if (P.id.empty()) throw std::logic_error("ranks: the particles carry no deck numbers");
  {
    const std::vector<ParticleField> f = particle_fields(P);
    fields_.clear();
    for (size_t k = 0; k < f.size(); ++k)
      if (f[k].d ? !f[k].d->empty() : !f[k].i->empty()) fields_.push_back(int(k));
  }
  // Every rank holds every particle here: the counts need no communication.
  const StepContext& c = sim.ctx;
  contact_ = c.other != nullptr;
  counts_.assign(size_t(c.npatch) + 1 + (contact_ ? size_t(c.npatch) : 0), 0);
  bin_rows(c, 0, P.np);  // every particle's patch, in pscratch
  const int* patch = c.pscratch;
  for (int p = 0; p < P.np; ++p) {
    const int q = patch[p];
    if (q < 0) continue;
    ++counts_[size_t(q)];
    if (second(c, p)) ++counts_[size_t(c.npatch) + 1 + size_t(q)];
  }
  partition(sim, draw(c.npatch));
  std::vector<int> keep;
  for (int p = 0; p < P.np; ++p) {
    const int q = patch[p];
    if ((q >= 0 ? owner_[size_t(q)] : size_ - 1) == rank_) keep.push_back(p);
  }
  for (const ParticleField& f : particle_fields(P)) {
    const int n = f.ncomp;
    if (f.d && !f.d->empty()) {
      std::vector<double> v(size_t(n) * keep.size());
      gather_rows(f.d->data(), n, int(keep.size()), [&](int i) { return keep[size_t(i)]; }, v.data());
      *f.d = std::move(v);
    } else if (f.i && !f.i->empty()) {
      std::vector<int32_t> v(size_t(n) * keep.size());
      gather_rows(f.i->data(), n, int(keep.size()), [&](int i) { return keep[size_t(i)]; }, v.data());
      *f.i = std::move(v);
    }
  }
  P.np = int(keep.size());
  gidx_ = std::move(keep);
  perm_.resize(gidx_.size());
  std::iota(perm_.begin(), perm_.end(), 0);
  // Before the rebinding, which copies the context into component 2's (contact).
  sim.ctx.exchange = &MpiRanks::exchange;
  sim.ctx.exchange_data = this;
  sim.ctx.order = perm_.data();
  sim.ctx.prebinned = 1;
  sim.particles_changed();
  bin_rows(sim.ctx, 0, P.np);
}

void MpiRanks::migrate(Simulation& sim) {
  Particles& P = sim.model.particles;
  const StepContext& c = sim.ctx;
  const int npatch = c.npatch;
  const int ncount = npatch + 1 + (contact_ ? npatch : 0);
  std::vector<int> local(size_t(ncount), 0);
  dest_.resize(size_t(P.np));
  auto rank_of = [&](int q) { return q >= 0 ? owner_[size_t(q)] : size_ - 1; };
  // A new grid window (the adaptive grid, on every rank alike) has other patches: the
  // ranks' runs are drawn for it below, and the particles counted as moving then.
  const bool new_window = !same_window(c);
  // The bin stage's binning, done here (prebinned): it tells which particles move.
  bin_rows(c, 0, P.np);
  const int* patch = c.pscratch;
  for (int p = 0; p < P.np; ++p) {
    const int q = patch[p];
    if (q >= 0) {
      ++local[size_t(q)];
      if (second(c, p)) ++local[size_t(npatch) + 1 + size_t(q)];
    }
    if (!new_window && rank_of(q) != rank_) ++local[size_t(npatch)];
  }
  counts_.resize(size_t(ncount));
  check(MPI_Allreduce(local.data(), counts_.data(), ncount, MPI_INT, MPI_SUM, comm_), "counts");
  bytes_sent_ += double(ncount) * sizeof(int);
  auto shares = [&]() {
    long most = 0, all = 0;
    for (int u = 0; u < size_; ++u) {
      long n = 0;
      for (int q = first_[size_t(u)]; q < first_[size_t(u) + 1]; ++q) n += counts_[size_t(q)];
      most = std::max(most, n);
      all += n;
    }
    return all > 0 ? double(most) * size_ / double(all) : 1.0;
  };
  bool redrawn = false;
  if (new_window) {
    partition(sim, draw(npatch));
    redrawn = true;
  }
  imbalance_ = shares();
  // The ranks' runs redrawn from the counts that every rank now holds, when the largest
  // share has drifted past rebalance_above_ of the mean and the rule draws other runs (the
  // bits do not depend on them).
  if (imbalance_ > rebalance_above_) {
    std::vector<int> first = draw(npatch);
    if (first != first_) {
      // USF contact reads the last step's contact marks at the nodes its particles read,
      // which after the redraw include nodes this rank did not assemble: every node's from
      // its old owner first.
      if (contact_ && c.scheme == SCHEME_USF) share_owned_nodes(c, c.gnormal, 3);
      partition(sim, std::move(first));
      imbalance_ = shares();
      ++rebalances_;
      redrawn = true;
    }
  }
  for (int p = 0; p < P.np; ++p) dest_[size_t(p)] = rank_of(patch[p]);
  if (counts_[size_t(npatch)] == 0 && !redrawn) return;  // nobody moves
  // Rows to each rank, then the rows from each rank.
  std::vector<int> nsend(static_cast<size_t>(size_), 0), nrecv(static_cast<size_t>(size_), 0);
  for (int p = 0; p < P.np; ++p)
    if (dest_[size_t(p)] != rank_) ++nsend[size_t(dest_[size_t(p)])];
  check(MPI_Alltoall(nsend.data(), 1, MPI_INT, nrecv.data(), 1, MPI_INT, comm_), "counts of moving particles");
  const size_t rb = row_bytes(P);
  std::vector<int> sbytes(static_cast<size_t>(size_)), rbytes(static_cast<size_t>(size_)), sdisp(size_t(size_) + 1, 0), rdisp(size_t(size_) + 1, 0);
  for (int u = 0; u < size_; ++u) {
    sbytes[size_t(u)] = int(size_t(nsend[size_t(u)]) * rb);
    rbytes[size_t(u)] = int(size_t(nrecv[size_t(u)]) * rb);
    sdisp[size_t(u) + 1] = sdisp[size_t(u)] + sbytes[size_t(u)];
    rdisp[size_t(u) + 1] = rdisp[size_t(u)] + rbytes[size_t(u)];
  }
  std::vector<char> out(size_t(sdisp[size_t(size_)])), in(size_t(rdisp[size_t(size_)]));
  {
    std::vector<int> at(sdisp.begin(), sdisp.end() - 1);
    for (int p = 0; p < P.np; ++p) {
      const int d = dest_[size_t(p)];
      if (d == rank_) continue;
      pack_row(P, p, gidx_[size_t(p)], out.data() + at[size_t(d)]);
      at[size_t(d)] += int(rb);
    }
  }
  bytes_sent_ += double(out.size()) + double(size_) * sizeof(int);
  check(MPI_Alltoallv(out.data(), sbytes.data(), sdisp.data(), MPI_BYTE, in.data(), rbytes.data(), rdisp.data(),
                      MPI_BYTE, comm_),
        "moving particles");
  // The rows move in O(movers): a leaving row's place is taken by the last staying row,
  // arrivals are appended, and perm_ (the rows in ascending storage index, which the bin
  // and energy stages follow through StepContext::order) is updated in place of the arrays.
  const std::vector<ParticleField> f = particle_fields(P);
  auto for_arrays = [&](auto&& fn) {  // fn(array, values per row), over every array of the run
    for (int k : fields_) {
      const ParticleField& fk = f[size_t(k)];
      if (fk.d) fn(*fk.d, size_t(fk.ncomp));
      else fn(*fk.i, size_t(fk.ncomp));
    }
  };
  const int n0 = P.np;
  newidx_.resize(size_t(n0));  // each old row's new index, -1 when it left
  int n = n0, i = 0;
  for (;;) {
    while (n > 0 && dest_[size_t(n) - 1] != rank_) newidx_[size_t(--n)] = -1;  // leaving rows at the end
    while (i < n && dest_[size_t(i)] == rank_) {
      newidx_[size_t(i)] = i;
      ++i;
    }
    if (i >= n) break;
    // Row i leaves, row n - 1 stays (i < n - 1): it moves to i, with its binning.
    for_arrays([&](auto& vec, size_t nc) {
      std::memcpy(vec.data() + nc * size_t(i), vec.data() + nc * (size_t(n) - 1), nc * sizeof(vec[0]));
    });
    for (int a = 0; a < 3; ++a) c.lx[3 * size_t(i) + size_t(a)] = c.lx[3 * (size_t(n) - 1) + size_t(a)];
    c.cell[i] = c.cell[n - 1];
    c.pscratch[i] = c.pscratch[n - 1];
    newidx_[size_t(i)] = -1;
    newidx_[size_t(n) - 1] = i;
    gidx_[size_t(i)] = gidx_[size_t(n) - 1];
    dest_[size_t(i)] = rank_;  // row i now holds a staying particle
    --n;
    ++i;
  }
  const int nin = int(in.size() / rb), total = n + nin;
  {
    size_t offset = sizeof(int);  // of the array's values in an arriving row
    for_arrays([&](auto& vec, size_t nc) {
      const size_t w = sizeof(vec[0]);
      vec.resize(nc * size_t(total));
      for (int j = 0; j < nin; ++j)
        std::memcpy(vec.data() + nc * size_t(n + j), in.data() + size_t(j) * rb + offset, nc * w);
      offset += nc * w;
    });
  }
  gidx_.resize(size_t(total));
  std::vector<int> arrived(static_cast<size_t>(nin));
  for (int j = 0; j < nin; ++j) {
    std::memcpy(&gidx_[size_t(n + j)], in.data() + size_t(j) * rb, sizeof(int));
    arrived[size_t(j)] = n + j;
  }
  auto by_storage = [&](int a, int b) { return gidx_[size_t(a)] < gidx_[size_t(b)]; };
  std::sort(arrived.begin(), arrived.end(), by_storage);
  size_t kept = 0;  // perm_ without the leaving rows, in the rows' new indices (still ascending)
  for (int p : perm_)
    if (newidx_[size_t(p)] >= 0) perm_[kept++] = newidx_[size_t(p)];
  perm_.resize(kept);
  perm_next_.resize(size_t(total));
  std::merge(perm_.begin(), perm_.end(), arrived.begin(), arrived.end(), perm_next_.begin(), by_storage);
  perm_.swap(perm_next_);
  P.np = total;
  sim.ctx.order = perm_.data();  // before the rebinding, which copies it into component 2's context
  sim.particles_changed();
  bin_rows(sim.ctx, n, total);  // the arrivals' binning
}

void MpiRanks::add_ghost_slots(Simulation& sim) {
  const int lo = first_[size_t(rank_)], hi = first_[size_t(rank_) + 1];
  for (StepContext* c : {&sim.ctx, contact_ ? &sim.ctx2 : nullptr}) {
    if (!c) continue;
    // This rank's particles (of the context's component) must be exactly those binned
    // into its patches.
    long mine = 0;
    for (int q = lo; q < hi; ++q) mine += count(q, c->only_comp);
    if (c->patch_start[c->npatch] != mine || c->patch_start[lo] != 0 || c->patch_start[hi] != mine)
      throw std::logic_error("ranks: a particle is binned into another rank's patch");
    for (const Neighbour& n : neighbours_)
      for (int q : n.recv)
        if (count(q, c->only_comp) > 0) c->patch_slot[q] = c->nslot++;
  }
  // The patch statistics of the whole run (with contact, component 1's, as on one rank).
  const StepContext& c = sim.ctx;
  std::vector<int> start(size_t(c.npatch) + 1, 0);
  for (int q = 0; q < c.npatch; ++q) start[size_t(q) + 1] = start[size_t(q)] + count(q, c.only_comp);
  sim.stats = patch_stats(sim.grid, start.data());
}

void MpiRanks::exchange_buffers(const StepContext* c, int first, int nfield) {
  const size_t pn = size_t(patch_nodes(c));
  const int comp = c->only_comp;
  // The values of the non-empty ones among patches qs (node lists start).
  auto values = [&](const std::vector<int>& qs, const std::vector<int>& start) {
    size_t n = 0;
    for (size_t i = 0; i < qs.size(); ++i)
      if (count(qs[i], comp) > 0) n += size_t(start[i + 1] - start[i]);
    return n * size_t(nfield);
  };
  auto buffer = [&](int q) { return c->patch_buf + size_t(c->patch_slot[q]) * pn * kNodeFields + size_t(first); };
  std::vector<MPI_Request> req;
  req.reserve(2 * neighbours_.size());
  for (Neighbour& n : neighbours_) {
    n.in.resize(values(n.recv, n.recv_start));
    if (!n.in.empty()) {
      req.emplace_back();
      check(MPI_Irecv(n.in.data(), int(n.in.size()), MPI_DOUBLE, n.rank, 1, comm_, &req.back()), "receive");
    }
  }
  for (Neighbour& n : neighbours_) {
    n.out.resize(values(n.send, n.send_start));
    double* o = n.out.data();
    for (size_t i = 0; i < n.send.size(); ++i) {
      if (count(n.send[i], comp) == 0) continue;
      const double* b = buffer(n.send[i]);
      for (int k = n.send_start[i]; k < n.send_start[i + 1]; ++k)
        for (int f = 0; f < nfield; ++f) *o++ = b[size_t(n.send_nodes[size_t(k)]) * kNodeFields + size_t(f)];
    }
    bytes_sent_ += double(n.out.size()) * sizeof(double);
    if (!n.out.empty()) {
      req.emplace_back();
      check(MPI_Isend(n.out.data(), int(n.out.size()), MPI_DOUBLE, n.rank, 1, comm_, &req.back()), "send");
    }
  }
  check(MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE), "buffer exchange");
  for (Neighbour& n : neighbours_) {
    const double* in = n.in.data();
    for (size_t i = 0; i < n.recv.size(); ++i) {
      if (count(n.recv[i], comp) == 0) continue;
      double* b = buffer(n.recv[i]);
      for (int k = n.recv_start[i]; k < n.recv_start[i + 1]; ++k)
        for (int f = 0; f < nfield; ++f) b[size_t(n.recv_nodes[size_t(k)]) * kNodeFields + size_t(f)] = *in++;
    }
  }
}

void MpiRanks::exchange_columns(double* cols, int nf, bool outside) {
  // The energy stage's columns (outside: one per patch, then the particles outside the
  // grid, the last rank's) sum particles, so a patch without particles (counts_, the step's
  // binning) has a column of zeros on every rank: only the others travel. The contact
  // stage's sum nodes, which patches without particles have too: all of them travel.
  auto travels = [&](int q) { return !outside || count(q, 0) > 0; };
  std::vector<int> cnt(static_cast<size_t>(size_)), disp(static_cast<size_t>(size_));
  int total = 0;
  for (int u = 0; u < size_; ++u) {
    int n = outside && u == size_ - 1 ? 1 : 0;
    for (int q = first_[size_t(u)]; q < first_[size_t(u) + 1]; ++q) n += travels(q);
    cnt[size_t(u)] = nf * n;
    disp[size_t(u)] = total;
    total += nf * n;
  }
  std::vector<double> all(static_cast<size_t>(total));
  // Rank u's columns in patch order, then (the last rank) the outside column; pack (true)
  // copies them from cols into all, unpack (false) back.
  auto copy = [&](int u, bool pack) {
    double* a = all.data() + disp[size_t(u)];
    auto one = [&](int q) {
      double* col = cols + size_t(nf) * size_t(q);
      if (pack) std::copy(col, col + nf, a);
      else std::copy(a, a + nf, col);
      a += nf;
    };
    for (int q = first_[size_t(u)]; q < first_[size_t(u) + 1]; ++q)
      if (travels(q)) one(q);
    if (outside && u == size_ - 1) one(int(owner_.size()));
  };
  copy(rank_, true);
  bytes_sent_ += double(cnt[size_t(rank_)]) * sizeof(double);
  check(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, all.data(), cnt.data(), disp.data(), MPI_DOUBLE, comm_),
        "per-patch partials");
  for (int u = 0; u < size_; ++u)
    if (u != rank_) copy(u, false);
}

void MpiRanks::gather(const Particles& local_const, Particles& all) {
  Particles& local = const_cast<Particles&>(local_const);  // particle_fields takes a mutable set
  const size_t rb = row_bytes(local);
  std::vector<char> out(size_t(local.np) * rb);
  for (int p = 0; p < local.np; ++p) pack_row(local, p, gidx_[size_t(p)], out.data() + size_t(p) * rb);
  std::vector<int> bytes(static_cast<size_t>(size_)), disp(size_t(size_) + 1, 0);
  const int mine = int(out.size());
  check(MPI_Gather(&mine, 1, MPI_INT, bytes.data(), 1, MPI_INT, 0, comm_), "gather");
  for (int u = 0; u < size_; ++u) disp[size_t(u) + 1] = disp[size_t(u)] + bytes[size_t(u)];
  std::vector<char> in(root() ? size_t(disp[size_t(size_)]) : 0);
  check(MPI_Gatherv(out.data(), mine, MPI_BYTE, in.data(), bytes.data(), disp.data(), MPI_BYTE, 0, comm_), "gather");
  all = Particles();
  if (!root()) return;
  const int n = np_global_;
  if (int(in.size() / rb) != n) throw std::logic_error("ranks: particles lost");
  all.np = n;
  std::vector<ParticleField> fa = particle_fields(all);
  size_t offset = sizeof(int);
  for (int k : fields_) {
    ParticleField& fk = fa[size_t(k)];
    const size_t nc = size_t(fk.ncomp);
    auto place = [&](auto& vec) {
      using V = typename std::decay_t<decltype(vec)>::value_type;
      vec.assign(nc * size_t(n), V());
      for (int j = 0; j < n; ++j) {
        int g;
        std::memcpy(&g, in.data() + size_t(j) * rb, sizeof(int));
        std::memcpy(vec.data() + nc * size_t(g), in.data() + size_t(j) * rb + offset, nc * sizeof(V));
      }
      offset += nc * sizeof(V);
    };
    if (fk.d) place(*fk.d);
    else place(*fk.i);
  }
}

void MpiRanks::share_owned_nodes(const StepContext& c, double* field, int ncomp) {
  // Rank u's part: the nodes owned by its patches, patch after patch, each in k, j, i order.
  auto for_nodes_of = [&](int u, auto&& f) {
    for (int q = first_[size_t(u)]; q < first_[size_t(u) + 1]; ++q) for_owned_nodes(&c, owned_nodes(&c, q), f);
  };
  std::vector<int> cnt(static_cast<size_t>(size_)), disp(size_t(size_) + 1, 0);
  for (int u = 0; u < size_; ++u) {
    int n = 0;
    for_nodes_of(u, [&](int) { ++n; });
    cnt[size_t(u)] = n * ncomp;
    disp[size_t(u) + 1] = disp[size_t(u)] + cnt[size_t(u)];
  }
  std::vector<double> all(size_t(disp[size_t(size_)]));
  double* o = all.data() + disp[size_t(rank_)];
  for_nodes_of(rank_, [&](int n) {
    for (int a = 0; a < ncomp; ++a) *o++ = field[size_t(ncomp) * size_t(n) + size_t(a)];
  });
  bytes_sent_ += double(cnt[size_t(rank_)]) * sizeof(double);
  check(MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, all.data(), cnt.data(), disp.data(), MPI_DOUBLE, comm_),
        "node values");
  const double* in = all.data();
  for (int u = 0; u < size_; ++u)
    for_nodes_of(u, [&](int n) {
      for (int a = 0; a < ncomp; ++a) field[size_t(ncomp) * size_t(n) + size_t(a)] = *in++;
    });
}

// Launched by mpirun (Open MPI's or another's environment): the caller starts MPI only then,
// so that a plain `mpm3d deck` never initialises it.
bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

}  // namespace

int run_main_mpi(int argc, char** argv) {
  if (!launched_by_mpirun()) return run_main(argc, argv, nullptr);
  int provided = 0;
  // The stages call MPI between their parallel regions, from the master thread only.
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    std::cerr << "mpm3d: MPI_Init_thread failed\n";
    return 1;
  }
  int rc = 0;
  {
    MpiRanks ranks(MPI_COMM_WORLD);
    rc = run_main(argc, argv, ranks.size() > 1 ? &ranks : nullptr);
    // Every rank returns the same status (deck errors, refusals and health errors are
    // reached by all of them); the root's is the run's.
    check(MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD), "status");
  }
  MPI_Finalize();
  return rc;
}

}  // namespace mpm3d
