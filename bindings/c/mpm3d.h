/* MPM3D-CXX C API (docs/DESIGN.md section 5a).
 *
 * A plain C99 interface to the MPM3D-CXX solver: open a legacy deck, choose the stage
 * kernels, advance the model, read and write the particle arrays, write the HDF5 state
 * file. The Fortran module mpm3d_api (bindings/fortran/mpm3d_api.f90) wraps exactly
 * these functions with ISO_C_BINDING.
 *
 * Conventions
 *   - Every function that can fail returns 0 (MPM3D_OK) on success and one of the
 *     non-zero MPM3D_ERR_* codes on failure; mpm3d_last_error() then gives a one-line
 *     message. Getters that return a value return NaN (double) or -1 (integer) when the
 *     handle is null. No function throws across the C boundary or aborts the process.
 *   - Every call except mpm3d_last_error() clears the calling thread's message first, so
 *     after a successful call mpm3d_last_error() returns "".
 *   - Particle arrays use the shared layout of docs/DESIGN.md section 5: one array per field,
 *     the component index fastest, as Fortran x(3,np): element (c, p) (0-based) at
 *     a[c + ncomp*p]. Stress is in Voigt order xx yy zz yz xz xy.
 *   - A handle may be used by one thread at a time; different handles are independent.
 *     The step itself runs on OpenMP threads (OMP_NUM_THREADS, or mpm3d_set_threads);
 *     results are bit for bit the same for any thread count.
 */
#ifndef MPM3D_H
#define MPM3D_H

#if defined(MPM3D_BUILDING_CAPI) && (defined(__GNUC__) || defined(__clang__))
#define MPM3D_API __attribute__((visibility("default")))
#else
#define MPM3D_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Return codes. */
enum {
  MPM3D_OK = 0,
  MPM3D_ERR_ARGUMENT = 1, /* null handle or pointer, unknown array name, wrong size, n < 0 */
  MPM3D_ERR_IO = 2,       /* a file cannot be opened, created or written */
  MPM3D_ERR_DECK = 3,     /* the deck has an error: the message is "FILE:LINE: problem" */
  MPM3D_ERR_KERNEL = 4,   /* unknown kernel specification or kernels not built */
  MPM3D_ERR_HEALTH = 5,   /* numerical breakdown (NaN/Inf) found after a step */
  MPM3D_ERR_MEMORY = 6,   /* out of memory */
  MPM3D_ERR_INTERNAL = 7  /* any other failure inside the library */
};

/* An open simulation (opaque). */
typedef struct mpm3d_sim mpm3d_sim;

/* Library version, e.g. "0.1.0". Never null. */
MPM3D_API const char* mpm3d_version(void);

/* The message of the last failed call in this thread ("" when the last call succeeded).
 * Never null; valid until the next call into the library from the same thread. */
MPM3D_API const char* mpm3d_last_error(void);

/* Reads a legacy deck (particles generated, time step computed) and prepares the grid.
 * On success *out is a new handle to be released with mpm3d_close; on failure *out is
 * set to NULL. A missing file gives MPM3D_ERR_IO, an input error MPM3D_ERR_DECK with the
 * message "FILE:LINE: problem". */
MPM3D_API int mpm3d_open(const char* deck_path, mpm3d_sim** out);

/* Releases the handle and everything it owns; mpm3d_close(NULL) does nothing. */
MPM3D_API void mpm3d_close(mpm3d_sim* sim);

/* Chooses the stage kernels, as the program's options do: "cxx" or "fortran" takes every
 * stage from one language (--kernel), "stage=lang,..." changes single stages (--kernels,
 * stage names as printed by `mpm3d --list-stages`). Changes apply on top of the current
 * table (a new handle starts with every stage from C++); the table is left unchanged on
 * error. */
MPM3D_API int mpm3d_set_kernel(mpm3d_sim* sim, const char* spec);

/* 1 when the library was built with the Fortran reference kernels, else 0. */
MPM3D_API int mpm3d_have_fortran_kernels(void);

/* Sets the number of OpenMP threads of later steps (omp_set_num_threads: process-wide).
 * n must be at least 1. */
MPM3D_API int mpm3d_set_threads(int n);

/* Advances nsteps explicit steps (nsteps >= 0). It does not stop at the deck's end time:
 * compare mpm3d_time with mpm3d_end_time for that. On a numerical breakdown it stops
 * after the failing step with MPM3D_ERR_HEALTH (the message names the step, the particle
 * and the field); the handle stays usable for reading and writing the state. */
MPM3D_API int mpm3d_step(mpm3d_sim* sim, int nsteps);

/* State of the run. */
MPM3D_API double mpm3d_time(const mpm3d_sim* sim);      /* simulated time */
MPM3D_API long mpm3d_steps(const mpm3d_sim* sim);       /* steps taken */
MPM3D_API int mpm3d_num_particles(const mpm3d_sim* sim);
MPM3D_API double mpm3d_dt(const mpm3d_sim* sim);        /* time step */
MPM3D_API double mpm3d_end_time(const mpm3d_sim* sim);  /* the deck's end time */
/* Energies of the current particle state (after the last step, or as opened; refreshed
 * by mpm3d_set_array). */
MPM3D_API double mpm3d_kinetic_energy(const mpm3d_sim* sim);
MPM3D_API double mpm3d_internal_energy(const mpm3d_sim* sim);
/* Total momentum (3 values) into dst. */
MPM3D_API int mpm3d_momentum(const mpm3d_sim* sim, double* dst);

/* Particle arrays by name, with their number of values n:
 *   "position" (3,np)  "velocity" (3,np)  "stress" (6,np)
 *   "mass" (np)  "volume" (np)  "epeff" (np)  "internal_energy" (np)
 *   "temperature" (np, only in models with a thermal Johnson-Cook material).
 * mpm3d_array_size returns the n an array needs (-1 and a message for an unknown name).
 * get copies the array into dst, set copies src into the model; n must equal the size
 * exactly. Setting positions between steps is allowed (particles are binned anew every
 * step). */
MPM3D_API long mpm3d_array_size(const mpm3d_sim* sim, const char* name);
MPM3D_API int mpm3d_get_array(const mpm3d_sim* sim, const char* name, double* dst, long n);
MPM3D_API int mpm3d_set_array(mpm3d_sim* sim, const char* name, const double* src, long n);

/* Writes the particle state as the program's --state option does (HDF5, docs/DESIGN.md
 * section 6; written to a temporary file and renamed). */
MPM3D_API int mpm3d_write_state(const mpm3d_sim* sim, const char* path);

/* Checkpoint and restart (docs/RELIABILITY.md). mpm3d_write_checkpoint writes everything a
 * step needs (every particle array, step, time, dt, energies, external work, the grid) to
 * an HDF5 file, atomically (temporary file + rename). mpm3d_restart loads such a file into
 * a handle opened from the same deck (counts and arrays are checked: MPM3D_ERR_IO naming
 * the problem, the handle unchanged); later steps then give the same bits as the run that
 * wrote it, for any thread count. */
MPM3D_API int mpm3d_write_checkpoint(const mpm3d_sim* sim, const char* path);
MPM3D_API int mpm3d_restart(mpm3d_sim* sim, const char* path);

#ifdef __cplusplus
}
#endif

#endif /* MPM3D_H */
