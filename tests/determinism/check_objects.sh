#!/usr/bin/env bash
# Checks the machine code of libgyro against the determinism contract:
#  1. no fused multiply-add anywhere (x86: vfmadd/vfmsub/vfnmadd/vfnmsub; aarch64:
#     fmadd/fmsub/fnmadd/fnmsub/fmla/fmls);
#  2. (x86) VEX/EVEX-encoded code (AVX, any 'v' mnemonic) only inside gyro's AVX kernel
#     namespaces or xsimd's AVX types: nothing compiled with AVX flags may leak into code
#     the SSE2 or scalar path can call (xsimd pitfall 6);
#  3. the shared library exports only gyro_* symbols.
# Usage: check_objects.sh LIBRARY [OBJDUMP] [NM]
set -euo pipefail
lib=$1
objdump=${2:-objdump}
nm=${3:-nm}
fail=0
dis=$("$objdump" -d --no-show-raw-insn -C "$lib")

fma=$(grep -E '^[[:space:]]+[0-9a-f]+:[[:space:]]+(vfn?m(add|sub)[0-9a-z]*|fn?m(add|sub)|fml[as])[[:space:]]' <<<"$dis" || true)
if [[ -n $fma ]]; then
  echo "FAIL: fused multiply-add instructions in $lib:"; head -20 <<<"$fma"; fail=1
else
  echo "ok: no FMA instructions"
fi

if grep -q 'x86-64' <<<"$("$objdump" -f "$lib")"; then
  leaks=$(awk '
    /^[0-9a-f]+ <.*>:$/ { fn = $0; sub(/^[0-9a-f]+ </, "", fn); sub(/>:$/, "", fn); next }
    /^[ \t]+[0-9a-f]+:[ \t]+v[a-z0-9]+[ \t]/ {
      if (fn !~ /arch_avx2|arch_avx512|xsimd::avx/ && !(fn in seen)) { seen[fn] = 1; print fn }
    }' <<<"$dis")
  if [[ -n $leaks ]]; then
    echo "FAIL: AVX-encoded code outside the AVX kernels:"; head -20 <<<"$leaks"; fail=1
  else
    echo "ok: AVX code only in arch_avx2 / arch_avx512"
  fi
fi

exports=$("$nm" -D --defined-only "$lib" | awk '$2 ~ /[TDBRWVui]/ { print $3 }' | grep -v '^gyro_' || true)
if [[ -n $exports ]]; then
  echo "FAIL: exported symbols other than gyro_*:"; head -20 <<<"$exports"; fail=1
else
  echo "ok: $("$nm" -D --defined-only "$lib" | grep -c ' gyro_') exports, all gyro_*"
fi
exit $fail
