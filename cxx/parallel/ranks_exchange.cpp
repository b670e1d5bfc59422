// MpiRanks (mpi_ranks.hpp): what travels during a step: the patch buffers' shared nodes, the
// per-patch columns of the energy and contact stages, owned node values, and the particles
// gathered on the root for output.
#include "core/patch_index.hpp"
#include "parallel/mpi_ranks.hpp"

namespace mpm3d {

void MpiRanks::exchange_buffers(const StepContext* c, int first, int nfield) {
  const size_t pn = size_t(patch_nodes(c));
  const int comp = c->contact.only_comp;
  // The values of the non-empty ones among patches qs (node lists start).
  auto values = [&](const std::vector<int>& qs, const std::vector<int>& start) {
    size_t n = 0;
    for (size_t i = 0; i < qs.size(); ++i)
      if (count(qs[i], comp) > 0) n += size_t(start[i + 1] - start[i]);
    return n * size_t(nfield);
  };
  auto buffer = [&](int q) { return c->patch.patch_buf + size_t(c->patch.patch_slot[q]) * pn * kNodeFields + size_t(first); };
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

}  // namespace mpm3d
