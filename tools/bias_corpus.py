#!/usr/bin/env python3
"""The bias corpus (docs/techniques.md, "Bias"): `penumbra compare` on built-in scenes and the
glTF 2 models of Debian's assimp-testmodels, 480x270, a 2-degree sun where the scene has no
light of its own, once per bias setting; prints each technique's worst acne and leak beyond blur
over the corpus as a Markdown table.

    tools/bias_corpus.py [--penumbra BIN] [--set key=value ...] [--techniques LIST]
                         [--out DIR] [--samples N]
"""
import argparse
import json
import os
import subprocess
import sys

BUILTIN = ["showcase", "spot", "grazing", "room", "foliage", "demo", "figure", "bleeding"]
# Sun directions for the figure beyond its own: overhead and low.
EXTRA = [("figure-high", "builtin:figure", ["--sun-dir=-0.3,-0.95,0.1"]),
         ("figure-low", "builtin:figure", ["--sun-dir=0.9,-0.27,-0.3"])]
GLTF = "/usr/share/assimp/models/glTF2"
MODELS = ["2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "draco/2CylinderEngine.gltf",
          "ClearCoat-glTF/ClearCoatTest.gltf", "textureTransform/TextureTransformTest.gltf",
          "BoxTextured-glTF/BoxTextured.gltf"]


def scenes():
    for name in BUILTIN:
        yield name, "builtin:" + name, []
    yield from EXTRA
    for model in MODELS:
        path = os.path.join(GLTF, model)
        if os.path.exists(path):
            yield os.path.basename(model).split(".")[0] + ("-draco" if "draco/" in model else ""), \
                path, ["--light-angle", "2"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--penumbra", default="build/release/apps/penumbra/penumbra")
    ap.add_argument("--set", action="append", default=[], help="key=value for every run")
    ap.add_argument("--out", default="/tmp/bias-corpus")
    ap.add_argument("--samples", default="64")
    ap.add_argument("--techniques", help="compare's --techniques (default: every row)")
    args = ap.parse_args()
    worst = {}
    for label, scene, extra in scenes():
        out = os.path.join(args.out, label)
        cmd = [args.penumbra, "compare", scene, "-o", out, "--width", "480", "--height", "270",
               "--samples", args.samples] + extra
        for s in args.set:
            cmd += ["--set", s]
        if args.techniques:
            cmd += ["--techniques", args.techniques]
        print("corpus:", label, file=sys.stderr, flush=True)
        done = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if done.returncode != 0:
            print(f"corpus: {label}: {done.stderr.strip().splitlines()[-1]}", file=sys.stderr)
            continue
        with open(os.path.join(out, "metrics.json")) as f:
            metrics = json.load(f)["techniques"]
        for row, m in metrics.items():
            w = worst.setdefault(row, {"acne": (0, ""), "leak": (0, ""), "mis": (0, "")})
            for key, field in (("acne", "acne_beyond_blur"), ("leak", "leak_beyond_blur"),
                               ("mis", "misclassified_outside_edges")):
                if m[field] >= w[key][0]:
                    w[key] = (m[field], label)
    print("| technique | worst acne beyond blur | worst leak beyond blur "
          "| worst misclassified away from edges |")
    print("| --- | --- | --- | --- |")
    for row, w in worst.items():
        print(f"| {row} | " + " | ".join(f"{100 * w[k][0]:.3f}% ({w[k][1]})"
                                         for k in ("acne", "leak", "mis")) + " |")


if __name__ == "__main__":
    main()
