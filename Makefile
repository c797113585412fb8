# gyro: two commands do everything on a fresh Debian machine.
#   make demo   install what is missing, build, run the demo on the embedded scene
#   make test   install what is missing, build, pass every test (unit, C ABI, sanitizers,
#               determinism across SIMD levels, threads, g++, clang++ and aarch64/qemu)
SHELL := /bin/bash
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=
PREFIX ?= /usr/local
BENCH_ARGS ?=
SAN_SIMD_LEVELS ?= $(if $(filter x86_64,$(shell uname -m)),scalar;avx2;avx512,auto)

.PHONY: all deps build demo test unit sanitize determinism lint bench install clean

all: build

deps:
	@.ci/deps build

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DGYRO_WERROR=ON $(CMAKE_ARGS) >/dev/null
	@cmake --build $(BUILD) -j$(JOBS) -- --no-print-directory

demo: build
	@./$(BUILD)/capi/examples/gyro-demo $(BUILD)/demo

# Everything CI runs.
test: unit sanitize determinism
	@echo "make test: all passed"

unit: build
	ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS)

# The whole suite again under AddressSanitizer and UndefinedBehaviorSanitizer, built by
# clang++, with the C ABI fuzz target (tests/fuzz; libFuzzer needs clang) in the same build:
# one instrumented library serves both (clang++ builds it in about half g++'s time, and a
# second build for the fuzzer cost two more minutes). -O1: the instrumented kernels take
# minutes to compile at -O2, and speed does not matter here; -g1: line tables are all a
# report needs. SSE2 is left out on x86-64 (AVX2 and AVX-512 keep the 8- and 16-wide tails;
# `unit` runs every level). Not run twice: the golden-hash scenes (half the instrumented
# run's time; `unit` and `determinism` check them on three compilers and architectures, and
# the code they run is tested here by the other tests), the dethash tool, the object checks
# and the lint. GYRO_TEST_QUICK shortens the replay mutation test (the fuzz run mutates
# recordings too). fuzz.capi_bounded is a bounded libFuzzer run (~45 s); a build that found
# no libFuzzer has no such test, and that must fail, not pass without it.
sanitize: deps
	@.ci/deps test
	@cmake -S . -B build-asan -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
	  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" -DGYRO_SANITIZE=address,undefined -DGYRO_SIMD_LEVELS="$(SAN_SIMD_LEVELS)" \
	  -DGYRO_BUILD_BENCH=OFF -DGYRO_BUILD_EXAMPLES=OFF -DGYRO_WERROR=ON $(CMAKE_ARGS) >/dev/null
	@cmake --build build-asan -j$(JOBS)
	@ctest --test-dir build-asan -N -R '^fuzz\.capi_bounded$$' | grep -q 'Total Tests: 1' || \
	  { echo "sanitize: no fuzz.capi_bounded test (libFuzzer missing?)"; exit 1; }
	ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp UBSAN_OPTIONS=print_stacktrace=1 \
	  GYRO_TEST_QUICK=1 \
	  ctest --test-dir build-asan --output-on-failure -j$(JOBS) -E '^(determinism\.matrix|objects\.|lint\.|Scenes/Determinism\.)'

# The same golden hashes from g++, clang++ and aarch64 (cross-built, run under qemu-user).
determinism: build
	@.ci/deps determinism
	@.ci/determinism $(BUILD)

lint:
	@tests/determinism/lint.sh .

bench: build
	@.ci/deps bench
	@cmake -S . -B $(BUILD) -DGYRO_BUILD_BENCH=ON >/dev/null && cmake --build $(BUILD) -j$(JOBS) --target gyro-bench
	@./$(BUILD)/bench/gyro-bench $(BENCH_ARGS)

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf build build-asan build-clang build-aarch64
