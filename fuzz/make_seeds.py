#!/usr/bin/env python3
"""Writes the hand-picked seed corpus: fuzz/seeds/<target>/<name>.

Each seed is a mode byte (0 raw f32, 1 raw f64, 2 structured f32, 3
structured f64; see src/lib.rs) followed by the target's input in raw mode:
floats as little-endian bit patterns, in the order the target reads them.
Run it from fuzz/ after changing a target's input layout; the seeds are
checked in, so CI does not need Python.
"""
import math
import os
import struct

NAN, INF = float("nan"), float("inf")
SUB32 = struct.unpack("<f", struct.pack("<I", 1))[0]  # smallest f32 subnormal
MAX32 = struct.unpack("<f", struct.pack("<I", 0x7F7FFFFF))[0]


def raw(mode, *parts):
    """mode 0: f32, 1: f64; parts are floats, or ('u32', n) for integers."""
    out = bytes([mode])
    for p in parts:
        if isinstance(p, tuple):
            out += struct.pack("<I", p[1])
        else:
            out += struct.pack("<f" if mode == 0 else "<d", p)
    return out


def vecs(*vs):
    return [c for v in vs for c in v]


def write(target, name, data):
    d = os.path.join("seeds", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def structured(target):
    # Structured mode from a few byte patterns: libFuzzer mutates from here.
    for name, fill in [("zeros", 0x00), ("mid", 0x80), ("ones", 0xFF), ("mixed", 0x5A)]:
        write(target, f"structured-f32-{name}", bytes([2]) + bytes([fill]) * 160)
        write(target, f"structured-f64-{name}", bytes([3]) + bytes([fill]) * 160)


# Boxes: box min, max, ray origin, dir, t_max.
UNIT = [(0, 0, 0), (1, 1, 1)]
boxes = {
    "axis-parallel-hit": vecs(*UNIT, (-1, 0.5, 0.5), (1, 0, 0)) + [INF],
    "in-face-plane": vecs(*UNIT, (-1, 1, 0.5), (1, 0, 0)) + [INF],
    "on-slab-plane-negzero": vecs(*UNIT, (-1, 0, 0.5), (1, -0.0, -0.0)) + [INF],
    "through-edge": vecs(*UNIT, (-1, -1, 0.5), (1, 1, 0)) + [INF],
    "through-corner": vecs(*UNIT, (-1, -1, -1), (1, 1, 1)) + [INF],
    "starts-inside": vecs(*UNIT, (0.5, 0.5, 0.5), (0.3, -0.2, 0.1)) + [INF],
    "zero-thickness": vecs((0, 0, 0), (1, 0, 1), (0.5, -1, 0.5), (0, 1, 0)) + [INF],
    "point-box": vecs((1, 1, 1), (1, 1, 1), (0, 0, 0), (1, 1, 1)) + [INF],
    "inverted": vecs((1, 1, 1), (0, 0, 0), (-1, 0.5, 0.5), (1, 0, 0)) + [INF],
    "t-max-zero": vecs(*UNIT, (0.5, 0.5, 0.5), (1, 0, 0)) + [0.0],
    "t-max-nan": vecs(*UNIT, (-1, 0.5, 0.5), (1, 0, 0)) + [NAN],
    "subnormal-dir": vecs(*UNIT, (0.5, 0.5, -1), (SUB32, 0, 1)) + [INF],
    "huge-dir": vecs(*UNIT, (0.5, 0.5, -1), (0, 0, MAX32)) + [INF],
    "nan-origin": vecs(*UNIT, (NAN, 0.5, 0.5), (1, 0, 0)) + [INF],
    "inf-box": vecs((-INF, 0, 0), (INF, 1, 1), (-1, 0.5, 0.5), (1, 0, 0)) + [INF],
    "zero-dir": vecs(*UNIT, (0.5, 0.5, 0.5), (0, 0, 0)) + [INF],
}
for target in ["aabb", "aabb_slab_vs_naive"]:
    for name, xs in boxes.items():
        write(target, f"raw-f32-{name}", raw(0, *xs))
        write(target, f"raw-f64-{name}", raw(1, *xs))
    structured(target)

# Planes: point, normal, ray origin, dir, t_max.
planes = {
    "straight-down": vecs((0, 0, 0), (0, 1, 0), (0, 3, 0), (1, -2, 0)) + [INF],
    "parallel": vecs((0, 0, 0), (0, 1, 0), (0, 1, 0), (1, 0, 0)) + [INF],
    "in-plane": vecs((0, 0, 0), (0, 1, 0), (0, 0, 0), (1, 0, 0)) + [INF],
    "on-plane-leaving": vecs((0, 0, 0), (0, 1, 0), (0, 0, 0), (0, 1, 0)) + [INF],
    "zero-normal": vecs((0, 0, 0), (0, 0, 0), (0, 1, 0), (0, -1, 0)) + [INF],
    "t-max-exact": vecs((0, 0, 2), (0, 0, 1), (0, 0, 0), (0, 0, 1)) + [2.0],
    "grazing": vecs((64, 64, 64), (0, 4, -3.9999995), (0, 19, 19), (0, -4, -4)) + [INF],
    "tiny": vecs((SUB32, 0, 0), (1, 0, 0), (0, 0, 0), (SUB32, 0, 0)) + [INF],
    "huge": vecs((MAX32, 0, 0), (1, 0, 0), (-MAX32, 0, 0), (1, 0, 0)) + [INF],
}
for name, xs in planes.items():
    write("plane", f"raw-f32-{name}", raw(0, *xs))
    write("plane", f"raw-f64-{name}", raw(1, *xs))
structured("plane")

# Triangles: a, b, c, ray origin, dir, t_max.
TRI = [(0, 0, 0), (2, 0, 0), (0, 2, 0)]
tris = {
    "interior": vecs(*TRI, (0.5, 0.25, 4), (0, 0, -2)) + [INF],
    "edge": vecs(*TRI, (1, 1, 4), (0, 0, -1)) + [INF],
    "vertex": vecs(*TRI, (0, 0, 4), (0, 0, -1)) + [INF],
    "edge-on": vecs(*TRI, (-1, 0.5, 0), (1, 0, 0)) + [INF],
    "degenerate": vecs((0, 0, 0), (1, 1, 1), (2, 2, 2), (0, 1, -1), (0, 0, 1)) + [INF],
    "coincident": vecs((1, 1, 1), (1, 1, 1), (1, 1, 1), (1, 1, 0), (0, 0, 1)) + [INF],
    "origin-on-triangle": vecs(*TRI, (0.5, 0.5, 0), (0, 0, 1)) + [INF],
    "oblique": vecs((0, 0, 3), (1, 0, 3), (0, 1, 3.1), (0, 0, 0), (0.1, 0.2, 1)) + [INF],
    "far-sliver": vecs((1e6, 0, 0), (1e6, 1, 0), (1e6, 2, 1e-3), (0, 0.5, 0), (1, 0, 0)) + [INF],
    "t-max-zero": vecs(*TRI, (0.5, 0.25, 4), (0, 0, -2)) + [0.0],
    "nan": vecs(*TRI, (NAN, 0.25, 4), (0, 0, -2)) + [INF],
    "subnormal-dir": vecs(*TRI, (0.5, 0.25, 4), (SUB32, SUB32, -SUB32)) + [INF],
}
for target in ["triangle", "triangle_watertight_vs_mt"]:
    for name, xs in tris.items():
        write(target, f"raw-f32-{name}", raw(0, *xs))
        write(target, f"raw-f64-{name}", raw(1, *xs))
    structured(target)

# Spawn: triangle, ray, new dir; plane, ray, new dir; then point,
# point error, normal, normal error, dir for a direct call.
spawns = {
    "bounce-back": vecs(*TRI, (0.5, 0.25, 4), (0, 0, -2), (0.3, 0.1, 1))
    + vecs((0, 0, 0), (0, 1, 0), (0.1, 3, 0.2), (0.3, -1, 0.7), (0.3, 1, 0.7))
    + vecs((1, 0, 0), (1e-7, 1e-7, 1e-7), (0, 0, 1), (0, 0, 0), (0, 0, 1)),
    "transmit": vecs(*TRI, (0.5, 0.25, 4), (0, 0, -2), (0.3, 0.1, -1))
    + vecs((0, 0, 0), (0, 1, 0), (0.1, 3, 0.2), (0.3, -1, 0.7), (0.3, -1, 0.7))
    + vecs((1, 0, 0), (0, 0, 0), (0, 0, 1), (0, 0, 0), (0, 0, -1)),
    "grazing": vecs(*TRI, (1, 1, 4), (0, 0, -1), (1, 0, 1e-7))
    + vecs((0, 0, 0), (3, 1, 0), (0, 3, 0), (0, -1, 0), (1, -3, 1e-6))
    + vecs((0, 0, 0), (0, 0, 0), (0, 0, 1), (0, 0, 0), (1, 0, 0)),
    "vertex-at-origin": vecs(*TRI, (0, 0, 4), (0, 0, -1), (0, 0, 1))
    + vecs((0, 0, 0), (0, 0, 1), (0, 0, 1), (0, 0, -1), (0, 0, 1))
    + vecs((NAN, 0, 0), (0, 0, 0), (0, 0, 1), (0, 0, 0), (0, 0, 1)),
}
for name, xs in spawns.items():
    write("spawn", f"raw-f32-{name}", raw(0, *xs))
    write("spawn", f"raw-f64-{name}", raw(1, *xs))
structured("spawn")

# Camera: eye, view, up, focal, fov, width, height, x, y, i, j.
def cam(mode, eye, view, up, focal, fov, w, h, x, y, i, j):
    return raw(mode, *vecs(eye, view, up), focal, fov, ("u32", w), ("u32", h), x, y, ("u32", i), ("u32", j))

cams = {
    "centre": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1.5, math.pi / 2, 3, 3, 1.5, 1.5, 1, 1),
    "corner": ((0, 1, 5), (0, 0, -1), (0, 1, 0), 240, math.radians(60), 640, 480, 0, 0, 639, 479),
    "up-parallel": ((0, 0, 0), (0, 1, 0), (0, 2, 0), 1, 1, 4, 4, 2, 2, 0, 0),
    "up-oblique": ((1, 2, 3), (1, -1, 0.5), (0.2, 1, 7), 100, 0.5, 101, 51, 50.5, 25.5, 50, 25),
    "empty-image": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1, 1, 0, 1, 0, 0, 0, 0),
    "huge-focal": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1e30, 1e-30, 3, 3, 1.5, 1.5, 1, 1),
    "tiny-view": ((0, 0, 0), (SUB32, 0, 0), (0, 1, 0), 1, 1, 3, 3, 1.5, 1.5, 1, 1),
    "nan-position": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1, 1, 3, 3, NAN, INF, 0xFFFFFFFF, 0),
    "fov-pi": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1, math.pi, 3, 3, 1, 1, 1, 1),
}
for name, args in cams.items():
    write("camera", f"raw-f32-{name}", cam(0, *args))
    write("camera", f"raw-f64-{name}", cam(1, *args))
