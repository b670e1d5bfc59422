#include <cstdlib>  // defines __GLIBC__ with glibc
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "app/cli.hpp"

// The program keeps the memory it frees for its next allocations. glibc's defaults hand a
// large block (128 KiB up, a deck's tokens, the particle and grid arrays) to the kernel on
// free and take fresh pages for the next, and every fresh page is a page fault: on the
// 311,550-particle landslides the set-up spent a quarter of its time in them, and this cut
// the whole run by 6-7 % (docs/PERFORMANCE.md). The library itself (bindings) leaves its
// host program's allocator as it is.
static void keep_freed_memory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 256 << 20);   // blocks up to 256 MiB from the heap, reused
  mallopt(M_TRIM_THRESHOLD, 1024 << 20);  // a freed heap top stays (up to 1 GiB)
  mallopt(M_TOP_PAD, 16 << 20);           // the heap grows 16 MiB at a time
#endif
}

int main(int argc, char** argv) {
  keep_freed_memory();
#ifdef MPM3D_HAVE_MPI
  return mpm3d::run_main_mpi(argc, argv);
#else
  return mpm3d::run_main(argc, argv);
#endif
}
