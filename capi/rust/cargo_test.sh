#!/bin/sh
# ctest capi.rust: `cargo test --offline` on the Rust bindings against the built libgyro.
# Usage: cargo_test.sh CARGO LIB_DIR API_JSON TARGET_DIR MANIFEST [PRELOAD...]
#   CARGO       cargo's path ("" when CMake found none: the test is skipped, exit 77)
#   LIB_DIR     the directory of libgyro.so (GYRO_LIB_DIR for gyro-sys's build.rs)
#   API_JSON    gyro_api.json (GYRO_API_JSON for the layout tests)
#   TARGET_DIR  CARGO_TARGET_DIR, inside the CMake build directory
#   MANIFEST    capi/rust/Cargo.toml
#   PRELOAD     sanitizer runtimes a sanitized libgyro needs first in the test processes
set -eu
cargo=$1 lib_dir=$2 api_json=$3 target_dir=$4 manifest=$5
shift 5
if [ -z "$cargo" ] || [ ! -x "$cargo" ]; then
  echo "capi.rust: SKIPPED: cargo was not found when CMake configured (put it on PATH or set -DCARGO=...)"
  exit 77
fi
if [ ! -f "$api_json" ]; then
  echo "capi.rust: $api_json is missing: build the gyro_api_json target first"
  exit 1
fi
export GYRO_LIB_DIR="$lib_dir" GYRO_API_JSON="$api_json" CARGO_TARGET_DIR="$target_dir"
export LD_LIBRARY_PATH="$lib_dir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export PATH="$(dirname "$cargo"):$PATH" CARGO_TERM_COLOR=never
if [ $# -gt 0 ]; then
  # A sanitized libgyro needs its runtimes loaded first: run the test binaries (not cargo,
  # rustc or build scripts) through `env LD_PRELOAD=...` (ASAN_OPTIONS etc. pass through).
  preload=$(echo "$@" | tr ' ' ':')
  host=$(rustc -vV | sed -n 's/^host: //p' | tr 'a-z.-' 'A-Z__')
  export "CARGO_TARGET_${host}_RUNNER=env LD_PRELOAD=$preload"
  echo "capi.rust: test binaries run with LD_PRELOAD=$preload"
fi
start=$(date +%s%N)
status=0
"$cargo" test --offline --manifest-path "$manifest" || status=$?
echo "capi.rust: cargo test took $(( ($(date +%s%N) - start) / 1000000 )) ms (target dir $target_dir)"
exit $status