structured("camera")


# Batches: a layout byte (bit 0 triangles, bit 1 sixteen lanes, the rest the
# number of filled lanes), t_max, ray origin, dir, then the shapes.
def batch(mode, triangles, sixteen, shapes, origin, direction, t_max=INF):
    layout = (1 if triangles else 0) | (2 if sixteen else 0) | (len(shapes) << 2)
    floats = [t_max] + list(origin) + list(direction) + [c for s in shapes for v in s for c in v]
    return bytes([mode, layout]) + raw(mode, *floats)[1:]


ROW = [[(2 * i, 0, 0), (2 * i + 1, 1, 1)] for i in range(8)]
HEX = [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0) for k in range(7)]
FAN = [[(0, 0, 0), HEX[k], HEX[k + 1]] for k in range(6)]
batches = {
    "boxes-row-along": (False, False, ROW, (-1, 0.5, 0.5), (1, 0, 0)),
    "boxes-row-in-face": (False, True, ROW + ROW, (-1, 1, 0.5), (1, 0, 0)),
    "boxes-row-corner": (False, False, ROW[:3], (-1, -1, -1), (1, 1, 1)),
    "triangles-fan-centre": (True, False, FAN, (0, 0, 1), (0, 0, -1)),
    "triangles-fan-edge": (True, True, FAN, (0.5, 0, 1), (0, 0, -1)),
    "triangles-fan-edge-on": (True, False, FAN, (-2, 0, 0), (1, 0, 0)),
}
for name, (tri, sixteen, shapes, o, d) in batches.items():
    write("batch", f"raw-f32-{name}", batch(0, tri, sixteen, shapes, o, d))
    write("batch", f"raw-f64-{name}", batch(1, tri, sixteen, shapes, o, d))
