#!/usr/bin/env python3
"""The translucent layer's two methods against the coloured truth on generated scenes.

Each seed makes a glTF of its own: a grey ground under two to five coloured sheets at random
heights, sizes and places, each BLEND (alpha 0.3-0.9, some with transmission) or transmitting
(KHR_materials_transmission 0.5-1), lit by a sun, a spot or a point light (the seed picks, in
turn) from a random place. Each is rendered with hard shadows and translucent.method off,
coloured and moments, and measured against a one-ray truth (the lights have no size): the
luminance RMSE that `compare` reports. docs/translucency.md ("Which method") has a run.

    PYTHONPATH=build/release/python python3 tools/translucent_methods.py [--seeds 7300:7330]
"""
import argparse
import base64
import json
import random
import struct
import sys
import tempfile
from pathlib import Path

import numpy as np

import penumbra

METHODS = ("off", "coloured", "moments")


def sheet(lo, hi, y):
    (x0, z0), (x1, z1) = lo, hi
    positions = [(x0, y, z1), (x1, y, z1), (x1, y, z0), (x0, y, z0)]
    return positions, [(0.0, 1.0, 0.0)] * 4, [0, 1, 2, 0, 2, 3]


class Gltf:
    def __init__(self):
        self.buffer, self.views, self.accessors = bytearray(), [], []
        self.meshes, self.materials, self.nodes = [], [], []

    def view(self, data, target):
        self.views.append({"buffer": 0, "byteOffset": len(self.buffer),
                           "byteLength": len(data), "target": target})
        self.buffer.extend(data)
        self.buffer.extend(b"\0" * (-len(self.buffer) % 4))
        return len(self.views) - 1

    def accessor(self, data, target, count, kind, component, bounds=None):
        a = {"bufferView": self.view(data, target), "componentType": component, "count": count,
             "type": kind}
        if bounds:
            a["min"], a["max"] = bounds
        self.accessors.append(a)
        return len(self.accessors) - 1

    def mesh(self, positions, normals, indices, material):
        lo = [min(p[k] for p in positions) for k in range(3)]
        hi = [max(p[k] for p in positions) for k in range(3)]
        pack = lambda f, items: b"".join(struct.pack(f, *v) for v in items)
        primitive = {
            "attributes": {
                "POSITION": self.accessor(pack("<3f", positions), 34962, len(positions), "VEC3",
                                          5126, (lo, hi)),
                "NORMAL": self.accessor(pack("<3f", normals), 34962, len(normals), "VEC3", 5126)},
            "indices": self.accessor(pack("<I", [(i,) for i in indices]), 34963, len(indices),
                                     "SCALAR", 5125),
            "material": material}
        self.meshes.append({"primitives": [primitive]})
        self.nodes.append({"mesh": len(self.meshes) - 1})

    def document(self, light):
        self.nodes.append({"extensions": {"KHR_lights_punctual": {"light": 0}},
                           "translation": [0, 6, 0]})
        uri = "data:application/octet-stream;base64," + base64.b64encode(self.buffer).decode()
        return {"asset": {"version": "2.0"},
                "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission"],
                "extensions": {"KHR_lights_punctual": {"lights": [light]}},
                "scene": 0, "scenes": [{"nodes": list(range(len(self.nodes)))}],
                "nodes": self.nodes, "meshes": self.meshes, "materials": self.materials,
                "accessors": self.accessors, "bufferViews": self.views,
                "buffers": [{"byteLength": len(self.buffer), "uri": uri}]}


