#!/usr/bin/python3
"""One row of `penumbra compare`, reproduced from Python: the same scene, view, technique and
truth give the same metrics as compare's metrics.json (the GPU times aside).

    compare_row.py SCENE ROW [--width W] [--height H] [--shadow-map-size N] [--samples N]
                   [--light-radius R] [--light-angle DEG]

prints the row's metrics as JSON. Needs the module on the path: `make python` installs it.
"""
import argparse
import json

import penumbra

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("scene", help="builtin:NAME or a glTF file")
parser.add_argument("row", help="a technique or a compare row, e.g. pcf[box7]")
parser.add_argument("--width", type=int, default=1280)
parser.add_argument("--height", type=int, default=720)
parser.add_argument("--shadow-map-size", type=int, default=2048)
parser.add_argument("--samples", type=int, default=256)
parser.add_argument("--frames", type=int, default=5)
parser.add_argument("--light-radius", type=float)
parser.add_argument("--light-angle", type=float)
args = parser.parse_args()

# compare's steps: the scene, a renderer at the view's size, the row, the truth of the same view.
scene = penumbra.Scene.load(args.scene)
renderer = penumbra.Renderer(scene, args.width, args.height,
                             shadow_map_size=args.shadow_map_size,
                             light_radius=args.light_radius, light_angle=args.light_angle)
result = renderer.render(args.row, frames=args.frames)
truth = renderer.reference(samples=args.samples, gbuffer=result)
print(json.dumps(penumbra.metrics(result, truth), indent=2))
