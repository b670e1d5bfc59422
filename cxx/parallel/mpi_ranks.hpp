// MpiRanks, the ranks of a distributed run over MPI (cxx/solver/ranks.hpp): the class, its
// collectives and the state its files share. Its work is in three files by concern:
// ranks_partition.cpp (the ranks' patch runs and the nodes their neighbours need),
// ranks_migrate.cpp (particles placed on and moved between ranks) and ranks_exchange.cpp
// (patch buffers, per-patch columns, node values and the gather of the particles);
// app/mpi_main.cpp starts MPI. Linked into the mpm3d program only when CMake finds MPI.
//
// Ownership: rank r owns the patches [first_[r], first_[r+1]) (runs of consecutive patch
// indices with equal shares of the particles, the rule OpenMP threads use inside a rank),
// the particles inside them, and those outside the grid if it is the last rank. Every
// rank keeps the whole grid window's node arrays; it assembles the nodes its particles read
// from its own patch buffers and copies of its neighbours' (ghost patches), of which only
// those nodes travel.
#pragma once
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

#include "solver/ranks.hpp"
#include "solver/simulation.hpp"

namespace mpm3d {

inline void check(int rc, const char* what) {
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
    auto* self = static_cast<MpiRanks*>(c->ranks.exchange_data);
    if (kind == EXCHANGE_BUFFERS) self->exchange_buffers(c, first, count);
    else if (kind == EXCHANGE_PARTIALS) self->exchange_columns(c->out.partials, kReduceFields, true);
    else self->exchange_columns(c->contact.cpartials, kContactFields, false);
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
  bool second(const StepContext& c, int p) const { return contact_ && c.contact.body_comp[c.part.body[p]] == 2; }
  bool same_window(const StepContext& c) const {
    for (int a = 0; a < 3; ++a)
      if (window_[a] != c.grid.cell_off[a] || window_[3 + a] != c.grid.nc[a]) return false;
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

}  // namespace mpm3d
