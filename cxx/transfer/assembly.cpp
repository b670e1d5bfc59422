// The canonical assembly of the patch buffers into the node arrays (transfer_common.hpp
// assemble; docs/DESIGN.md section 4), for buffers without a halo (the trilinear family)
// and with one (the 27-node stencils, sgmp). The P2G of every family, the G2P remap and
// the contact's mass gradients end with it.
#include <algorithm>
#include <cstddef>
#include <stdexcept>

#include "core/step_state.hpp"
#include "transfer/transfer_common.hpp"

namespace mpm3d {
namespace {

// The trilinear assembly (no halo): owner patch q gathers each of its nodes from its own
// buffer and those of its seven lower neighbours. The field range is a compile-time
// constant, so the per-node loops unroll.
template <int first, int count>
void assemble_fields(const StepContext* c, double* dst_mass, double* dst_mom, double* dst_force) {
  const int P = c->patch.patch_cells, Q = P + 1;
  const int npd0 = c->patch.npd[0], npd1 = c->patch.npd[1], npd2 = c->patch.npd[2];
  const int pn = Q * Q * Q;
  for_patches(c, [&](int q) {
    if (patch_at_rest(c, q)) return;  // its nodes keep the sums of the step before
    const int qx = q % npd0, qy = (q / npd0) % npd1, qz = q / (npd0 * npd1);
    // Slots of the patch and its lower neighbours: nb[cz][cy][cx], c = 0 lower, 1 self.
    const double* nb[2][2][2];
    bool any = false;
    for (int cz = 0; cz < 2; ++cz)
      for (int cy = 0; cy < 2; ++cy)
        for (int cx = 0; cx < 2; ++cx) {
          const int px = qx - 1 + cx, py = qy - 1 + cy, pz = qz - 1 + cz;
          const double* b = nullptr;
          if (px >= 0 && py >= 0 && pz >= 0) {
            const int slot = c->patch.patch_slot[px + npd0 * (py + npd1 * pz)];
            if (slot >= 0) b = c->patch.patch_buf + size_t(slot) * size_t(pn) * kNodeFields;
          }
          nb[cz][cy][cx] = b;
          any = any || b;
        }
    if (!any) return;  // inactive: no stage reads these nodes
    const int i0 = qx * P, j0 = qy * P, k0 = qz * P;
    const int i1 = qx == npd0 - 1 ? c->grid.nn[0] : i0 + P;
    const int j1 = qy == npd1 - 1 ? c->grid.nn[1] : j0 + P;
    const int k1 = qz == npd2 - 1 ? c->grid.nn[2] : k0 + P;
    for (int k = k0; k < k1; ++k)
      for (int j = j0; j < j1; ++j) {
        // Row pointers of the contributing buffers, in ascending patch order: (cz, cy)
        // ascending, and within each the lower x patch (cx = 0) before the own one.
        const double* row[8];
        int cxs[8], nrow = 0;
        const int czlo = (k == k0 && qz > 0) ? 0 : 1;
        const int cylo = (j == j0 && qy > 0) ? 0 : 1;
        for (int cz = czlo; cz < 2; ++cz)
          for (int cy = cylo; cy < 2; ++cy)
            for (int cx = 0; cx < 2; ++cx) {
              const double* b = nb[cz][cy][cx];
              if (!b) continue;
              const int lj = j - (qy - 1 + cy) * P, lk = k - (qz - 1 + cz) * P;
              // Buffer node of x index i is at (i - (qx - 1 + cx) P) + Q (lj + Q lk).
              row[nrow] = b + std::ptrdiff_t(Q * (lj + Q * lk) - (qx - 1 + cx) * P) * kNodeFields;
              cxs[nrow++] = cx;
            }
        const int nbase = c->grid.nn[0] * (j + c->grid.nn[1] * k);
        for (int i = i0; i < i1; ++i) {
          const bool lower_x = (i == i0 && qx > 0);
          double sum[kNodeFields] = {0, 0, 0, 0, 0, 0, 0};
          for (int r = 0; r < nrow; ++r) {
            if (cxs[r] == 0 && !lower_x) continue;
            const double* v = row[r] + size_t(i) * kNodeFields + first;
            for (int f = 0; f < count; ++f) sum[f] += v[f];
          }
          store_node_fields(first, count, sum, i + nbase, dst_mass, dst_mom, dst_force);
        }
      }
  });
}

// Patches whose buffers (halo H) hold node n along one axis: [lo, hi].
inline void patch_range(int n, int P, int H, int npd, int& lo, int& hi) {
  const int t = n - P - H;
  lo = t <= 0 ? 0 : (t + P - 1) / P;
  hi = (n + H) / P;
  if (hi > npd - 1) hi = npd - 1;
}

// The assembly for buffers with a halo (27-node stencils, sgmp): the owner patch of each node
// gathers it from every non-empty patch whose buffer holds it, in ascending patch index.
// The owned block is summed one contributing patch at a time (the patch's whole overlap at
// once, patches in ascending index) straight into the node arrays, set to +0.0 first: every
// node gets the same additions in the same order as a node-by-node gather, at a fraction of
// its index arithmetic.
template <int first, int count>
void assemble_wide(const StepContext* c, double* dst_mass, double* dst_mom, double* dst_force, const int* boxes) {
  const int P = c->patch.patch_cells, H = c->patch.patch_halo, Q = P + 1 + 2 * H;
  const size_t pn = size_t(Q) * size_t(Q) * size_t(Q);
  const int nn0 = c->grid.nn[0], nn1 = c->grid.nn[1];
  auto field = [&](int f, size_t n) -> double& { return node_field(f, n, dst_mass, dst_mom, dst_force); };
  for_patches(c, [&](int q) {
    if (patch_at_rest(c, q)) return;  // its nodes keep the sums of the step before
    const OwnedNodes o = owned_nodes(c, q);
    if (!o.active) return;
    for (int k = o.lo[2]; k < o.hi[2]; ++k)
      for (int j = o.lo[1]; j < o.hi[1]; ++j) {
        const size_t row = size_t(nn0) * (size_t(j) + size_t(nn1) * size_t(k));
        for (int i = o.lo[0]; i < o.hi[0]; ++i)
          for (int f = first; f < first + count; ++f) field(f, row + size_t(i)) = 0.0;
      }
    int rlo[3], rhi[3];
    for (int a = 0; a < 3; ++a) {
      int l0, h0, l1, h1;
      patch_range(o.lo[a], P, H, c->patch.npd[a], l0, h0);
      patch_range(o.hi[a] - 1, P, H, c->patch.npd[a], l1, h1);
      rlo[a] = l0;
      rhi[a] = h1;
    }
    for (int rz = rlo[2]; rz <= rhi[2]; ++rz)
      for (int ry = rlo[1]; ry <= rhi[1]; ++ry)
        for (int rx = rlo[0]; rx <= rhi[0]; ++rx) {
          const int slot = c->patch.patch_slot[rx + c->patch.npd[0] * (ry + c->patch.npd[1] * rz)];
          if (slot < 0) continue;
          const int r3[3] = {rx, ry, rz};
          int b0[3], b1[3];  // the overlap of the owned block and the buffer's (written) nodes
          const int* box = boxes ? boxes + 6 * size_t(slot) : nullptr;
          bool empty = false;
          for (int a = 0; a < 3; ++a) {
            const int first_node = r3[a] * P - H;
            b0[a] = std::max(o.lo[a], box ? first_node + box[a] : first_node);
            b1[a] = std::min(o.hi[a], box ? first_node + box[3 + a] : r3[a] * P + P + H + 1);
            empty = empty || b0[a] >= b1[a];
          }
          if (empty) continue;
          const double* buf = c->patch.patch_buf + size_t(slot) * pn * kNodeFields;
          for (int k = b0[2]; k < b1[2]; ++k)
            for (int j = b0[1]; j < b1[1]; ++j) {
              const int ln0 = (b0[0] - rx * P + H) + Q * ((j - ry * P + H) + Q * (k - rz * P + H));
              const size_t n0 = size_t(nn0) * (size_t(j) + size_t(nn1) * size_t(k)) + size_t(b0[0]);
              for (int i = 0; i < b1[0] - b0[0]; ++i) {
                const double* v = buf + size_t(ln0 + i) * kNodeFields;
                for (int f = first; f < first + count; ++f) field(f, n0 + size_t(i)) += v[f];
              }
            }
        }
  });
}

}  // namespace

void assemble(const StepContext* c, int first, int count, double* dst_mass, double* dst_mom,
              double* dst_force, const int* boxes) {
  if (c->ranks.exchange) c->ranks.exchange(c, EXCHANGE_BUFFERS, first, count);  // ghost patches' buffers
  const bool wide = c->patch.patch_halo > 0;
  if (wide && first == 0 && count == 7)
    assemble_wide<0, 7>(c, dst_mass, dst_mom, dst_force, boxes);
  else if (wide && first == 0 && count == 4)
    assemble_wide<0, 4>(c, dst_mass, dst_mom, dst_force, boxes);
  else if (wide && first == 1 && count == 3)
    assemble_wide<1, 3>(c, dst_mass, dst_mom, dst_force, boxes);
  else if (wide && first == 4 && count == 3)
    assemble_wide<4, 3>(c, dst_mass, dst_mom, dst_force, boxes);
  else if (wide)
    throw std::logic_error("assemble: unexpected field range");
  else if (first == 0 && count == 7)
    assemble_fields<0, 7>(c, dst_mass, dst_mom, dst_force);
  else if (first == 0 && count == 4)
    assemble_fields<0, 4>(c, dst_mass, dst_mom, dst_force);
  else if (first == 1 && count == 3)
    assemble_fields<1, 3>(c, dst_mass, dst_mom, dst_force);
  else if (first == 4 && count == 3)
    assemble_fields<4, 3>(c, dst_mass, dst_mom, dst_force);
  else
    throw std::logic_error("assemble: unexpected field range");
}

}  // namespace mpm3d
