# geotex: the two commands of the README, and a few more.
#   make demo   set up, build, run the main job on the bundled synthetic sphere
#   make test   set up, build, run the tests (Release, then ASan + UBSan)
#   make check  the tests on the Release build only
BUILD     ?= build
SAN_BUILD ?= build-sanitize
CMAKE_FLAGS ?=
LAUNCHER := $(shell command -v ccache >/dev/null 2>&1 && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

.PHONY: all setup setup-test setup-bench configure build check test demo bench test-sanitize clean

all: build

setup:
	@scripts/setup-deps.sh build
setup-test:
	@scripts/setup-deps.sh test
setup-bench:
	@scripts/setup-deps.sh bench

configure: setup
	@test -f $(BUILD)/build.ninja || cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(LAUNCHER) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD)

# What CI runs (.ci/run): the suite on the Release build, then again under the sanitizers.
test: check test-sanitize

# The suite once, on the Release build: the quick check while developing.
check: setup-test build
	cd $(BUILD) && ctest --output-on-failure -j 2

demo: build
	scripts/demo.sh $(BUILD)/geotex out/demo

# A synthetic collection of 36 objects: geotex batch, a private Virtuoso, geotex publish and
# one cross-object question answered by the store (scripts/demo_collection.sh).
.PHONY: demo-collection
demo-collection: setup-test build
	scripts/demo_collection.sh $(BUILD)/geotex out/demo-collection

# The paper's experiments (noise, density, scale, negative details; bench/experiments/):
# rewrites the experiments section of bench/RESULTS.md and bench/figures/ (a few minutes);
# then the words experiment (issue 15), which rewrites the words section (about 2 minutes).
bench: setup-bench build
	python3 bench/experiments/run_experiments.py --build $(BUILD)
	python3 bench/experiments/words.py --build $(BUILD) --before bench/experiments/words-before.json

# Stage times and peak memory on icospheres (levels 5-9, scales 2/4/8%) and the CGAL demo
# meshes, with MeshLab's smoothing + Hausdorff distance beside: bench/RESULTS.md (perf section).
.PHONY: bench-perf
bench-perf: setup-bench build
	bench/perf/run_perf.py --geotex $(BUILD)/geotex --results bench/RESULTS.md

# The suite under AddressSanitizer and UndefinedBehaviorSanitizer (but the tests labelled
# release_only in CMakeLists.txt: the level-7 annotate run, the kill test, the benchmarks).
# -g1: line tables only, enough for the file and line of each frame of a sanitizer's report;
# full debug info (-g) cost 37% more compiler time on a CGAL unit (32.3 s against 23.6 s).
# -O1, the level AddressSanitizer's documentation advises: a quarter less compiler time than
# -O2 (cli/cmd_segment.cpp 31.4 s against 23.3 s), and the suite's time is mostly starting
# processes, not computing.
test-sanitize: setup-test
	@test -f $(SAN_BUILD)/build.ninja || cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
		-DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
		-DGEOTEX_SANITIZE=ON -DGEOTEX_BUILD_BENCH=OFF $(LAUNCHER)
	cmake --build $(SAN_BUILD)
	cd $(SAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j 2 -LE release_only

clean:
	rm -rf $(BUILD) $(SAN_BUILD) out

# libFuzzer targets under AddressSanitizer and UndefinedBehaviorSanitizer (clang; see
# fuzz/README.md): each runs FUZZ_SECONDS on its corpus in $(FUZZ_BUILD)/corpus/<target>;
# problem inputs go to $(FUZZ_BUILD)/artifacts/. Fails when a target found one.
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?=
.PHONY: fuzz
fuzz:
	@scripts/setup-deps.sh fuzz
	@test -f $(FUZZ_BUILD)/build.ninja || CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -G Ninja \
		-DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEOTEX_FUZZ=ON -DGEOTEX_BUILD_TESTS=OFF \
		-DGEOTEX_BUILD_BENCH=OFF $(LAUNCHER)
	cmake --build $(FUZZ_BUILD) --target fuzz_all geotex
	fuzz/make_seeds.sh $(FUZZ_BUILD)
	fuzz/run_fuzzers.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)
