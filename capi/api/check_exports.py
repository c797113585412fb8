#!/usr/bin/env python3
"""ctest capi.api_json: the API description and the shared library agree.

Every function of gyro_api.json is exported by libgyro (a missing one: declared in gyro.h
but not implemented, or hidden), and every exported gyro_* symbol is in the JSON (an export
the header does not declare). Also checks the JSON's shape: the keys bindings read.
Usage: check_exports.py --json gyro_api.json --lib libgyro.so [--nm nm]
"""
import argparse
import json
import subprocess
import sys


def exported(nm, lib):
    out = subprocess.run([nm, "-D", "--defined-only", lib], check=True, capture_output=True, text=True).stdout
    names = set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 3 and parts[1] in ("T", "W", "i"):  # code: text, weak, indirect
            names.add(parts[2].split("@")[0])
        elif len(parts) >= 3 and parts[2].startswith("gyro_"):
            names.add(parts[2].split("@")[0])  # data exports are reported too
    return {n for n in names if n.startswith("gyro_")}


def check_shape(api):
    errors = []
    for key in ("abi_version", "constants", "typedefs", "opaque", "structs", "functions"):
        if key not in api:
            errors.append(f"missing key {key!r}")
    if errors:
        return errors
    if not isinstance(api["abi_version"].get("major"), int) or not isinstance(api["abi_version"].get("minor"), int):
        errors.append("abi_version needs integer major and minor")
    for c in api["constants"]:
        if not isinstance(c.get("value"), int) or "enum" not in c:
            errors.append(f"constant {c.get('name')}: value and enum")
    for s in api["structs"]:
        if not s.get("fields") or s.get("size", 0) <= 0 or s.get("align", 0) <= 0:
            errors.append(f"struct {s.get('name')}: fields, size and align")
        for f in s.get("fields", []):
            if not all(k in f for k in ("name", "type", "offset", "size", "count")):
                errors.append(f"struct {s['name']}.{f.get('name')}: name, type, offset, size, count")
            if f.get("type") == "union" and not f.get("members"):
                errors.append(f"struct {s['name']}.{f.get('name')}: a union without members")
    for f in api["functions"]:
        if not all(k in f for k in ("name", "return", "params", "doc")):
            errors.append(f"function {f.get('name')}: name, return, params, doc")
    return errors


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--json", required=True)
    ap.add_argument("--lib", required=True)
    ap.add_argument("--nm", default="nm")
    a = ap.parse_args()
    with open(a.json) as fh:
        api = json.load(fh)
    errors = check_shape(api)
    declared = {f["name"] for f in api.get("functions", [])}
    exports = exported(a.nm, a.lib)
    missing = sorted(declared - exports)
    undocumented = sorted(exports - declared)
    for n in missing:
        errors.append(f"declared in gyro.h but not exported by {a.lib}: {n}")
    for n in undocumented:
        errors.append(f"exported by {a.lib} but not declared in gyro.h: {n}")
    print(f"{a.json}: ABI {api['abi_version']['major']}.{api['abi_version']['minor']}, "
          f"{len(declared)} functions, {len(api.get('structs', []))} structs, "
          f"{len(api.get('constants', []))} constants; {len(exports)} gyro_* exports")
    if errors:
        for e in errors:
            print("FAIL:", e)
        return 1
    print("OK: the library exports exactly the functions gyro.h declares")
    return 0


if __name__ == "__main__":
    sys.exit(main())
