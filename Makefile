# Thin wrapper over CMake. `make run` and `make test` do all set-up on a fresh Debian machine.
BUILD ?= build
JOBS  ?= $(shell nproc)
DEB_PACKAGES = g++ gfortran cmake make libeigen3-dev libhdf5-dev hdf5-tools googletest \
               libgtest-dev libbenchmark-dev python3 python3-numpy python3-matplotlib \
               libopenmpi-dev openmpi-bin time
DECK ?= inputs/taylor/taylor_coarse.mpm
# `make fuzz` only (docs/RELIABILITY.md): libFuzzer comes with Debian's clang.
FUZZ_PACKAGES = clang libclang-rt-dev
# `make report` only: its contact and granular studies read the runs' HDF5 files in Python.
REPORT_PACKAGES = python3-h5py
FUZZ_TIME ?= 600
SAN_BUILD ?= $(BUILD)-sanitize
# ASan/UBSan run: every report is fatal, leaks included.
SAN_ENV = ASAN_OPTIONS=detect_leaks=1:detect_stack_use_after_return=1 \
          UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
          LSAN_OPTIONS=suppressions=$(CURDIR)/tools/lsan.supp
# bindings.install_example links the installed (instrumented) library into an outside
# project built without the sanitizers: meaningless in this build. The single-stage swaps
# (fref_*_stage_*) run the same kernels as the --kernel fortran and mixed variants that
# stay in: left out to keep CI short, as are the paraview.* tests (ParaView reading files
# the normal build's run of the same tests has checked) and the 311,550-particle landslide
# decks (their reader and stages run under the sanitizers on the smaller clay deck), and the
# sgmp stop's advice (3,000 steps of a public dam break to reach the stop whose path
# health.advice_fits_the_deck runs under the sanitizers on a smaller deck), and the thread
# comparisons of the two longest decks (threads.lead_sphere_small 268 s, threads.granular_column
# 90 s of the sanitizer run's 1,492 s, 2026-12-05; the same decks run under the sanitizers in
# fref_lead_sphere_small_*, Hypervelocity.* and DruckerPrager.CohesionlessColumnComesToRest).
SAN_CTEST_ARGS ?= -E '^bindings\.install_example$$|_stage_|^paraview\.|_landslide_|^health\.sgmp_|^threads\.(lead_sphere_small|granular_column)$$'
# Debian's interpreter (where python3-numpy/matplotlib live), even when another python3 is first on PATH.
PYTHON ?= $(shell test -x /usr/bin/python3 && echo /usr/bin/python3 || echo python3)
REPORT_ARGS ?=

.PHONY: all deps build run test bench report report-deps clean fuzz fuzz-deps test-sanitize

all: build

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "installing:$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing >/dev/null; \
	  else echo "missing Debian packages:$$missing (run as root, or install them)"; exit 1; fi; \
	fi

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

run: build
	tools/taylor_run.sh $(BUILD) $(DECK)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The whole test suite under AddressSanitizer + UBSan (+ LeakSanitizer), in $(SAN_BUILD).
test-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -DCMAKE_BUILD_TYPE=Release -DMPM3D_SANITIZE=ON
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && $(SAN_ENV) ctest --output-on-failure -j $(JOBS) $(SAN_CTEST_ARGS)

fuzz-deps:
	@$(MAKE) --no-print-directory deps DEB_PACKAGES="$(FUZZ_PACKAGES)"

# Bounded libFuzzer run of the deck reader: `make fuzz FUZZ_TIME=seconds` (default 600).
fuzz: fuzz-deps
	tools/fuzz.sh $(FUZZ_TIME) $(BUILD)-fuzz

bench: build
	tools/bench.sh $(BUILD)

report-deps:
	@$(MAKE) --no-print-directory deps DEB_PACKAGES="$(REPORT_PACKAGES)"

report: build report-deps
	$(PYTHON) tools/report.py $(BUILD) --threads 2 $(REPORT_ARGS)
	$(PYTHON) tools/current_decks.py $(BUILD) --threads 2

clean:
	rm -rf $(BUILD) $(BUILD)-fuzz $(SAN_BUILD)
