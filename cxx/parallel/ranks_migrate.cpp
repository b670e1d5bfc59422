// MpiRanks (mpi_ranks.hpp): the particles placed on their ranks at the start (distribute), moved
// between ranks before a step (migrate), and the ghost patches' buffer slots.
#include "core/patch_index.hpp"
#include "parallel/mpi_ranks.hpp"

namespace mpm3d {

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
  contact_ = c.contact.other != nullptr;
  counts_.assign(size_t(c.patch.npatch) + 1 + (contact_ ? size_t(c.patch.npatch) : 0), 0);
  bin_rows(c, 0, P.np);  // every particle's patch, in pscratch
  const int* patch = c.patch.pscratch;
  for (int p = 0; p < P.np; ++p) {
    const int q = patch[p];
    if (q < 0) continue;
    ++counts_[size_t(q)];
    if (second(c, p)) ++counts_[size_t(c.patch.npatch) + 1 + size_t(q)];
  }
  partition(sim, draw(c.patch.npatch));
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
  sim.ctx.ranks.exchange = &MpiRanks::exchange;
  sim.ctx.ranks.exchange_data = this;
  sim.ctx.ranks.order = perm_.data();
  sim.ctx.ranks.prebinned = 1;
  sim.particles_changed();
  bin_rows(sim.ctx, 0, P.np);
}

void MpiRanks::migrate(Simulation& sim) {
  Particles& P = sim.model.particles;
  const StepContext& c = sim.ctx;
  const int npatch = c.patch.npatch;
  const int ncount = npatch + 1 + (contact_ ? npatch : 0);
  std::vector<int> local(size_t(ncount), 0);
  dest_.resize(size_t(P.np));
  auto rank_of = [&](int q) { return q >= 0 ? owner_[size_t(q)] : size_ - 1; };
  // A new grid window (the adaptive grid, on every rank alike) has other patches: the
  // ranks' runs are drawn for it below, and the particles counted as moving then.
  const bool new_window = !same_window(c);
  // The bin stage's binning, done here (prebinned): it tells which particles move.
  bin_rows(c, 0, P.np);
  const int* patch = c.patch.pscratch;
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
      if (contact_ && c.method.scheme == SCHEME_USF) share_owned_nodes(c, c.contact.gnormal, 3);
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
    for (int a = 0; a < 3; ++a) c.part.lx[3 * size_t(i) + size_t(a)] = c.part.lx[3 * (size_t(n) - 1) + size_t(a)];
    c.part.cell[i] = c.part.cell[n - 1];
    c.patch.pscratch[i] = c.patch.pscratch[n - 1];
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
  sim.ctx.ranks.order = perm_.data();  // before the rebinding, which copies it into component 2's context
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
    for (int q = lo; q < hi; ++q) mine += count(q, c->contact.only_comp);
    if (c->patch.patch_start[c->patch.npatch] != mine || c->patch.patch_start[lo] != 0 || c->patch.patch_start[hi] != mine)
      throw std::logic_error("ranks: a particle is binned into another rank's patch");
    for (const Neighbour& n : neighbours_)
      for (int q : n.recv)
        if (count(q, c->contact.only_comp) > 0) c->patch.patch_slot[q] = c->patch.nslot++;
  }
  // The patch statistics of the whole run (with contact, of both components, as on one rank).
  const StepContext& c = sim.ctx;
  std::vector<int> start(size_t(c.patch.npatch) + 1, 0);
  for (int q = 0; q < c.patch.npatch; ++q) start[size_t(q) + 1] = start[size_t(q)] + count(q, 0);
  sim.stats = patch_stats(sim.grid, start.data());
}

}  // namespace mpm3d
