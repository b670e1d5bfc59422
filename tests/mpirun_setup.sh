# Sourced by the ranks tests (rank_determinism.sh, rank_failure.sh) with $mpirun set: the
# environment every mpirun of a test runs in, and exit 77 (skipped) where mpirun is absent or
# cannot start two processes at all (no shared memory, no network interface).
[ -x "$mpirun" ] || { echo "mpirun absent: skipped"; exit 77; }
# Open MPI refuses to start as root unless told: set here, for the tests only.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Oversubscribed, spinning threads and ranks wait for each other's time slices (2x2 on two
# cores ran 25x slower): waiting threads and ranks yield.
export OMP_WAIT_POLICY=passive OMPI_MCA_mpi_yield_when_idle=1
# Under AddressSanitizer (make test-sanitize): the slow unwinder, so that Open MPI's own
# leaks show the library frames tools/lsan.supp suppresses them by.
if [ -n "${ASAN_OPTIONS:-}" ]; then export ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0"; fi
timeout 60 "$mpirun" --oversubscribe --bind-to none -np 2 true > /dev/null 2>&1 ||
  { echo "mpirun cannot start 2 processes here: skipped"; exit 77; }