for name, fill in [("zeros", 0x00), ("mid", 0x80), ("ones", 0xFF), ("mixed", 0x5A)]:
    for layout in (0x21, 0x22, 0x3F):
        write("batch", f"structured-f32-{name}-{layout:02x}", bytes([2, layout]) + bytes([fill]) * 400)
        write("batch", f"structured-f64-{name}-{layout:02x}", bytes([3, layout]) + bytes([fill]) * 400)


# Thin lens: eye, view, up, focal, width, height, radius, focal distance,
# x, y, then two lens samples (s, t).
def thin_lens(mode, eye, view, up, focal, w, h, radius, distance, x, y, lens):
    samples = [c for st in lens for c in st]
    return raw(mode, *vecs(eye, view, up), focal, ("u32", w), ("u32", h), radius, distance, x, y, *samples)

lenses = {
    "centre-sample": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 8, 3, 3, 1, 4, 1.5, 1.5, [(0.5, 0.5), (1, 0.5)]),
    "corners": ((1, 2, 3), (0.3, -1, 0.2), (0, 1, 0), 500, 640, 480, 0.05, 10, 320.5, 0.5, [(0, 0), (0.99999994, 0.99999994)]),
    "zero-radius": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 100, 64, 64, 0, 3, 10, 10, [(0.1, 0.9), (0.5, 0.5)]),
    "far-eye": ((1e5, -3e4, 2e5), (1, 0, 0), (0, 0, 1), 1000, 1920, 1080, 0.5, 30, 0.5, 1079.5, [(0.3, 0.7), (0.75, 0.25)]),
    "focus-near-zero": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 100, 200, 200, 2, 1, 100.5, 100.5, [(0.9, 0.5), (0.5, 0.1)]),
    "negative-radius": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1, 3, 3, -1, 1, 1.5, 1.5, [(0.5, 0.5), (0, 0)]),
    "nan-distance": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1, 3, 3, 1, NAN, 1.5, 1.5, [(0.5, 0.5), (0, 0)]),
    "huge-radius": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1, 3, 3, MAX32, 1, 1.5, 1.5, [(0.2, 0.5), (0, 0)]),
    "outside-samples": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 10, 8, 8, 1, 5, -3, 20, [(-2, 7), (NAN, 0.5)]),
}
for name, args in lenses.items():
    write("thin_lens", f"raw-f32-{name}", thin_lens(0, *args))
    write("thin_lens", f"raw-f64-{name}", thin_lens(1, *args))
