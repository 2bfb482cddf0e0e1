# The verbs people type. Each installs what is missing first (Debian packages,
# the .venv, the C++ build), so `make validate` and `make test` work on a fresh
# Debian 12 machine.
SHELL := /bin/bash
VENV  := .venv
PY    := $(VENV)/bin/python
BUILD := build
SUDO  := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

APT_PACKAGES := build-essential cmake ninja-build python3 python3-venv python3-dev \
	libembree-dev libopenexr-dev libtbb-dev libpugixml-dev libtinyobjloader-dev \
	libcli11-dev zlib1g-dev libopenimageio-dev libllvm19 googletest libgtest-dev chromium

# Mitsuba's llvm variants need LLVM 19 (Debian's libllvm19; 15 and 16 crash).
export DRJIT_LIBLLVM_PATH ?= $(firstword $(wildcard /usr/lib/*/libLLVM.so.19* /usr/lib/*/libLLVM-19.so))

# pytest's processes (pytest-xdist), each given whole files so that a file's fixtures (a loopback Dask
# cluster, Mitsuba's engine, a set of null renders) are made once.
TEST_JOBS ?= 2

SANITIZE_BUILD := build-sanitize
FUZZ_RUNS ?= 2000
FUZZ_SEED ?= 1
# The campaign of `images --scene` (harness, Mitsuba and mcval together; tests/fuzz/fuzz_images.py).
FUZZ_IMAGE_RUNS ?= 2000
FUZZ_IMAGE_SEED ?= 4104

.PHONY: validate test references bench build deps clean sanitize sanitize-build fuzz mutate

## validate: run the whole validation; writes results/<run>/ and fails on any FAIL
validate: build
	$(PY) -m harness validate

## test: the harness's layer contract (lint-imports), the Python suites (pytest), then the sanitizer run (the C++
## unit tests among it) and a short fuzz pass
test: deps
	@# The sanitizer build needs only the Debian packages: it compiles beside pip's install, which leaves a core idle.
	$(MAKE) --no-print-directory -j2 build sanitize-build
	$(VENV)/bin/lint-imports
	$(PY) -m pytest -n $(TEST_JOBS) --dist loadfile
	$(MAKE) --no-print-directory sanitize
	$(MAKE) --no-print-directory fuzz FUZZ_RUNS=300 FUZZ_IMAGE_RUNS=0

## sanitize: an ASan+UBSan build (-O1 -g1, as ASan advises: half the -O2 -g compile, the same run time within
## a tenth); the C++ tests, every scene x integrator and the fuzz corpus run under it
sanitize: sanitize-build build
	ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 $(SANITIZE_BUILD)/test_renderer --gtest_brief=1
	$(PY) tests/fuzz/replay.py --render $(SANITIZE_BUILD)/render

sanitize-build: deps
	@[ -f $(SANITIZE_BUILD)/build.ninja ] || cmake -S . -B $(SANITIZE_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
		-DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DMCVAL_SANITIZE=ON
	NINJA_STATUS="[sanitize %f/%t] " cmake --build $(SANITIZE_BUILD) --target render test_renderer

## fuzz: a bounded mutation-fuzz campaign of the sanitized renderer (FUZZ_RUNS variants, seed FUZZ_SEED), then
## one of `images --scene` (FUZZ_IMAGE_RUNS variants, seed FUZZ_IMAGE_SEED); each finding is saved as a
## reproducer (tests/fuzz/crashes/, tests/fuzz/findings/) and fails the target
fuzz: sanitize-build build
	$(PY) tests/fuzz/fuzz_scenes.py --runs $(FUZZ_RUNS) --seed $(FUZZ_SEED) --render $(SANITIZE_BUILD)/render
	@[ "$(FUZZ_IMAGE_RUNS)" = 0 ] || $(PY) tests/fuzz/fuzz_images.py --runs $(FUZZ_IMAGE_RUNS) --seed $(FUZZ_IMAGE_SEED)

## references: render and store the Mitsuba references (the only command that writes references/)
references: build
	$(PY) -m harness references

## bench: warp throughput of both engines (interleaved), speed against error for every case and engine, and ray
## rates beside a raw Embree loop
bench: build
	@mkdir -p results
	cmake --build $(BUILD) --target bench_rays
	$(BUILD)/bench_rays scenes/highpoly.xml --json results/bench_rays.json
	$(PY) bench/warp_throughput.py --json results/warp_throughput.json
	$(PY) -m harness bench --rays-json results/bench_rays.json

## mutate: mutation testing (mutmut, not in CI) of the statistics, checks and reports against the fast tests;
## the kill rate per module and the survivors in results/mutation/ (MUTATE= narrows the modules)
MUTATE ?= harness.statistics.welch* harness.statistics.chi2* harness.statistics.constants* \
	harness.statistics.family_level* harness.comparison.compare* harness.comparison.summary* harness.images.regression* harness.comparison.metrics* \
	harness.warps.checks* harness.bench.ladder*
mutate: $(VENV)/.installed
	@$(VENV)/bin/mutmut --version >/dev/null 2>&1 || $(PY) -m pip install --quiet "mutmut>=3.8,<4"
	@mkdir -p results/mutation
	-OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 $(VENV)/bin/mutmut run $(foreach m,$(MUTATE),'$(m)') > results/mutation/mutmut.log 2>&1
	$(PY) tools/mutation_report.py --out results/mutation $(foreach m,$(MUTATE),'$(m)')

## build: Debian packages, the .venv, the C++ renderer (`render` in .venv/bin) and the scenes' meshes
build: deps $(VENV)/.installed
	@[ -f $(BUILD)/build.ninja ] || cmake -S . -B $(BUILD) -G Ninja -DPython_EXECUTABLE=$(abspath $(PY))
	cmake --build $(BUILD)
	ln -sf $(abspath $(BUILD))/render $(VENV)/bin/render
	$(PY) scenes/generate_meshes.py -q
	@# The project's bytecode, which every Python process (test workers, Dask workers) would otherwise
	@# compile again where PYTHONDONTWRITEBYTECODE is set.
	$(PY) -m compileall -q harness tests tools

## deps: install the Debian packages that are missing (apt-get, with sudo unless root)
deps:
	@missing=$$(for p in $(APT_PACKAGES); do \
		dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q "ok installed" || echo $$p; done); \
	if [ -n "$$missing" ]; then \
		echo "Installing Debian packages:" $$missing; \
		$(SUDO) apt-get update && \
		$(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $$missing; \
	fi

# The .venv with the pinned Python packages; the C++ module is found through a .pth file. pip compiles the
# packages' bytecode as it installs them (with PYTHONDONTWRITEBYTECODE set, nothing else would).
$(VENV)/.installed: pyproject.toml | deps
	[ -x $(PY) ] || python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e .
	echo "$(abspath $(BUILD))/python" > "$$($(PY) -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')/mcval_renderer-build.pth"
	touch $@

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(VENV) results .fuzz mutants