def generated(seed, folder):
    """The seed's scene (a .gltf in folder), its light's kind and the seed's generator."""
    rng = random.Random(seed)
    g = Gltf()
    g.materials.append({"pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1.0]}})
    g.mesh(*sheet((-8, -8), (8, 8), 0.0), 0)
    for _ in range(rng.randint(2, 5)):
        colour = [rng.uniform(0.1, 1.0) for _ in range(3)] + [1.0]
        m = {"pbrMetallicRoughness": {"baseColorFactor": colour}, "doubleSided": True}
        transmission = {"KHR_materials_transmission": {"transmissionFactor": 0.0}}
        if rng.random() < 0.5:
            m["alphaMode"], colour[3] = "BLEND", rng.uniform(0.3, 0.9)
            if rng.random() < 0.5:
                m["extensions"] = transmission
        else:
            m["extensions"] = transmission
        transmission["KHR_materials_transmission"]["transmissionFactor"] = rng.uniform(0.5, 1.0)
        g.materials.append(m)
        cx, cz, hx, hz = (rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(0.7, 2),
                          rng.uniform(0.7, 2))
        g.mesh(*sheet((cx - hx, cz - hz), (cx + hx, cz + hz), rng.uniform(0.6, 3.5)),
               len(g.materials) - 1)
    kind = ("directional", "spot", "point")[seed % 3]
    light = {"type": kind, "name": "L", "intensity": 3.0 if kind == "directional" else 60.0}
    if kind == "spot":
        light["spot"] = {"innerConeAngle": 0.8, "outerConeAngle": 1.1}
    path = Path(folder) / f"sheets-{seed}.gltf"
    path.write_text(json.dumps(g.document(light)))
    return path, kind, rng


def measure(seed, folder, width, height, map_size, validation=False):
    path, kind, rng = generated(seed, folder)
    scene = penumbra.Scene.load(str(path))
    towards = (rng.uniform(-0.6, 0.6), -1.0, rng.uniform(-0.6, 0.6))
    if kind == "directional":
        scene.edit(sun_dir=towards)
    else:
        place = (rng.uniform(-1.5, 1.5), rng.uniform(5, 7), rng.uniform(-1.5, 1.5))
        scene.edit(light_pos={"L": place}, light_dir={"L": towards} if kind == "spot" else {})
    scene.edit(camera_pos=(0, 9, 7), look_at=(0, 0, 0))
    renderer = penumbra.Renderer(scene, width, height, shadow_map_size=map_size,
                                 validation=validation)
    truth = renderer.reference(samples=1)
    return kind, [penumbra.metrics(renderer.render("hard", params={"translucent.method": m},
                                                   frames=1), truth)["rmse"] for m in METHODS]


def arguments(argv=None):
    """The command line; its defaults are the run docs/translucency.md reports."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="7300:7330", help="FIRST:END (END excluded)")
    parser.add_argument("--width", type=int, default=256)
    parser.add_argument("--height", type=int, default=192)
    parser.add_argument("--shadow-map-size", type=int, default=1024,
                        help="1024: a sun's moments at 2048 pass lavapipe's budget")
    parser.add_argument("--validation", action="store_true",
                        help="run the Khronos validation layer (its messages are errors)")
    return parser.parse_args(argv)


def main(argv=None):
    args = arguments(argv)
    first, end = (int(s) for s in args.seeds.split(":"))
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for seed in range(first, end):
            kind, errors = measure(seed, folder, args.width, args.height, args.shadow_map_size,
                                   args.validation)
            rows.append(errors)
            print(f"seed {seed} {kind:<11} " +
                  " ".join(f"{m} {e:.4f}" for m, e in zip(METHODS, errors)), flush=True)
    e = np.array(rows)
    coloured, moments = e[:, 1], e[:, 2]
    print(f"{len(e)} scenes, luminance RMSE mean / worst: " +
          ", ".join(f"{m} {e[:, i].mean():.4f} / {e[:, i].max():.4f}"
                    for i, m in enumerate(METHODS)))
    print(f"coloured better on {(coloured < moments - 1e-4).sum()}, moments on "
          f"{(moments < coloured - 1e-4).sum()}, within 1e-4 on "
          f"{(abs(coloured - moments) <= 1e-4).sum()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
