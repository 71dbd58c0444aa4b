#!/usr/bin/env python3
"""Writes a glTF scene for measuring virtual maps in motion over dense still geometry.

A ground with a grid of finely tessellated spheres (the still casters) and a small ball
(material "ball") that crosses it along x in four seconds (animation "move"), with a camera.
docs/techniques.md ("Static and dynamic casters") and docs/performance.md use it at its
defaults: 144 spheres of 2304 triangles, 331,778 still triangles, a ball of 576.

    python3 tools/heavy_static_scene.py -o /tmp/heavy
    penumbra render /tmp/heavy/heavy.gltf -o out --fps 10 --frames 8 --set virtual.enabled=1
"""
import argparse
import json
import math
import pathlib
import struct


def sphere(centre, radius, segments, rings):
    vertices, indices = [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            vertices.append((centre[0] + radius * math.sin(theta) * math.cos(phi),
                             centre[1] + radius * math.cos(theta),
                             centre[2] + radius * math.sin(theta) * math.sin(phi)))
    for i in range(rings):
        for j in range(segments):
            a = i * (segments + 1) + j
            b = a + segments + 1
            indices += [a, a + 1, b, a + 1, b + 1, b]
    return vertices, indices


def floats(values, fmt):
    return b"".join(struct.pack(fmt, *v) if isinstance(v, tuple) else struct.pack(fmt, v)
                    for v in values)


def bounds(points):
    return ([min(p[k] for p in points) for k in range(3)],
            [max(p[k] for p in points) for k in range(3)])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", required=True, help="directory for heavy.gltf/.bin")
    parser.add_argument("--spheres", type=int, default=12, help="spheres a side of the grid")
    parser.add_argument("--segments", type=int, default=48,
                        help="segments around each sphere (half as many rings)")
    args = parser.parse_args()
    if args.spheres < 1 or args.segments < 3:
        parser.error("--spheres must be at least 1 and --segments at least 3")

    half = 12.0
    still = [(-half, 0, -half), (half, 0, -half), (half, 0, half), (-half, 0, half)]
    still_indices = [0, 2, 1, 0, 3, 2]
    step = 2 * half / args.spheres
    for a in range(args.spheres):
        for b in range(args.spheres):
            centre = (-half + (a + 0.5) * step, 0.6, -half + (b + 0.5) * step)
            v, i = sphere(centre, 0.5, args.segments, args.segments // 2)
            still_indices += [k + len(still) for k in i]
            still += v
    ball, ball_indices = sphere((0, 0, 0), 0.3, 24, 12)
    times, places = [0.0, 4.0], [(-6.0, 1.8, 0.3), (6.0, 1.8, 0.3)]

    parts = [floats(still, "<3f"), floats(still_indices, "<I"), floats(ball, "<3f"),
             floats(ball_indices, "<I"), floats(times, "<f"), floats(places, "<3f")]
    views, blob = [], b""
    for part in parts:
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(part)})
        blob += part + b"\0" * ((-len(part)) % 4)
    still_lo, still_hi = bounds(still)
    ball_lo, ball_hi = bounds(ball)
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": len(still), "type": "VEC3",
         "min": still_lo, "max": still_hi},
        {"bufferView": 1, "componentType": 5125, "count": len(still_indices), "type": "SCALAR"},
        {"bufferView": 2, "componentType": 5126, "count": len(ball), "type": "VEC3",
         "min": ball_lo, "max": ball_hi},
        {"bufferView": 3, "componentType": 5125, "count": len(ball_indices), "type": "SCALAR"},
        {"bufferView": 4, "componentType": 5126, "count": 2, "type": "SCALAR",
         "min": [times[0]], "max": [times[-1]]},
        {"bufferView": 5, "componentType": 5126, "count": 2, "type": "VEC3"}]
    doc = {
        "asset": {"version": "2.0", "generator": "penumbra tools/heavy_static_scene.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0}, {"mesh": 1, "translation": list(places[0])},
                  {"camera": 0, "translation": [0, 9, 14], "rotation": [-0.2588, 0, 0, 0.9659]}],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 100}}],
        "materials": [{"name": "still"}, {"name": "ball"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": 2}, "indices": 3, "material": 1}]}],
        "animations": [{"name": "move",
                        "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}],
                        "samplers": [{"input": 4, "output": 5, "interpolation": "LINEAR"}]}],
        "buffers": [{"byteLength": len(blob), "uri": "heavy.bin"}],
        "bufferViews": views,
        "accessors": accessors}
    out = pathlib.Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    (out / "heavy.bin").write_bytes(blob)
    (out / "heavy.gltf").write_text(json.dumps(doc))
    print(f"wrote {out / 'heavy.gltf'}: {len(still_indices) // 3} still triangles, "
          f"{len(ball_indices) // 3} in the ball")


if __name__ == "__main__":
    main()
