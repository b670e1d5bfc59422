/* Built against an installed MPM3D with `pkg-config --cflags --libs mpm3d`:
 *   pkgconfig_smoke DECK  -> opens the deck, takes 3 steps, prints the state. */
#include <stdio.h>

#include <mpm3d.h>

int main(int argc, char** argv) {
  mpm3d_sim* sim = NULL;
  if (argc != 2) return 2;
  if (mpm3d_open(argv[1], &sim) != MPM3D_OK || mpm3d_step(sim, 3) != MPM3D_OK) {
    fprintf(stderr, "pkgconfig_smoke: %s\n", mpm3d_last_error());
    mpm3d_close(sim);
    return 1;
  }
  printf("mpm3d %s: %d particles, step %ld, t %.6e, KE %.6e\n", mpm3d_version(), mpm3d_num_particles(sim),
         mpm3d_steps(sim), mpm3d_time(sim), mpm3d_kinetic_energy(sim));
  mpm3d_close(sim);
  return 0;
}