structured("thin_lens")


# Orthographic: centre, view, up, pixel size, width, height, x, y.
def ortho(mode, centre, view, up, size, w, h, x, y):
    return raw(mode, *vecs(centre, view, up), size, ("u32", w), ("u32", h), x, y)

orthos = {
    "down": ((0, 10, 0), (0, -1, 0), (0, 0, -1), 0.5, 4, 2, 0.5, 0.5),
    "far-centre": ((1e6, 2e6, -3e6), (1, 1, 1), (0, 0, 1), 0.001, 1920, 1080, 960, 540),
    "zero-size": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 0, 4, 4, 1, 1),
    "huge-size": ((0, 0, 0), (0, 0, -1), (0, 1, 0), MAX32, 4, 4, -1e30, 1e30),
    "nan-position": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 1, 4, 4, NAN, INF),
    "up-parallel": ((0, 0, 0), (0, 0, -1), (0, 0, 2), 1, 4, 4, 1, 1),
}
for name, args in orthos.items():
    write("orthographic", f"raw-f32-{name}", ortho(0, *args))
    write("orthographic", f"raw-f64-{name}", ortho(1, *args))
structured("orthographic")


# Panoramas: eye, view, up, width, height, x, y, then a direction.
def pano(mode, eye, view, up, w, h, x, y, d):
    return raw(mode, *vecs(eye, view, up), ("u32", w), ("u32", h), x, y, *d)

