// Ranks: what a Simulation asks of the other processes of a distributed run. The solver
// calls this interface; MPI ranks implement it above it (MpiRanks, cxx/parallel/, linked into
// the mpm3d program only). A Simulation without one
// (Simulation::ranks null) is the whole run on one process and calls none of this.
//
// Each rank owns a contiguous run of patches and the particles inside them. The bits of a
// run do not depend on the number of ranks, because nothing is summed across ranks: the
// patch buffers of neighbouring ranks' patches are copied (a buffer holds the sums of its
// own patch's particles only), the energy stage's per-patch partials are gathered and
// folded in patch order on every rank, and every other collective is a min, a max or an
// integer sum (docs/ARCHITECTURE.md, "Ranks").
#pragma once
#include <string>
#include <vector>

#include "core/particle.hpp"
#include "stages/update_step.hpp"

namespace mpm3d {

class Simulation;

class Ranks {
 public:
  virtual ~Ranks() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool root() const { return rank() == 0; }

  // Set-up, after the Simulation is built from the whole deck on every rank: draw the
  // ranks' patch runs from the particle counts and keep this rank's particles.
  virtual void distribute(Simulation& sim) = 0;
  // Before each bin stage: bins this rank's particles (StepContext::prebinned) and moves
  // those whose patch is another rank's there, with every field (on a new grid window, the
  // adaptive grid's, after drawing the ranks' runs of its patches); StepContext::order lists
  // this rank's particles in ascending storage index of one rank's run.
  virtual void migrate(Simulation& sim) = 0;
  // After each bin stage: buffer slots for the non-empty patches of other ranks next to
  // this rank's patches (the ghost patches), after this rank's own slots.
  virtual void add_ghost_slots(Simulation& sim) = 0;

  // The largest particle share over the mean above which migrate redraws the ranks' runs.
  virtual void set_rebalance_above(double ratio) = 0;

  // Collectives: exact whatever the order (integers, min, max).
  virtual long sum(long v) = 0;
  virtual int min(int v) = 0;
  virtual double min(double v) = 0;
  virtual double max(double v) = 0;
  // Each value the largest over the ranks (a rank without a value gives -infinity).
  virtual void max(std::vector<double>& values) = 0;
  // The text s of rank `from` on every rank.
  virtual std::string broadcast(const std::string& s, int from) = 0;
  // All particles, in one rank's storage order (every field, with the deck numbers), on
  // the root; other ranks get an empty set.
  virtual void gather(const Particles& local, Particles& all) = 0;
  // The root's values on every rank.
  virtual void broadcast(std::vector<double>& values) = 0;
  // A node field (ncomp per node) of context c made whole on every rank: each node's values
  // from the rank owning the node's patch, whose sums are complete there.
  virtual void share_owned_nodes(const StepContext& c, double* field, int ncomp) = 0;
  // Ends every rank at once with exit status code: for an error met by this rank alone.
  [[noreturn]] virtual void abort(int code) = 0;
  // Total particles of the run.
  virtual int global_np() const = 0;
  // The ranks' particle shares: largest over mean (1: balanced).
  virtual double imbalance() const = 0;
  // Bytes this rank has sent to other ranks in the steps so far.
  virtual double bytes_sent() const = 0;
  // Times the ranks' patch runs were redrawn for balance.
  virtual long rebalances() const = 0;
};

}  // namespace mpm3d
