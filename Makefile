# Thin wrapper over CMake. `make run` and `make test` do all set-up on a fresh Debian machine.
BUILD ?= build
JOBS  ?= $(shell nproc)
DEB_PACKAGES = g++ gfortran cmake make libeigen3-dev libhdf5-dev hdf5-tools googletest \
               libgtest-dev libbenchmark-dev python3 python3-numpy python3-matplotlib
DECK ?= inputs/taylor/taylor_coarse.mpm
# Debian's interpreter (where python3-numpy/matplotlib live), even when another python3 is first on PATH.
PYTHON ?= $(shell test -x /usr/bin/python3 && echo /usr/bin/python3 || echo python3)
REPORT_ARGS ?=

.PHONY: all deps build run test bench report clean

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

bench: build
	tools/bench.sh $(BUILD)

report: build
	$(PYTHON) tools/report.py $(BUILD) --threads 2 $(REPORT_ARGS)

clean:
	rm -rf $(BUILD)