panos = {
    "centre": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 361, 181, 180.5, 90.5, (0, 0, -1)),
    "poles": ((1, 2, 3), (1, 0, 0), (0, 1, 0), 360, 180, 0.5, 0.0, (0, 1, 0)),
    "edges": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 256, 256, 256.0, 256.0, (0, 0, 1)),
    "outside": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 64, 64, -1e6, 1e7, (1e-30, 0, 0)),
    "nan": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 64, 32, NAN, 3, (NAN, 0, 1)),
    "inf": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 64, 32, INF, -INF, (INF, 0, 1)),
    "zero-dir": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 8, 8, 4, 4, (0, 0, 0)),
    "empty": ((0, 0, 0), (0, 0, -1), (0, 1, 0), 0, 8, 4, 4, (0, 0, 1)),
}
for target in ["equirectangular", "equal_area"]:
    for name, args in panos.items():
        write(target, f"raw-f32-{name}", pano(0, *args))
        write(target, f"raw-f64-{name}", pano(1, *args))
    structured(target)


# Matrix camera: view and projection (32 floats, columns), a clip-space
# byte, width, height, x, y.
def matrix_cam(mode, view, proj, clip, w, h, x, y):
    floats = raw(mode, *[c for m in (view, proj) for col in m for c in col])
    return floats + bytes([clip]) + raw(mode, ("u32", w), ("u32", h), x, y)[1:]

I4 = [(1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)]
# glam's directx perspective_rh(fov = 1, aspect = 1, near 0.1, far 100).
F = 1 / math.tan(0.5)
PERSP = [(F, 0, 0, 0), (0, F, 0, 0), (0, 0, 100 / (0.1 - 100), -1), (0, 0, 0.1 * 100 / (0.1 - 100), 0)]
# directx orthographic_rh(-2, 2, -1, 1, 1, 21).
ORTHO = [(0.5, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1 / (1 - 21), 0), (0, 0, 1 / (1 - 21), 1)]
mats = {
    "perspective": (I4, PERSP, 0, 64, 64, 31.5, 10.5),
    "orthographic": (I4, ORTHO, 0, 4, 2, 0.5, 0.5),
    "vulkan": (I4, PERSP, 2, 64, 48, 0.5, 47.5),
    "zero": (I4, [(0, 0, 0, 0)] * 4, 1, 8, 8, 4, 4),
    "nan": (I4, [(NAN, 0, 0, 0)] + PERSP[1:], 0, 8, 8, 4, 4),
    "huge": ([(MAX32, 0, 0, 0), (0, MAX32, 0, 0), (0, 0, MAX32, 0), (0, 0, 0, 1)], PERSP, 0, 8, 8, -1e30, 1e30),
    "far-outside": (I4, PERSP, 1, 8, 8, 1e38, -3e38),
}
for name, args in mats.items():
    write("matrix_camera", f"raw-f32-{name}", matrix_cam(0, *args))
    write("matrix_camera", f"raw-f64-{name}", matrix_cam(1, *args))
structured("matrix_camera")


# Hit differentials: ray direction, dx origin, dx dir, dy origin, dy dir,
# triangle a, b, c, then t.
hits = {
    "floor": ((0, -1, 0), (0, 0, 0), (0.01, 0, 0), (0, 0, 0), (0, 0, 0.01), (-50, -10, 50), (50, -10, 50), (-50, -10, -50), 10),
    "ortho": ((0, 0, -1), (0.5, 0, 0), (0, 0, 0), (0, -0.5, 0), (0, 0, 0), (0, 0, -3), (4, 0, -3), (0, 4, -3), 3),
    "parallel": ((1, 0, 0), (0, 0, 0), (0, 1, 0), (0, 0, 0), (0, 0, 1), (0, 0, 0), (1, 0, 0), (0, 1, 0), 1),
    "degenerate": ((0, 0, -1), (0, 0, 0), (1, 0, 0), (0, 0, 0), (0, 1, 0), (0, 0, 0), (1, 1, 1), (2, 2, 2), 1),
    "grazing": ((1, 0, -1e-7), (0, 0, 0), (0, 0.001, 0), (0, 0, 0), (0, 0, 0.001), (0, -1, 0), (0, 1, 0), (1000, 0, -1e-4), 5),
    "nan": ((0, 0, -1), (NAN, 0, 0), (0, 0, 0), (0, 0, 0), (0, 0, 0), (0, 0, -1), (1, 0, -1), (0, 1, -1), INF),
}
for name, args in hits.items():
    *vs, t = args
    write("hit_differentials", f"raw-f32-{name}", raw(0, *vecs(*vs), t))
    write("hit_differentials", f"raw-f64-{name}", raw(1, *vecs(*vs), t))
structured("hit_differentials")

