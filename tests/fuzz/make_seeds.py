#!/usr/bin/env python3
"""Writes the seed corpus of gyro-fuzz-capi (tests/fuzz/corpus/): one small program per
family of operations, in the byte format fuzz_capi.cpp reads. Run it after changing that
format; check a seed with GYRO_FUZZ_TRACE=1 build-asan/tests/fuzz/gyro-fuzz-capi SEED."""
import os
import sys

# Opcodes (kOps in fuzz_capi.cpp).
WORLD_CREATE, WORLD_DESTROY, BODY_CREATE, BODY_DESTROY, BODY_SET, BODY_GET, STEP = range(7)
SOFT_CREATE, SOFT_CALL, MESH_CREATE, MESH_DESTROY, HULL_CREATE, HULL_DESTROY = range(7, 13)
CONVEX_PAIRS, BATCH_RAYCAST, BATCH_OVERLAP, MESH_RAYCAST, CAMERA, SCENE = range(13, 19)
SNAP_ROUNDTRIP, SNAP_MUTATE, RAW_BYTES, RECORD, SETTINGS = range(19, 24)

class Special(int):
    """A float byte of the special table (0xF0..)."""


NAN, INF = Special(0xF1), Special(0xF3)


def f(v):
    """A float in (b - 120) / 8 encoding."""
    if isinstance(v, Special):
        return int(v)
    b = int(round(v * 8)) + 120
    assert 0 <= b < 0xF0, v
    return b


def v3(x, y, z):
    return [f(x), f(y), f(z)]


def body(shape, x=4, y=2, z=4, edits=(), nulls=0, world=0, extra=()):
    """shape: 0 sphere, 1 box, 2 plane, 3 mesh (extra: the mesh pick), 4 capsule, 5 hull."""
    return [BODY_CREATE, world, shape, *extra, x, y, z, len(edits), *[b for e in edits for b in e], nulls]


def step(kind=0, world=0):
    return [STEP, world, kind]


def rays(n=4, edits=(), np=0):
    """n rays straight down from (x, 5, z), edits (ray, kind, values...)."""
    return [n + 8, *[4] * 16, len(edits), *[b for e in edits for b in e], np]


def shapes(n, t, edits=()):
    """n shapes of type t (1 sphere .. 5 triangle), edits (component, element, float byte)."""
    return [n + 8, t, 1, 1, *[4] * 16, len(edits), *[b for e in edits for b in e], 19]


def cshape(t, edit=(7,)):
    """A convex shape of type t (5: hull 0), then one edit."""
    return [t, 0, 0, *([0] if t == 5 else []), *edit]


def pose(x=4, quat=None):
    return [x, 4, 1] if quat is None else [x, 4, 2, *quat]


def camera(k=0):
    return [0, 0, 0, 0, 4, k, 1]


def soft_call(k, extra=(), p=1, q=2):
    return [SOFT_CALL, 0, 0, k, p, q, 1, *extra]


SOFT_EXTRA = {1: [0], 2: [1], 3: [0, 0], 4: [1], 5: [f(1)], 6: [f(2)], 12: v3(0, 1, 0), 13: v3(1, 0, 0),
              15: [f(1), 1], 17: [3, 4], 22: v3(0, 2, 0), 23: v3(0, 2, 0)}

