"""Each kind of Scene.edit against the CLI's same option: the same lights (a light aimed keeps its
place, a light moved keeps its aim) and the same visibility and positions, bit for bit, for the
sun, the spot and the bulb of the three-light asset."""
import base64
import json
import math
import struct
from pathlib import Path

import pytest

import penumbra
from conftest import VIEW, VIEW_ARGS, read_pfm, run_cli, same_bits

W, H, MAP = 32, 24, 128

# (name, Scene.edit's keywords, the CLI's options); each without the fixed view where it sets one.
EDITS = [
    ("sun_dir", {"sun_dir": (0.3, -1.0, 0.2)}, ["--sun-dir", "0.3,-1,0.2"]),
    ("light_pos", {"light_pos": {"bulb": (0.5, 2.5, 0.5), "light1": (1.0, 4.0, 1.0)}},
     ["--light-pos", "bulb=0.5,2.5,0.5", "--light-pos", "light1=1,4,1"]),
    ("light_dir", {"light_dir": {"light1": (0.2, -1.0, 0.1), "light0": (-0.4, -1.0, 0.3)}},
     ["--light-dir", "light1=0.2,-1,0.1", "--light-dir", "light0=-0.4,-1,0.3"]),
    ("add_light", {"add_light": ["point:pos=1,2.5,1,radius=0.1", "sun:dir=0,-1,0.2"]},
     ["--add-light", "point:pos=1,2.5,1,radius=0.1", "--add-light", "sun:dir=0,-1,0.2"]),
    ("ground", {"ground": True}, ["--ground"]),
    ("double_sided", {"double_sided": True}, ["--double-sided"]),
]
VIEWS = [
    ("camera", {"camera_pos": (2.0, 7.0, 8.0), "look_at": (0.0, 0.5, 0.0), "fov": 40.0},
     ["--camera-pos", "2,7,8", "--look-at", "0,0.5,0", "--fov", "40"]),
    ("view", {"view": "exterior"}, ["--view", "exterior"]),
]


def render_both(asset, tmp_path, edit, args):
    scene = penumbra.Scene.load(str(asset))
    scene.edit(**edit)
    result = penumbra.Renderer(scene, W, H, shadow_map_size=MAP, validation=True).render(
        "hard", frames=1)
    run_cli("render", asset, "-o", tmp_path, "--technique", "hard", "--width", W, "--height", H,
            "--shadow-map-size", MAP, "--frames", 1, "--format", "pfm", *args)
    return scene, result


def assert_same_images(result, tmp_path, name):
    for i, v in enumerate(result.visibility):
        file = "visibility.pfm" if i == 0 else f"visibility_{i}.pfm"
        assert same_bits(v, read_pfm(tmp_path / file)), f"{name}: {file}"
    assert not (tmp_path / f"visibility_{len(result.visibility)}.pfm").exists(), name
    assert same_bits(result.position, read_pfm(tmp_path / "position.pfm")), name


@pytest.mark.parametrize("name,edit,args", EDITS, ids=[e[0] for e in EDITS])
def test_each_edit_renders_as_the_clis_same_option(asset, tmp_path, name, edit, args):
    scene, result = render_both(asset, tmp_path, {**VIEW, **edit}, [*VIEW_ARGS, *args])
    assert_same_images(result, tmp_path, name)
    assert [l["name"] for l in result.lights] == [l["name"] for l in scene.lights]


@pytest.mark.parametrize("name,edit,args", VIEWS, ids=[e[0] for e in VIEWS])
def test_each_view_edit_renders_as_the_clis_same_option(asset, tmp_path, name, edit, args):
    _, result = render_both(asset, tmp_path, edit, args)
    assert_same_images(result, tmp_path, name)


def by_name(scene):
    return {l["name"]: l for l in scene.lights}