# Instance: the matrix's columns and translation, an object box (min,
# max), a world ray (origin, dir).
BOX = ((-1, -1, -1), (1, 1, 1))
RAY = ((0.5, 3, 0.25), (0, -1, 0))
insts = {
    "identity": ((1, 0, 0), (0, 1, 0), (0, 0, 1), (0, 0, 0)),
    "far-rotated": ((0.6, 0.8, 0), (-0.8, 0.6, 0), (0, 0, 1), (1e5, -3e4, 7)),
    "anisotropic-shear": ((1e3, 0, 0), (0.5, 1e-3, 0), (2, 0, 1), (0, 1e4, 0)),
    "singular": ((1, 2, 3), (2, 4, 6), (0, 0, 1), (0, 0, 0)),
    "nan": ((NAN, 0, 0), (0, 1, 0), (0, 0, 1), (0, 0, 0)),
}
for name, m in insts.items():
    write("instance", f"raw-f32-{name}", raw(0, *vecs(*m, *BOX, *RAY)))
    write("instance", f"raw-f64-{name}", raw(1, *vecs(*m, *BOX, *RAY)))
structured("instance")


# Spheres: ray origin, dir, sphere centre, radius, t_max, then the
# interval's ends lo, hi.
spheres = {
    "through-centre": vecs((0, 0, -5), (0, 0, 2), (0, 0, 0)) + [1, INF, 0, INF],
    "tangent": vecs((-2, 1, 0), (1, 0, 0), (0, 0, 0)) + [1, INF, 0, INF],
    "just-outside": vecs((-2, 1.0000001, 0), (1, 0, 0), (0, 0, 0)) + [1, INF, 0, INF],
    "from-inside": vecs((0.25, -0.5, 0.125), (0.3, 0.2, -0.7), (0, 0, 0)) + [1, INF, 0, INF],
    "on-surface-leaving": vecs((1, 0, 0), (1, 0, 0), (0, 0, 0)) + [1, INF, 0, INF],
    "on-surface-entering": vecs((1, 0, 0), (-1, 0, 0), (0, 0, 0)) + [1, INF, 0, INF],
    "window-at-exit": vecs((-4, 0, 0), (1, 0, 0), (0, 0, 0)) + [2, 6, 2, 6],
    "t-max-at-entry": vecs((-4, 0, 0), (1, 0, 0), (0, 0, 0)) + [2, 2, 1.5, 2],
    "far": vecs((0, 0, 0), (0.6, 0.8, 0), (6e4, 8e4, 0)) + [0.01, INF, 0, INF],
    "negative-radius": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0)) + [-2, INF, 0, 3],
    "zero-radius": vecs((-1, 0, 0), (1, 0, 0), (0, 0, 0)) + [0, INF, 0, INF],
    "subnormal-dir": vecs((0, 0, 5), (0, 0, -SUB32), (0, 0, 0)) + [1, INF, 0, INF],
    "huge": vecs((-MAX32, 0, 0), (1, 0, 0), (MAX32, 0, 0)) + [MAX32, INF, 0, INF],
    "nan-radius": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0)) + [NAN, INF, 0, INF],
    "t-max-nan": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0)) + [1, NAN, NAN, 1],
}
for name, xs in spheres.items():
    write("sphere", f"raw-f32-{name}", raw(0, *xs))
    write("sphere", f"raw-f64-{name}", raw(1, *xs))
structured("sphere")


# Quads: ray origin, dir, corners a, b, c, d, t_max, then the interval's
# ends lo, hi.
SQUARE = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
quads = {
    "inside": vecs((0.25, 0.75, 1), (0, 0, -1), *SQUARE) + [INF, 0, INF],
    "through-diagonal": vecs((0.5, 0.5, 1), (0, 0, -1), *SQUARE) + [INF, 0, INF],
    "on-edge": vecs((0.5, 0, 1), (0, 0, -1), *SQUARE) + [INF, 0, INF],
    "at-corner": vecs((1, 1, 1), (0, 0, -1), *SQUARE) + [INF, 0, INF],
    "folded": vecs((0.3, 0.6, 1), (0, 0, -1), (0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0.3)) + [INF, 0, INF],
    "collapsed-edge": vecs((0.5, 0.25, 1), (0, 0, -1), (0, 0, 0), (0, 0, 0), (1, 1, 0), (0, 1, 0)) + [INF, 0, INF],
    "grazing": vecs((-1, 0.5, 0), (1, 0, 0), *SQUARE) + [INF, 0, INF],
    "window-at-hit": vecs((0.25, 0.5, 1), (0, 0, -1), *SQUARE) + [1, 0.5, 1],
    "far": vecs((1e5 + 0.5, 1e5 + 0.5, 1), (0, 0, -1), (1e5, 1e5, 0), (1e5 + 1, 1e5, 0), (1e5 + 1, 1e5 + 1, 0), (1e5, 1e5 + 1, 0)) + [INF, 0, INF],
    "nan-corner": vecs((0.5, 0.5, 1), (0, 0, -1), (NAN, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)) + [INF, 0, INF],
    "t-max-nan": vecs((0.5, 0.5, 1), (0, 0, -1), *SQUARE) + [NAN, NAN, 1],
}
for name, xs in quads.items():
    write("quad", f"raw-f32-{name}", raw(0, *xs))
    write("quad", f"raw-f64-{name}", raw(1, *xs))
