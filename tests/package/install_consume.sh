#!/usr/bin/env bash
# package.install_consume: installs a gyro build into a fresh prefix and consumes it as a C
# program would, from outside the source tree:
#  1. cmake --install BUILD --prefix WORK/prefix; the headers, libraries, CMake package and
#     gyro.pc are there, and the installed libgyro.so exports only gyro_* symbols;
#  2. CMake: a C-only project (consumer/) with find_package(gyro CONFIG REQUIRED) links
#     gyro::gyro and gyro::gyro_static and nothing else;
#  3. pkg-config: `cc consumer.c $(pkg-config --cflags --libs gyro)`, and --static with the
#     archive picked for -lgyro;
#  4. the four programs run, report the header's ABI, and print the same world hash; the
#     static ones do not load libgyro.so, the shared ones do.
# Usage: install_consume.sh BUILD_DIR WORK_DIR CONSUMER_SRC LIBDIR CMAKE CC PKG_CONFIG GENERATOR
set -euo pipefail
build=$1 work=$2 consumer=$3 libdir=$4 cmake=$5 cc=$6 pkg_config=$7 generator=$8
prefix=$work/prefix
fail() { echo "FAIL: $*" >&2; exit 1; }
step() { printf '%-58s' "$1"; }
start=$(date +%s%N)