seeds = {
    # bodies of every simple shape, forces, getters and steps; bad body defs and a stale id
    "bodies": [0, *body(2), *body(0), *body(1, 5, 4, 4), *body(4, 3, 6, 4), *step(), *step(),
               BODY_SET, 0, 1, 1, *v3(1, 0, 0), *v3(0, 1, 0),
               BODY_SET, 0, 1, 2, *v3(0, 10, 0), *v3(0, 0, 0),
               BODY_SET, 0, 2, 0, *v3(0, 3, 0), *v3(0, 0, 0), f(0), f(0), f(0), f(1), 1,
               BODY_SET, 0, 2, 7, *v3(0, 0, 0), *v3(0, 0, 0), 0,
               *[b for k in range(16) for b in (BODY_GET, 0, 1, k, 1, 1, *([3] if k == 12 else []))],
               *body(0, edits=[(3, NAN)]), *body(1, edits=[(10, f(-1))]), *body(1, edits=[(6, f(0), f(0), f(0), f(0))]),
               BODY_DESTROY, 0, 1, BODY_DESTROY, 0, 0xE0,
               BODY_SET, 0, 1, 0, *v3(0, 0, 0), *v3(0, 0, 0), f(0), f(0), f(0), f(1), 1,
               *step(2), STEP, 0, 5, NAN, *step(1)],
    # world definitions: valid edits, wrong struct_size, NaN gravity, bad thread count
    "worlds": [0, WORLD_CREATE, 1, 2, 1, 2, 21, 2, 0, *body(0, world=1), *step(world=1),
               WORLD_CREATE, 0, 1, 0, 1, 2, 0, WORLD_CREATE, 1, 1, 2, NAN, 0, 0, 0,
               WORLD_CREATE, 1, 1, 19, 3, 0, WORLD_CREATE, 1, 1, 0, 1, 1, 0,
               WORLD_DESTROY, 1, *body(0, world=1), *step(world=7)],
    # cloth, soft cube and soft mesh, then every soft-body call, in and out of range
    "soft": [0, *body(2), SOFT_CREATE, 0, 0, 0, 2, 2, 1, 1, 3, 0,
             SOFT_CREATE, 0, 1, 0, 2, 3, 0, SOFT_CREATE, 0, 2, 0, 0, 0,
             *[b for k in range(1, 24) for b in soft_call(k, SOFT_EXTRA.get(k, []))],
             *soft_call(7, p=0xF0), *soft_call(12, v3(0, 0, 0), p=0xF1), *soft_call(17, [0xF0, 4]),
             *step(), *soft_call(0), *soft_call(7),
             SOFT_CREATE, 0, 0, 0, 0xE0, 0xE5, 1, 1, 3, 0],
    # meshes (valid, NaN vertex, index out of range), a mesh body, mesh raycasts
    "mesh": [0, MESH_CREATE, 0, 8, 6, 0, 0, MESH_CREATE, 1, 8, 6, 1, 3, 2, NAN, 0, 0, 0,
             MESH_CREATE, 2, 8, 6, 1, 7, 4, 0, *body(3, extra=[0]), *body(0, 4, 3, 4), *step(),
             MESH_RAYCAST, 0, *rays(), 0, 0, 0, MESH_RAYCAST, 0, *rays(edits=[(1, 1, NAN, 0, 0)]), 0, 1, 0,
             MESH_DESTROY, 0, *step()],
    # convex hulls (a box, a lattice, a flat set), a hull body, pair queries of every kind
    "convex": [0, HULL_CREATE, 0, 4, 0, 0, 0, 12, HULL_CREATE, 1, 4, 2, *range(24), 0, 0, 12,
               HULL_CREATE, 2, 4, 3, 0, *[f(1), f(2)] * 24, 0, 0, 12,
               *body(5, extra=[0]), *body(0, 4, 4, 4), *step(),
               *[b for q in range(3) for b in (CONVEX_PAIRS, 12, *cshape(0), *pose(), *cshape(1), *pose(5),
                                                  *cshape(2), *pose(), *cshape(5), *pose(4, [f(0), f(0), f(0), f(1)]),
                                                  *cshape(3), *pose(), *cshape(4, (1, 1, *v3(0, 1, 0))), *pose(),
                                                  *cshape(5), *pose(), *cshape(1, (0, *v3(NAN, 1, 1))), *pose(),
                                                  q, 0)],
               HULL_DESTROY, 0, *step()],
    # brute-force raycasts and overlaps over each shape type, NaN and bad flags
    "batch": [0, *[b for t in range(1, 6) for b in (BATCH_RAYCAST, *rays(), *shapes(4, t), 0, 0, 0)],
              BATCH_RAYCAST, *rays(edits=[(0, 0, NAN, 0, 0)]), *shapes(4, 1), 0, 0, 0,
              BATCH_RAYCAST, *rays(), *shapes(4, 1), 0, 2, 0,
              *[b for t in range(1, 6) for b in (BATCH_OVERLAP, *shapes(4, t), *shapes(4, t % 5 + 1), t % 2, 0, 0, 1, 12)],
              BATCH_OVERLAP, *shapes(4, 3), *shapes(4, 3), 2, 0, 0, 1, 12,
              BATCH_OVERLAP, *shapes(4, 1, [(3, 0, NAN)]), *shapes(4, 1), 0, 0, 1, 1, 12],
    # camera, frustum and culling; scenes with every model shape, parents, rays, queries, picking
    "scene": [0, CAMERA, *camera(), 0, f(0), f(0), 0, 0, 1, 1, *shapes(4, 1),
              MESH_CREATE, 0, 8, 6, 0, 0, SCENE, 0, 0, 0, 1, 1, SCENE, 0, 1, 1, 1, 1,
              *[b for m in range(4) for b in (SCENE, 1, 0, m, *([0] if m == 2 else []), 4, 4, 4, 1, 0, 0)],
              SCENE, 1, 0, 0, 4, 4, 4, 0, 0, 0, 0, SCENE, 5, 0, 0, 1, SCENE, 4, 0, 1, 4, 4, 4, 1,
              SCENE, 6, 0, 0, *rays(), 0, 0, 0, SCENE, 6, 0, 0, *rays(), 0, 1, 0,
              SCENE, 7, 0, 0, 0, 0, 8, 1, 1, *shapes(4, 1),
              SCENE, 7, 0, 0, 1, 0, 8, 1, 1, *camera(), 1,
              SCENE, 7, 0, 0, 2, 0, 8, 1, 1, *camera(), f(0), f(0),
              SCENE, 3, 0, 0, SCENE, 3, 0, 0, SCENE, 2, 1, 4, 4, 4, 4, 1, 0, 0],
    # snapshots: round trip, restore into the second world, mutated and re-sealed, raw bytes
    "snapshot": [2, *body(2), *body(0), *body(1, 5, 4, 4), SOFT_CREATE, 0, 1, 0, 2, 3, 0, *step(), *step(),
                 SNAP_ROUNDTRIP, 0, 0, 0, SNAP_ROUNDTRIP, 0, 1, 1,
                 SNAP_MUTATE, 0, 1, 2, 0, 40, 0, 0, 0, 0xFF, SNAP_MUTATE, 0, 1, 3, 0, 64, 0, 0, 4, 3, 0x11,
                 SNAP_MUTATE, 0, 1, 0, 0, 0, 0, 0, 6, *step(world=1),
                 RAW_BYTES, 1, 1, 24, 0, *range(24), RAW_BYTES, 1, 0, 16, 0, *b"GYROSNAP", *range(8)],
    # recording, replaying, a corrupted recording; raw bytes to replay; process settings
    "replay": [0, RECORD, 0, 0, *body(2), *body(0), *step(), *step(), RECORD, 0, 2, RECORD, 0, 3, 0, 1, 0, 200, 0, 0, 0, 0x55,
               RECORD, 0, 1, RAW_BYTES, 0, 3, 16, 0, *range(16), 1, 1,
               SETTINGS, 0, 1, 1, SETTINGS, 0, 4, 1, SETTINGS, 1, 2, SETTINGS, 2, 9, 0xF0,
               SETTINGS, 3, SETTINGS, 5, 0, *step()],
}

out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
os.makedirs(out, exist_ok=True)
for name, prog in seeds.items():
    with open(os.path.join(out, name), "wb") as fh:
        fh.write(bytes(prog))
print(f"{len(seeds)} seeds in {out}")
