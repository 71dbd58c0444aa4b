"""Shared set-up for the Python module's tests: where the module and the CLI are, a scratch
directory, a glTF asset with a sun, a spot and a bulb (every light type), and PFM reading."""
import base64
import json
import os
import struct
import subprocess
from pathlib import Path

import numpy as np
import pytest

CLI = os.environ.get("PENUMBRA_CLI", "penumbra")
# A small view from above the box, so every light's shadow of it is seen.
VIEW = {"camera_pos": (0, 9, 9), "look_at": (0, 0, 0)}
VIEW_ARGS = ["--camera-pos", "0,9,9", "--look-at", "0,0,0"]


def run_cli(*args):
    """Runs the CLI; returns stdout, failing the test with stderr on a non-zero exit."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def read_pfm(path):
    """A PFM file as a float32 array, rows top to bottom: (h, w) or (h, w, 3)."""
    data = Path(path).read_bytes()
    header, rest = data.split(b"\n", 1)
    size, rest = rest.split(b"\n", 1)
    scale, pixels = rest.split(b"\n", 1)
    width, height = map(int, size.split())
    channels = 3 if header == b"PF" else 1
    order = "<" if float(scale) < 0 else ">"
    image = np.frombuffer(pixels, dtype=order + "f4", count=width * height * channels)
    shape = (height, width) if channels == 1 else (height, width, 3)
    return image.reshape(shape)[::-1].astype(np.float32)


def same_bits(a, b):
    """Arrays equal bit for bit (NaN payloads included)."""
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def three_light_gltf(path):
    """A 10 x 10 ground and a 2-unit box under a sun, a spot and a point light named bulb (as
    tests/three_light_asset.h writes it for the C++ tests)."""
    binary = bytearray()
    views, accessors = [], []

    def add(values, fmt, component, count, kind, bounds=None):
        while len(binary) % 4:
            binary.append(0)
        views.append({"buffer": 0, "byteOffset": len(binary),
                      "byteLength": struct.calcsize("<" + fmt * len(values))})
        binary.extend(struct.pack("<" + fmt * len(values), *values))
        accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count,
                    "type": kind}
        if bounds:
            accessor["min"], accessor["max"] = bounds
        accessors.append(accessor)
        return len(accessors) - 1

    def mesh(xyz, indices):
        lo = [min(xyz[i::3]) for i in range(3)]
        hi = [max(xyz[i::3]) for i in range(3)]
        p = add(xyz, "f", 5126, len(xyz) // 3, "VEC3", (lo, hi))
        i = add(indices, "H", 5123, len(indices), "SCALAR")
        return {"primitives": [{"attributes": {"POSITION": p}, "indices": i, "mode": 4}]}

    ground = mesh([-5, 0, -5, 5, 0, -5, 5, 0, 5, -5, 0, 5], [0, 2, 1, 0, 3, 2])
    box = mesh([-1, 0, -1, 1, 0, -1, 1, 2, -1, -1, 2, -1, -1, 0, 1, 1, 0, 1, 1, 2, 1, -1, 2, 1],
               [0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 3, 7, 0, 7, 4,
                1, 5, 6, 1, 6, 2, 3, 2, 6, 3, 6, 7, 0, 4, 5, 0, 5, 1])
    light = lambda index, node: {**node, "extensions": {"KHR_lights_punctual": {"light": index}}}
    nodes = [{"mesh": 0}, {"mesh": 1},
             light(0, {"rotation": [-0.6, 0.2, 0.1, 0.77]}),
             light(1, {"translation": [3, 6, 3], "rotation": [-0.38, 0.2, 0.08, 0.9]}),
             light(2, {"translation": [-2, 3, 1]})]
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
        "nodes": nodes, "meshes": [ground, box], "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(binary), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(bytes(binary)).decode()}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "directional", "intensity": 1.5},
            {"type": "spot", "intensity": 40, "spot": {"outerConeAngle": 0.7}},
            {"type": "point", "name": "bulb", "intensity": 5}]}},
    }
    Path(path).write_text(json.dumps(gltf))
    return Path(path)


@pytest.fixture(scope="session")
def asset(tmp_path_factory):
    return three_light_gltf(tmp_path_factory.mktemp("asset") / "lights.gltf")
