#!/usr/bin/python3
"""Sweep pcf.size on a scene and plot its error against the truth over its GPU cost.

    sweep_pcf.py [SCENE]     (a glTF file or builtin:NAME; default builtin:demo)

writes pcf_sweep.png beside where it runs and prints one line per size.
"""
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt

import penumbra

scene = penumbra.Scene.load(sys.argv[1] if len(sys.argv) > 1 else "builtin:demo")
renderer = penumbra.Renderer(scene, 640, 360, shadow_map_size=2048)
truth = renderer.reference(samples=64)  # traced once, used by every setting

sizes, rmse, cost = [3, 5, 7, 9, 11, 15], [], []
for size in sizes:
    result = renderer.render("pcf", pcf_filter="box", pcf_size=size)
    m = penumbra.metrics(result, truth)
    rmse.append(m["rmse"])
    cost.append(m["gpu_ms"]["total"])
    print(f"pcf.size={size:2d}  RMSE {m['rmse']:.4f}  GPU {m['gpu_ms']['total']:.2f} ms")

plt.plot(cost, rmse, "o-")
for size, x, y in zip(sizes, cost, rmse):
    plt.annotate(f"size {size}", (x, y), textcoords="offset points", xytext=(4, 4))
plt.xlabel("GPU ms per frame (median)")
plt.ylabel("RMSE against the ray-traced truth")
plt.title(f"pcf box kernels on {scene.name}")
plt.savefig("pcf_sweep.png", dpi=120)
print("wrote pcf_sweep.png")
