// The grid update: the integrate stage (nodal momenta from the forces), the boundary
// conditions of the box faces, and the multi-velocity contact and recontact stages.
#include <cmath>
#include <cstddef>

#include "stages/update_step.hpp"
#include "transfer/transfer.hpp"
#include "transfer/transfer_common.hpp"

namespace mpm3d {

// Faces holding more nodes than this are cleared by a team (a one-cell-thick deck's faces
// hold every node); smaller ones on the calling thread, where a team's fork and join cost
// more than it saves (docs/PERFORMANCE.md).
constexpr long kParallelBcNodes = 16384;

// The nodes any particle's stencil reaches, [lo, hi) per axis: those of the buffers of the
// non-empty patches (halo included). Every other node is in an inactive patch, read by no
// stage, or assembled as +0.0 in every field and left so by the grid update: the boundary
// conditions have nothing to change there, and an empty part of the grid costs them
// nothing. A distributed run keeps the whole grid.
static void reached_nodes(const StepContext* c, int lo[3], int hi[3]) {
  for (int a = 0; a < 3; ++a) lo[a] = 0, hi[a] = c->grid.nn[a];
  if (c->ranks.exchange) return;
  int plo[3] = {c->patch.npd[0], c->patch.npd[1], c->patch.npd[2]}, phi[3] = {-1, -1, -1};
  const int* slot = c->patch.patch_slot;
  for (int qz = 0; qz < c->patch.npd[2]; ++qz)
    for (int qy = 0; qy < c->patch.npd[1]; ++qy, slot += c->patch.npd[0]) {
      int xlo = -1, xhi = -1;  // the row's first and last non-empty patch
      for (int qx = 0; qx < c->patch.npd[0]; ++qx)
        if (slot[qx] >= 0) {
          if (xlo < 0) xlo = qx;
          xhi = qx;
        }
      if (xhi < 0) continue;
      const int q3lo[3] = {xlo, qy, qz}, q3hi[3] = {xhi, qy, qz};
      for (int a = 0; a < 3; ++a) {
        plo[a] = q3lo[a] < plo[a] ? q3lo[a] : plo[a];
        phi[a] = q3hi[a] > phi[a] ? q3hi[a] : phi[a];
      }
    }
  if (phi[0] < 0) return;  // no particle: the whole grid
  const int P = c->patch.patch_cells, H = c->patch.patch_halo;
  for (int a = 0; a < 3; ++a) {
    const int l = plo[a] * P - H, h = phi[a] * P + P + H + 1;
    lo[a] = l > 0 ? l : 0;
    hi[a] = h < c->grid.nn[a] ? h : c->grid.nn[a];
  }
}

// Components mask of a node run cleared in one pass (bit d: component d), one instance per
// mask so that adjacent components go out as one store.
template <unsigned kMask>
static void clear_run(double* row, long i0, long i1) {
  for (long i = i0; i < i1; ++i) {
    double* v = row + 3 * i;
    if (kMask & 1u) v[0] = 0.0;
    if (kMask & 2u) v[1] = 0.0;
    if (kMask & 4u) v[2] = 0.0;
  }
}

static void clear_run(double* row, long i0, long i1, unsigned m) {
  switch (m) {
    case 1: clear_run<1>(row, i0, i1); break;
    case 2: clear_run<2>(row, i0, i1); break;
    case 3: clear_run<3>(row, i0, i1); break;
    case 4: clear_run<4>(row, i0, i1); break;
    case 5: clear_run<5>(row, i0, i1); break;
    case 6: clear_run<6>(row, i0, i1); break;
    case 7: clear_run<7>(row, i0, i1); break;
    default: break;
  }
}

void apply_bc(const StepContext* c, double* a) {
  const int layers = c->grid.fix_layers > 1 ? c->grid.fix_layers : 1;  // 0 (unset) means 1
  int lo[3], hi[3];
  reached_nodes(c, lo, hi);
  unsigned comps[6];  // the components face f holds: all (fixed) or its normal one
  for (int face = 0; face < 6; ++face)
    comps[face] = c->grid.fix[face] == 0 ? 0u : (c->grid.fix[face] == 1 ? 7u : 1u << (face / 2));
  const int n0 = c->grid.nn[0], n1 = c->grid.nn[1], n2 = c->grid.nn[2];
  const int b0 = hi[0] - lo[0], b1 = hi[1] - lo[1];
  const long nodes = long(b0) * b1 * (hi[2] - lo[2]);
  if (nodes <= 0) return;
  long held = 0;  // the nodes of the held faces' planes within the box (a bound: edges twice)
  for (int face = 0; face < 6; ++face) {
    if (c->grid.fix[face] == 0) continue;
    const int axis = face / 2;
    held += layers * (nodes / (hi[axis] - lo[axis]));
  }
  // The box's nodes [first, last) in its node order, as rows along x: each row's y and z
  // faces' components in one pass (clear_run), then its x faces' nodes. Clearing is the
  // same in any order and clearing twice is clearing, so the threads of a team each take
  // one run, with no barrier between the faces.
  auto clear_range = [&](long first, long last) {
    for (long r = first / b0; r * b0 < last; ++r) {
      const int j = lo[1] + int(r % b1), k = lo[2] + int(r / b1);
      unsigned m = 0;  // the y and z faces holding the row
      if (j < layers) m |= comps[2];
      if (j >= n1 - layers) m |= comps[3];
      if (k < layers) m |= comps[4];
      if (k >= n2 - layers) m |= comps[5];
      const long i0 = first > r * b0 ? first - r * b0 : 0;  // within the box's row
      const long i1 = last < (r + 1) * b0 ? last - r * b0 : b0;
      double* row = a + 3 * (lo[0] + long(n0) * (j + long(n1) * k));
      clear_run(row, i0, i1, m);
      for (long l = 0; l < layers; ++l) {  // the x faces' nodes of the row
        const long lx = l - lo[0], hx = n0 - 1 - l - lo[0];
        if (lx >= i0 && lx < i1) clear_run(row + 3 * lx, 0, 1, comps[0]);
        if (hx >= i0 && hx < i1) clear_run(row + 3 * hx, 0, 1, comps[1]);
      }
    }
  };
  const int threads = omp_threads();
  if (threads > 1 && held > kParallelBcNodes) {
    team_region([&] {
      int t, T;
      team_position(t, T);
      clear_range(nodes * t / T, nodes * (t + 1) / T);
    });
    return;
  }
  clear_range(0, nodes);
}

namespace {

// Contact: g_i = sum_p m_p grad N_i(x_p) of the context's particles (the outward normal
// direction of its body at node i) into gnormal, through the force fields (4-6) of the
// patch buffers, which no stage reads after the force assembly; the gradients are the
// deck's shape-function family's (transfer/transfer.hpp).
void scatter_mass_gradient(StepContext* c) {
  const int* boxes = transfer_of(c).mass_gradient(c);
  assemble(c, 4, 3, c->grid.gmass, c->grid.gmom, c->contact.gnormal, boxes);
}

// Multi-velocity contact (Bardenhagen et al. 2000, 2001; Huang et al. 2011) between
// component 1 (this context) and component 2 (c->contact.other). At a node where both components
// have mass above the cut-off:
// - the unit normal n points from component 1 into component 2; it is g1 (normbody 1),
//   -g2 (2) or g1 - g2 (0), normalised, where g_k = sum_p m_p grad N_i(x_p) over the
//   particles of component k points out of body k;
// - q = (m2 p1 - m1 p2)/(m1 + m2) is the momentum component 1 gives up to reach the common
//   velocity; component 1's momentum changes by d = -(q.n n + f t), t = q - q.n n the
//   tangential part, f = 1 (stick) or mu |q.n| / |t| when |t| exceeds mu |q.n| (Coulomb
//   slip), and component 2's by -d.
// Stage `contact` (after both integrates): the nodes where the components approach
// (q.n > 0) are corrected, their forces change by d/dt_int (so that G2P's accelerations
// agree with the corrected momenta), and the unit normal of each corrected node is kept in
// this context's gnormal (zero at the other nodes of the loop), marking the node as in
// contact for this step. The contact force on component 1, the sum of d/dt_int over the
// nodes, goes to result[5..7] and the number of corrected nodes to ncontact: per-patch
// partials (cpartials: force, count; owned nodes in k, j, i order) folded in patch order,
// with several ranks after each rank's columns reached every rank.
// Stage `recontact`: the momenta of the nodes marked in contact are corrected again with
// the kept normals, for either sign of q.n, so that the strain rates see the same normal
// velocity for both bodies at these nodes as the position update did. MUSL runs it after
// both G2P remaps of the step, USF after both P2Gs of the next step (before the stresses;
// the marks of the previous step, which is why with USF the `contact` stage also clears
// the nodes of patches outside its loop). Without it the velocities that the strain rates
// read separate at nodes whose corrected velocities did not, and the stresses of the
// rebounding bodies release more work than the bodies did (the spheres deck gained
// 9-67% of its energy per impact, more with larger steps).
// Both stages apply the boundary conditions again.
// The correction of node n (contact: where the components approach; recontact: where it
// is marked); the contact force on component 1 is added to part. True when corrected.
template <bool kRemap>
inline bool contact_node(StepContext* c, StepContext* c2, int n, double part[3]) {
  const double cutoff = c->grid.mass_cutoff, mu = c->contact.contact_mu;
  // Rule contact=original: the force by the full dt also in the first step (of half dt).
  const double dt_force = c->rules.contact ? c->clock.dt : c->clock.dt_int;
  const int nb = c->contact.contact_normbody;
  const double m1 = c->grid.gmass[n], m2 = c2->grid.gmass[n];
  double* g1 = c->contact.gnormal + 3 * n;
  if (!(m1 > cutoff) || !(m2 > cutoff)) {
    if (!kRemap) g1[0] = g1[1] = g1[2] = 0.0;
    return false;
  }
  double un[3], qv[3];
  if (kRemap) {
    if (g1[0] == 0.0 && g1[1] == 0.0 && g1[2] == 0.0) return false;  // not in contact
    for (int a = 0; a < 3; ++a) un[a] = g1[a];
  } else {
    const double* g2 = c2->contact.gnormal + 3 * n;
    double nv[3];
    for (int a = 0; a < 3; ++a) nv[a] = nb == 1 ? g1[a] : (nb == 2 ? -g2[a] : g1[a] - g2[a]);
    for (int a = 0; a < 3; ++a) g1[a] = 0.0;
    const double len = std::sqrt((nv[0] * nv[0] + nv[1] * nv[1]) + nv[2] * nv[2]);
    if (!(len > 0.0)) return false;
    for (int a = 0; a < 3; ++a) un[a] = nv[a] / len;
  }
  double* p1 = c->grid.gmom + 3 * n;
  double* p2 = c2->grid.gmom + 3 * n;
  const double mt = m1 + m2;
  for (int a = 0; a < 3; ++a) qv[a] = (m2 * p1[a] - m1 * p2[a]) / mt;
  const double qn = (qv[0] * un[0] + qv[1] * un[1]) + qv[2] * un[2];
  if (!kRemap) {
    if (!(qn > 0.0)) return false;
    for (int a = 0; a < 3; ++a) g1[a] = un[a];  // in contact this step
  }
  double t[3];
  for (int a = 0; a < 3; ++a) t[a] = qv[a] - qn * un[a];
  const double tl = std::sqrt((t[0] * t[0] + t[1] * t[1]) + t[2] * t[2]);
  const double fr = mu * std::fabs(qn);
  const double ft = tl > fr ? fr / tl : 1.0;
  double* f1 = c->grid.gforce + 3 * n;
  double* f2 = c2->grid.gforce + 3 * n;
  for (int a = 0; a < 3; ++a) {
    const double d = -(qn * un[a] + ft * t[a]);
    p1[a] = p1[a] + d;
    p2[a] = p2[a] - d;
    if (!kRemap) {
      const double fc = d / dt_force;
      f1[a] = f1[a] + fc;
      f2[a] = f2[a] - fc;
      part[a] += fc;
    }
  }
  return true;
}

// Both stages over the owned nodes of the patches active in both components, patch by
// patch; the contact stage's force partials and count, and the boundary conditions.
template <bool kRemap>
void contact_correct(StepContext* c) {
  StepContext* c2 = c->contact.other;
  for_patches(c, [&](int q) {
    double part[3] = {0.0, 0.0, 0.0};
    int count = 0;
    const OwnedNodes o = owned_nodes(c, q);
    if (o.active && owned_nodes(c2, q).active) {
      for_owned_nodes(c, o, [&](int n) { count += contact_node<kRemap>(c, c2, n, part); });
    } else if (!kRemap && c->method.scheme == SCHEME_USF) {
      // USF reads the marks again in the next step (recontact before the stresses): no
      // node outside this loop keeps a mark or a mass gradient.
      for_owned_nodes(c, o, [&](int n) {
        double* g1 = c->contact.gnormal + 3 * n;
        g1[0] = g1[1] = g1[2] = 0.0;
      });
    }
    if (!kRemap) {
      double* col = c->contact.cpartials + size_t(kContactFields) * size_t(q);
      for (int a = 0; a < 3; ++a) col[a] = part[a];
      col[3] = double(count);
    }
  });
  apply_bc(c, c->grid.gmom);
  apply_bc(c2, c2->grid.gmom);
  if (kRemap) return;
  if (c->ranks.exchange) c->ranks.exchange(c, EXCHANGE_CONTACT, 0, 0);  // other ranks' columns
  double s[kContactFields] = {0.0, 0.0, 0.0, 0.0};
  for (int q = 0; q < c->patch.npatch; ++q)
    for (int a = 0; a < kContactFields; ++a) s[a] += c->contact.cpartials[size_t(kContactFields) * size_t(q) + size_t(a)];
  for (int a = 0; a < 3; ++a) c->out.result[5 + a] = s[a];
  c->contact.ncontact = int(s[3]);
  apply_bc(c, c->grid.gforce);
  apply_bc(c2, c2->grid.gforce);
}

}  // namespace
}  // namespace mpm3d