rm -rf "$work"
mkdir -p "$work"
[[ $libdir != /* ]] || fail "CMAKE_INSTALL_LIBDIR is absolute ($libdir): the install cannot be moved to a test prefix"

# ---- 1. install
step "install into $(basename "$work")/prefix"
"$cmake" --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 || { cat "$work/install.log"; fail "cmake --install"; }
for f in include/gyro.h "$libdir/libgyro.a" "$libdir/libgyro.so" "$libdir/cmake/gyro/gyroConfig.cmake" \
         "$libdir/cmake/gyro/gyroConfigVersion.cmake" "$libdir/cmake/gyro/gyroTargets.cmake" "$libdir/pkgconfig/gyro.pc"; do
  [[ -e $prefix/$f ]] || fail "not installed: $f"
done
ls "$prefix/include/gyro/"*.hpp >/dev/null 2>&1 || fail "not installed: the C++ headers include/gyro/*.hpp"
echo "ok ($(du -sh "$prefix" | cut -f1))"

step "installed libgyro.so exports only gyro_*"
so=$prefix/$libdir/libgyro.so
exports=$(nm -D --defined-only "$so" | awk '$2 ~ /[TDBRVWiu]/ { print $3 }')
others=$(grep -v '^gyro_' <<<"$exports" || true)
[[ -z $others ]] || fail "libgyro.so exports symbols other than gyro_*:"$'\n'"$(head -20 <<<"$others")"
n=$(grep -c '^gyro_' <<<"$exports" || true)
(( n > 100 )) || fail "only $n gyro_* exports in libgyro.so"
echo "ok ($n exports)"

# ---- 2. CMake consumer (C only)
step "CMake: find_package, gyro::gyro, gyro::gyro_static"
if ! "$cmake" -S "$consumer" -B "$work/cmake" -G "$generator" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER="$cc" \
     -DCMAKE_PREFIX_PATH="$prefix" -DGYRO_EXPECTED_PREFIX="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
     >"$work/cmake-configure.log" 2>&1; then
  cat "$work/cmake-configure.log"; fail "configuring the CMake consumer"
fi
"$cmake" --build "$work/cmake" >"$work/cmake-build.log" 2>&1 || { cat "$work/cmake-build.log"; fail "building the CMake consumer"; }
echo ok

# ---- 3. pkg-config consumer
step "pkg-config: --cflags --libs gyro (shared and --static)"
[[ -n $pkg_config && -x $(command -v "$pkg_config" || true) ]] ||
  fail "pkg-config not found (Debian package pkg-config; .ci/deps build must install it)"
export PKG_CONFIG_LIBDIR=$prefix/$libdir/pkgconfig
unset PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR
# The package must describe where it is installed now, not where the build was configured
# to install it: cmake --install --prefix (make install PREFIX=...) moves it.
pc_include=$("$pkg_config" --variable=includedir gyro)
[[ $(realpath -m "$pc_include") == "$(realpath -m "$prefix/include")" ]] ||
  fail "gyro.pc is not relocatable: includedir=$pc_include after installing into $prefix (prefix is fixed at configure time; it should be \${pcfiledir}-relative)"
mkdir -p "$work/pkg-config"
cflags=$("$pkg_config" --cflags gyro) libs=$("$pkg_config" --libs gyro) static_libs=$("$pkg_config" --static --libs gyro)
echo "  cflags: $cflags" >"$work/pkg-config/flags.txt"
echo "  libs: $libs" >>"$work/pkg-config/flags.txt"
echo "  static libs: $static_libs" >>"$work/pkg-config/flags.txt"
common=(-std=c99 -pedantic -Wall -Wextra -Werror)
# shellcheck disable=SC2086 # the flags are words
"$cc" "${common[@]}" -DCONSUMER_KIND='"pkg-config-shared"' "$consumer/consumer.c" $cflags $libs \
  -o "$work/pkg-config/consumer_shared" 2>"$work/pkg-config/shared.log" ||
  { cat "$work/pkg-config/flags.txt" "$work/pkg-config/shared.log"; fail "pkg-config shared link"; }
# With both libgyro.so and libgyro.a in one directory the linker takes the .so for -lgyro; a
# static link names the archive. Libs.private must then supply everything it needs.
static_words=()
for w in $static_libs; do
  if [[ $w == -lgyro ]]; then static_words+=(-Wl,-Bstatic -lgyro -Wl,-Bdynamic); else static_words+=("$w"); fi
done
# shellcheck disable=SC2086
"$cc" "${common[@]}" -DCONSUMER_KIND='"pkg-config-static"' "$consumer/consumer.c" $cflags "${static_words[@]}" \
  -o "$work/pkg-config/consumer_static" 2>"$work/pkg-config/static.log" ||
  { cat "$work/pkg-config/flags.txt" "$work/pkg-config/static.log"; fail "pkg-config --static link"; }
echo ok

# ---- 4. run them
declare -A programs=(
  [cmake-shared]=$work/cmake/consumer_shared [cmake-static]=$work/cmake/consumer_static
  [pkg-config-shared]=$work/pkg-config/consumer_shared [pkg-config-static]=$work/pkg-config/consumer_static)
hashes=()
for kind in cmake-shared cmake-static pkg-config-shared pkg-config-static; do
  exe=${programs[$kind]}
  step "run $kind"
  needed=$(readelf -d "$exe" | grep -c 'NEEDED.*libgyro\.so' || true)
  if [[ $kind == *static ]]; then
    (( needed == 0 )) || fail "$kind needs libgyro.so"
  else
    (( needed == 1 )) || fail "$kind does not link libgyro.so"
  fi
  # pkg-config gives no run path: the shared program finds the library as a user's would
  # (LD_LIBRARY_PATH or ldconfig); the CMake one has its build run path.
  out=$(LD_LIBRARY_PATH=$prefix/$libdir "$exe") || fail "$kind exited with $?"
  [[ $out =~ ^$kind\ abi\ [0-9]+\.[0-9]+\ version\ [^\ ]+\ hash\ (0x[0-9a-f]{16})$ ]] || fail "$kind printed: $out"
  hashes+=("${BASH_REMATCH[1]}")
  if [[ $kind == *shared ]]; then
    loaded=$(LD_LIBRARY_PATH=$prefix/$libdir ldd "$exe" | awk '/libgyro\.so/ { print $3 }')
    [[ -n $loaded && $(realpath "$loaded") == "$(realpath "$so")" ]] ||
      fail "$kind loads $loaded, not the installed library"
  fi
  echo "ok: $out"
done
for h in "${hashes[@]}"; do [[ $h == "${hashes[0]}" ]] || fail "the consumers' world hashes differ: ${hashes[*]}"; done
echo "package.install_consume: all passed in $(( ($(date +%s%N) - start) / 1000000 )) ms"