def test_aiming_keeps_a_lights_place_and_moving_keeps_its_aim(asset):
    before = by_name(penumbra.Scene.load(str(asset)))
    aimed = penumbra.Scene.load(str(asset))
    aimed.edit(light_dir={"light1": (0.0, -2.0, 0.0), "light0": (3.0, -4.0, 0.0)})
    after = by_name(aimed)
    assert after["light1"]["position"] == pytest.approx(before["light1"]["position"])
    assert after["light1"]["direction"] == pytest.approx([0.0, -1.0, 0.0])
    assert after["light0"]["direction"] == pytest.approx([0.6, -0.8, 0.0]), "normalised"
    assert after["bulb"] == before["bulb"], "only the named lights"

    moved = penumbra.Scene.load(str(asset))
    moved.edit(light_pos={"light1": (1.0, 5.0, -1.0), "bulb": (0.0, 2.0, 0.0)})
    after = by_name(moved)
    assert after["light1"]["position"] == pytest.approx([1.0, 5.0, -1.0])
    assert after["light1"]["direction"] == pytest.approx(before["light1"]["direction"])
    assert after["bulb"]["position"] == pytest.approx([0.0, 2.0, 0.0])
    assert after["light0"] == before["light0"]

    added = penumbra.Scene.load(str(asset))
    added.edit(sun_dir=(0.0, -3.0, 4.0))
    lights = added.lights
    assert len(lights) == len(before) + 1
    assert lights[-1]["type"] == "directional"
    assert lights[-1]["direction"] == pytest.approx([0.0, -0.6, 0.8])
    assert math.isclose(sum(x * x for x in lights[-1]["direction"]), 1.0, rel_tol=1e-6)


def test_a_refused_edit_leaves_the_scene_as_it_was(asset):
    scene = penumbra.Scene.load(str(asset))
    before = scene.lights
    with pytest.raises(penumbra.InputError, match="--light-dir"):
        scene.edit(light_pos={"bulb": (0.0, 9.0, 0.0)}, light_dir={"nobody": (0.0, -1.0, 0.0)})
    assert scene.lights == before
    with pytest.raises(penumbra.InputError, match="--light-dir"):
        scene.edit(light_dir={"bulb": (0.0, -1.0, 0.0)})  # a point light has no aim
    assert scene.lights == before


def lone_box_gltf(path):
    """A 2-unit box with no ground, light or camera: a lone model the loader grounds."""
    xyz = [-1, 0, -1, 1, 0, -1, 1, 2, -1, -1, 2, -1, -1, 0, 1, 1, 0, 1, 1, 2, 1, -1, 2, 1]
    indices = [0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 7, 3, 0, 4, 7,
               1, 6, 5, 1, 2, 6, 3, 6, 2, 3, 7, 6, 0, 5, 4, 0, 1, 5]
    data = struct.pack(f"<{len(xyz)}f", *xyz) + struct.pack(f"<{len(indices)}H", *indices)
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
             "min": [-1, 0, -1], "max": [1, 2, 1]},
            {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 4 * len(xyz)},
                        {"buffer": 0, "byteOffset": 4 * len(xyz), "byteLength": 2 * len(indices)}],
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(data).decode()}],
    }
    Path(path).write_text(json.dumps(gltf))
    return Path(path)


def test_the_automatic_ground_is_the_clis_and_no_ground_holds_for_later_edits(tmp_path):
    box = lone_box_gltf(tmp_path / "lone.gltf")
    grounded = penumbra.Scene.load(str(box))
    assert grounded.triangles == 14
    assert any("added a ground under 'lone'" in w for w in grounded.warnings)
    bare = penumbra.Scene.load(str(box), no_ground=True)
    assert bare.triangles == 12
    assert not any("added a ground" in w for w in bare.warnings)
    bare.edit(sun_dir=(0.3, -1.0, 0.2))  # a later edit keeps the load's no_ground
    assert bare.triangles == 12
    bare.edit(ground=True)  # an explicit ground is still the user's to add
    assert bare.triangles == 14
    result = penumbra.Renderer(grounded, W, H, shadow_map_size=MAP, validation=True).render(
        "hard", frames=1)
    run_cli("render", box, "-o", tmp_path / "cli", "--technique", "hard", "--width", W,
            "--height", H, "--shadow-map-size", MAP, "--frames", 1, "--format", "pfm")
    assert same_bits(result.visibility[0], read_pfm(tmp_path / "cli" / "visibility.pfm"))


