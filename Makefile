# geotex: the two commands of the README, and a few more.
#   make demo   set up, build, run the main job on the bundled synthetic sphere
#   make test   set up, build, run the tests
BUILD     ?= build
SAN_BUILD ?= build-sanitize
CMAKE_FLAGS ?=
LAUNCHER := $(shell command -v ccache >/dev/null 2>&1 && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

.PHONY: all setup setup-test setup-bench configure build test demo bench test-sanitize clean

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

test: setup-test build
	cd $(BUILD) && ctest --output-on-failure -j 2

demo: build
	scripts/demo.sh $(BUILD)/geotex out/demo

bench: setup-bench build
	bench/run_bench.sh $(BUILD) bench/out

# The whole suite under AddressSanitizer and UndefinedBehaviorSanitizer.
test-sanitize: setup-test
	@test -f $(SAN_BUILD)/build.ninja || cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
		-DGEOTEX_SANITIZE=ON -DGEOTEX_BUILD_BENCH=OFF $(LAUNCHER)
	cmake --build $(SAN_BUILD)
	cd $(SAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j 2

clean:
	rm -rf $(BUILD) $(SAN_BUILD) out