structured("quad")

# Patches: ray origin, dir, corners p00, p10, p01, p11, t_max, then the
# interval's ends lo, hi.
UNIT_PATCH = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
SADDLE = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 1)]
TWISTED = [(-1, -1, 1), (1, -1, -1), (-1, 1, -1), (1, 1, 1)]
patches = {
    "saddle-centre": vecs((0.5, 0.5, 3), (0, 0, -1), *SADDLE) + [INF, 0, INF],
    "saddle-twice": vecs((-1, -1, 0.25), (1, 1, 0), *TWISTED) + [INF, 0, INF],
    "saddle-second-crossing": vecs((-1, -1, 0.25), (1, 1, 0), *TWISTED) + [INF, 0.5, INF],
    "inside": vecs((0.25, 0.75, 1), (0, 0, -1), *UNIT_PATCH) + [INF, 0, INF],
    "through-diagonal": vecs((0.5, 0.5, 1), (0, 0, -1), *UNIT_PATCH) + [INF, 0, INF],
    "on-edge": vecs((0.5, 0, 1), (0, 0, -1), *UNIT_PATCH) + [INF, 0, INF],
    "at-corner": vecs((1, 1, 1), (0, 0, -1), *UNIT_PATCH) + [INF, 0, INF],
    "twisted-corner": vecs((1, 1, 3), (0, 0, -1), *SADDLE) + [INF, 0, INF],
    "collapsed-edge": vecs((0.25, 0.5, 1), (0, 0, -1), (0, 0, 0), (0, 0, 0), (0, 1, 0), (1, 1, 0.5)) + [INF, 0, INF],
    "collapsed-corner-hit": vecs((0, 1, 1), (0, 0, -1), (0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 1, 0)) + [INF, 0, INF],
    "point": vecs((0, 0, 1), (0, 0, -1), (0, 0, 0), (0, 0, 0), (0, 0, 0), (0, 0, 0)) + [INF, 0, INF],
    "bow-tie": vecs((0.5, 0.5, 1), (0, 0, -1), (0, 0, 0), (1, 1, 0), (0, 1, 0), (1, 0, 0)) + [INF, 0, INF],
    "grazing": vecs((-1, 0.5, 0), (1, 0, 0), *UNIT_PATCH) + [INF, 0, INF],
    "grazing-saddle": vecs((-1, 0.5, 0), (1, 0, 1e-7), *SADDLE) + [INF, 0, INF],
    "origin-on-patch": vecs((0.5, 0.5, 0.25), (0.3, 0.1, 1), *SADDLE) + [INF, 0, INF],
    "window-at-hit": vecs((0.25, 0.5, 1), (0, 0, -1), *UNIT_PATCH) + [1, 0.5, 1],
    "t-max-at-hit": vecs((0.5, 0.5, 3), (0, 0, -1), *SADDLE) + [2.75, 2.75, 3],
    "far": vecs((1e5 + 0.5, 1e5 + 0.5, 1), (0, 0, -1), (1e5, 1e5, 0), (1e5 + 1, 1e5, 0), (1e5, 1e5 + 1, 0), (1e5 + 1, 1e5 + 1, 0.5)) + [INF, 0, INF],
    "tiny": vecs((SUB32, SUB32, 1e-30), (0, 0, -1), (0, 0, 0), (4 * SUB32, 0, 0), (0, 4 * SUB32, 0), (4 * SUB32, 4 * SUB32, SUB32)) + [INF, 0, INF],
    "huge": vecs((0, 0, MAX32), (0, 0, -1), (-MAX32, -MAX32, 0), (MAX32, -MAX32, 0), (-MAX32, MAX32, 0), (MAX32, MAX32, MAX32)) + [INF, 0, INF],
    "nan-corner": vecs((0.5, 0.5, 1), (0, 0, -1), (NAN, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)) + [INF, 0, INF],
    "inf-corner": vecs((0.5, 0.5, 1), (0, 0, -1), (0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, INF)) + [INF, 0, INF],
    "t-max-nan": vecs((0.5, 0.5, 1), (0, 0, -1), *UNIT_PATCH) + [NAN, NAN, 1],
    "zero-dir": vecs((0.5, 0.5, 1), (0, 0, 0), *UNIT_PATCH) + [INF, 0, INF],
}
for name, xs in patches.items():
    write("patch", f"raw-f32-{name}", raw(0, *xs))
    write("patch", f"raw-f64-{name}", raw(1, *xs))
