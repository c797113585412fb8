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

# The whole suite again under AddressSanitizer and UndefinedBehaviorSanitizer (-O1: the
# instrumented kernels take minutes to compile at -O2, and speed does not matter here). The
# golden-hash scenes run there as GoogleTest cases; the dethash tool, the object checks and
# the lint give the same answers as in `unit`, so they are not run twice.
sanitize: deps
	@.ci/deps test
	@cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DGYRO_SANITIZE=address,undefined \
	  -DGYRO_BUILD_BENCH=OFF -DGYRO_BUILD_EXAMPLES=OFF -DGYRO_WERROR=ON $(CMAKE_ARGS) >/dev/null
	@cmake --build build-asan -j$(JOBS)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --test-dir build-asan --output-on-failure -j$(JOBS) -E '^(determinism\.matrix|objects\.|lint\.)'
	@# The C ABI fuzz target (tests/fuzz): libFuzzer needs clang, so a second, small ASan+UBSan
	@# build by clang++ of the library and the fuzz target only, and a bounded run (~45 s).
	@cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
	  -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DGYRO_SANITIZE=address,undefined -DGYRO_BUILD_GTESTS=OFF \
	  -DGYRO_BUILD_BENCH=OFF -DGYRO_BUILD_EXAMPLES=OFF -DGYRO_WERROR=ON $(CMAKE_ARGS) >/dev/null
	@cmake --build build-fuzz -j$(JOBS) --target gyro-fuzz-capi
	ctest --test-dir build-fuzz --output-on-failure -R '^fuzz\.'

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
	rm -rf build build-asan build-clang build-aarch64 build-fuzz
