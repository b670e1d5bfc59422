// MpiRanks (mpi_ranks.hpp): the ranks' patch runs, with equal shares of the particles, and per
// neighbouring rank the patches and buffer nodes that travel between them.
#include "core/patch_index.hpp"
#include "parallel/mpi_ranks.hpp"
#include "transfer/transfer_lanes.hpp"

namespace mpm3d {

// The bin stage's own kernel (transfer_lanes.hpp, bin_range), so both always agree.
void MpiRanks::bin_rows(const StepContext& c, int lo, int hi) {
  StepContext all = c;
  all.contact.only_comp = 0;  // the patches of both contact components
  if (lanes_use_avx2()) bin_range_avx2(&all, lo, hi, all.patch.pscratch);
  else bin_range<VectorLane<kLanes>>(&all, lo, hi, all.patch.pscratch);
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
  const int npatch = c.patch.npatch;
  first_ = std::move(first);
  for (int a = 0; a < 3; ++a) {
    window_[a] = c.grid.cell_off[a];
    window_[3 + a] = c.grid.nc[a];
  }
  owner_.assign(size_t(npatch), 0);
  for (int u = 0; u < size_; ++u)
    for (int q = first_[size_t(u)]; q < first_[size_t(u) + 1]; ++q) owner_[size_t(q)] = u;
  std::vector<std::vector<int>> send(static_cast<size_t>(size_)), recv(static_cast<size_t>(size_));
  const int n0 = c.patch.npd[0], n1 = c.patch.npd[1], n2 = c.patch.npd[2];
  // The patches whose buffers add into a node this rank's particles read, along one axis:
  // a particle of patch q reads nodes q P - H .. (q + 1) P + H (H the halo of the wide
  // stencils), and patch r's buffer holds nodes r P - H .. (r + 1) P + H, so r lies within
  // q -+ (1 + floor(2 H / P)): one patch each way for the trilinear stencil, and for the
  // 27-node ones when P >= 3.
  const int R = 1 + (2 * c.patch.patch_halo) / c.patch.patch_cells;
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
  const int P = c.patch.patch_cells, H = c.patch.patch_halo, Q = P + 1 + 2 * H, R = 1 + (2 * H) / P;
  const int n0 = c.patch.npd[0], n1 = c.patch.npd[1], n2 = c.patch.npd[2];
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

}  // namespace mpm3d