structured("patch")

# Discs: ray origin, dir, disc centre, normal, radius, inner radius,
# t_max, then the interval's ends lo, hi.
discs = {
    "through-centre": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 0, INF, 0, INF],
    "on-rim": vecs((1, 0, 1), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 0, INF, 0, INF],
    "on-hole-rim": vecs((0, 0.5, 1), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 0.5, INF, 0, INF],
    "in-hole": vecs((0.25, 0, 1), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 0.5, INF, 0, INF],
    "just-outside": vecs((1.0000001, 0, 1), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 0, INF, 0, INF],
    "ring-of-no-width": vecs((0.6, 0.8, 2), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 1, INF, 0, INF],
    "from-behind": vecs((0.3, 0.2, -2), (0.1, 0, 1), (0, 0, 0), (0, 0, 1)) + [1, 0, INF, 0, INF],
    "tilted": vecs((3, 2, 1), (-1, -0.5, -0.25), (0, 0, 0), (1, 2, 3)) + [2, 0.5, INF, 0, INF],
    "nearly-parallel": vecs((-2, 0, 1e-7), (1, 0, -1e-8), (0, 0, 0), (0, 0, 1)) + [1e3, 0, INF, 0, INF],
    "in-plane": vecs((-2, 0, 0), (1, 0, 0), (0, 0, 0), (0, 0, 1)) + [1, 0, INF, 0, INF],
    "from-the-plane": vecs((0.5, 0, 0), (0, 0.3, 1), (0, 0, 0), (0, 0, 1)) + [1, 0, INF, 0, INF],
    "window-at-crossing": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 0, 5, 5, 6],
    "t-max-at-crossing": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 0, 5, 4, 5],
    "far": vecs((0, 0, 0), (0.6, 0.8, 0), (6e4, 8e4, 0), (0.6, 0.8, 0)) + [0.01, 0, INF, 0, INF],
    "huge": vecs((-MAX32, 0, 0), (1, 0, 0), (0, 0, 0), (1, 0, 0)) + [MAX32, 0, INF, 0, INF],
    "tiny-normal": vecs((0, 0, 5), (0, 0.1, -1), (0, 0, 0), (SUB32, 0, 1e-30)) + [1, 0, INF, 0, INF],
    "zero-normal": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0), (0, 0, 0)) + [1, 0, INF, 0, INF],
    "negative-radii": vecs((0, 0.75, 5), (0, 0, -1), (0, 0, 0), (0, 0, -1)) + [-1, -0.5, INF, 0, INF],
    "hole-too-large": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 2, INF, 0, INF],
    "subnormal-dir": vecs((0, 0, 5), (0, 0, -SUB32), (0, 0, 0), (0, 0, 1)) + [1, 0, INF, 0, INF],
    "nan-radius": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [NAN, 0, INF, 0, INF],
    "inf-centre": vecs((0, 0, 5), (0, 0, -1), (INF, 0, 0), (0, 0, 1)) + [1, 0, INF, 0, INF],
    "t-max-nan": vecs((0, 0, 5), (0, 0, -1), (0, 0, 0), (0, 0, 1)) + [1, 0, NAN, NAN, 1],
}
for name, xs in discs.items():
    write("disc", f"raw-f32-{name}", raw(0, *xs))
    write("disc", f"raw-f64-{name}", raw(1, *xs))
structured("disc")