using namespace mpm3d;

// p_i += f_i dt_int at the nodes of the active patches; then the boundary conditions on
// momenta and forces (G2P reads both).
extern "C" void mpm3d_cxx_integrate(StepContext* c) {
  const double dt = c->clock.dt_int;
  double* mom = c->grid.gmom;
  const double* f = c->grid.gforce;
  for_patches(c, [&](int q) {
    if (patch_at_rest(c, q)) return;  // p = 0 + 0 dt there
    const OwnedNodes o = owned_nodes(c, q);
    if (!o.active) return;
    // One node row as one run of 3 (hi - lo) values, which vectorises.
    for (int k = o.lo[2]; k < o.hi[2]; ++k)
      for (int j = o.lo[1]; j < o.hi[1]; ++j) {
        const int row = 3 * (c->grid.nn[0] * (j + c->grid.nn[1] * k));
        for (int i = row + 3 * o.lo[0]; i < row + 3 * o.hi[0]; ++i) mom[i] = mom[i] + f[i] * dt;
      }
  });
  apply_bc(c, c->grid.gmom);
  apply_bc(c, c->grid.gforce);
}

extern "C" void mpm3d_cxx_contact(StepContext* c) {
  if (!c->contact.other) return;
  scatter_mass_gradient(c);
  scatter_mass_gradient(c->contact.other);
  contact_correct<false>(c);
}

extern "C" void mpm3d_cxx_recontact(StepContext* c) {
  if (!c->contact.other) return;
  contact_correct<true>(c);
}
