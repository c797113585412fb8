#!/usr/bin/env bash
# The determinism contract's source rules, enforced by the tests (the shared detlint tool
# is advisory and may not be present on CI):
#  - no libm transcendental in engine code (gyro has its own polynomials);
#  - no xsimd math, estimate or fused operation (only src/core/lanes.hpp touches xsimd ops);
#  - no OpenMP reduction clause; no xsimd or OpenMP in public headers;
#  - -ffp-contract=off set, no unsafe float flag in the build.
# A line may opt out with a comment "detlint: allow" and a reason.
set -uo pipefail
root=${1:-.}
cd "$root" || exit 2
fail=0
check() {  # pattern, message, paths...
  local pat=$1 msg=$2; shift 2
  local hits
  hits=$(grep -rnE --include='*.cpp' --include='*.hpp' --include='*.h' --include='*.c' "$pat" "$@" 2>/dev/null | grep -v 'detlint: allow')
  if [[ -n $hits ]]; then echo "lint: $msg"; sed 's/^/  /' <<<"$hits"; fail=1; fi
}
engine=(src include capi/gyro.h capi/gyro_capi.cpp)
check '(^|[^a-zA-Z0-9_])(std)?::(sin|cos|tan|asin|acos|atan2?|exp|log|log2|log10|pow|sinh|cosh|tanh|cbrt|hypot|fma)f?\(|[^_a-zA-Z.:](sinf|cosf|tanf|asinf|acosf|atanf|atan2f|expf|logf|powf|fmaf?)\(' \
  "libm transcendental in engine code (use gyro's own)" "${engine[@]}"
check 'xsimd::(sin|cos|tan|asin|acos|atan2?|exp|log|pow|rsqrt|reciprocal|fma|fms|fnma|fnms|hadd|reduce_add|bitwise_andnot)\b' \
  "xsimd operation outside the determinism contract" "${engine[@]}"
check '_mm(256|512)?_(rsqrt|rcp|fmadd|fmsub|fnmadd|fnmsub)' "approximate or fused intrinsic" "${engine[@]}"
check 'reduction *\(' "OpenMP reduction clause (its order depends on the thread count)" "${engine[@]}"
check '#include *<(xsimd|omp)' "xsimd or OpenMP included from a public header" include capi/gyro.h
check 'std::unordered_(map|set)' "unordered container in engine code (iteration order is not deterministic)" "${engine[@]}"
if grep -nE 'fast-math|finite-math-only|unsafe-math-optimizations|associative-math' CMakeLists.txt Makefile | grep -v 'MATCHES'; then
  echo "lint: unsafe float flag in the build"; fail=1
fi
grep -q -- '-ffp-contract=off' CMakeLists.txt || { echo "lint: CMakeLists.txt does not set -ffp-contract=off"; fail=1; }
[[ $fail -eq 0 ]] && echo "lint: determinism rules hold"
exit $fail