def animated_asset(asset, path):
    """The three-light asset with one animation, 'carry': the bulb (node 4) slides from
    (-2, 3, 1) to (2, 3, 1) over the first second."""
    gltf = json.loads(Path(asset).read_text())
    uri = gltf["buffers"][0]["uri"]
    head, data = uri.split(",", 1)
    binary = bytearray(base64.b64decode(data))
    for values, kind in (([0.0, 1.0], "SCALAR"), ([-2, 3, 1, 2, 3, 1], "VEC3")):
        while len(binary) % 4:
            binary.append(0)
        gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(binary),
                                    "byteLength": 4 * len(values)})
        binary.extend(struct.pack("<%df" % len(values), *values))
        gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 1,
                                  "componentType": 5126, "type": kind,
                                  "count": 2, "min": values[:1] if kind == "SCALAR" else None})
        if gltf["accessors"][-1]["min"] is None:
            del gltf["accessors"][-1]["min"]
        else:
            gltf["accessors"][-1]["max"] = values[-1:]
    n = len(gltf["accessors"])
    gltf["animations"] = [{"name": "carry",
                           "channels": [{"sampler": 0,
                                         "target": {"node": 4, "path": "translation"}}],
                           "samplers": [{"input": n - 2, "output": n - 1}]}]
    gltf["buffers"][0] = {"byteLength": len(binary),
                          "uri": head + "," + base64.b64encode(bytes(binary)).decode()}
    Path(path).write_text(json.dumps(gltf))
    return str(path)


def test_time_poses_an_animated_scene_as_the_clis_time_does(asset, tmp_path):
    path = animated_asset(asset, tmp_path / "carry.gltf")
    rest = penumbra.Scene.load(path)
    assert rest.time is None and rest.animation == "carry" and rest.animation_duration == 1.0
    assert any("drawn at rest" in w for w in rest.warnings)
    bulb = lambda scene: next(l for l in scene.lights if l["name"] == "bulb")
    assert bulb(rest)["position"] == pytest.approx([-2, 3, 1])
    for t, x in ((0.25, -1.0), (0.5, 0.0), (3.0, 2.0)):
        posed = penumbra.Scene.load(path, time=t, animation="carry")
        assert posed.time == t
        assert bulb(posed)["position"] == pytest.approx([x, 3, 1], abs=1e-6)
    # The CLI's --time moves the same light: the same shadow images.
    posed = penumbra.Scene.load(path, time=0.5)
    posed.edit(**VIEW)
    result = penumbra.Renderer(posed, W, H, shadow_map_size=MAP, validation=True).render(
        "hard", frames=1)
    run_cli("render", path, "-o", tmp_path, "--technique", "hard", "--width", W, "--height", H,
            "--shadow-map-size", MAP, "--frames", 1, "--format", "pfm", "--time", "0.5",
            *VIEW_ARGS)
    assert_same_images(result, tmp_path, "time")
    # ... and not the scene at rest's (the bulb moved 2 units).
    assert not same_bits(result.visibility[2], render_both(asset, tmp_path / "rest", VIEW,
                                                           VIEW_ARGS)[1].visibility[2])
    with pytest.raises(penumbra.InputError, match="--animation"):
        penumbra.Scene.load(path, time=1.0, animation="walk")
    with pytest.raises(penumbra.InputError, match="--time"):
        penumbra.Scene.load(path, time=-1.0)


def test_an_orbiting_added_light_is_placed_at_the_scenes_time():
    # A still scene loaded at 2 s: a quarter of an 8-second turn takes (3, _, 0) to (0, _, -3).
    scene = penumbra.Scene.load("builtin:resting", time=2.0)
    assert scene.time == 2.0
    scene.edit(add_light=["point:pos=3,4,0,orbit=8,about=0,0,0,name=bulb"])
    bulb = next(l for l in scene.lights if l["name"] == "bulb")
    assert bulb["position"] == pytest.approx([0, 4, -3], abs=1e-5)
    rest = penumbra.Scene.load("builtin:resting")
    rest.edit(add_light=["point:pos=3,4,0,orbit=8,about=0,0,0,name=bulb"])
    assert next(l for l in rest.lights if l["name"] == "bulb")["position"] == pytest.approx(
        [3, 4, 0], abs=1e-6)
