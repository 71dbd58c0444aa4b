"""The Python module against the CLI: the same arrays bit for bit for every light type, the same
metrics as compare's metrics.json, errors as exceptions before the device sees bad input, no
growth over many renders, and the GIL released while the device or Embree works."""
import json
import math
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import penumbra
from conftest import CLI, VIEW, VIEW_ARGS, read_pfm, run_cli, same_bits

W, H, MAP = 48, 32, 128


@pytest.fixture(scope="module")
def renderer(asset):
    scene = penumbra.Scene.load(str(asset))
    scene.edit(**VIEW)
    return penumbra.Renderer(scene, W, H, shadow_map_size=MAP, validation=True)


def test_arrays_have_the_contract_shapes_dtypes_and_nan_background():
    scene = penumbra.Scene.builtin("showcase")
    r = penumbra.Renderer(scene, 40, 24, shadow_map_size=256, validation=True)
    result = r.render("hard", frames=1)
    assert result.image.shape == (24, 40, 4) and result.image.dtype == np.uint8
    assert result.position.shape == (24, 40, 3) and result.position.dtype == np.float32
    assert result.normal.shape == (24, 40, 3) and result.normal.dtype == np.float32
    assert len(result.visibility) == 1
    v = result.visibility[0]
    assert v.shape == (24, 40) and v.dtype == np.float32
    background = np.isnan(result.position[..., 0])
    assert background[0].all(), "the sky fills the top row"
    assert not background[-1].any(), "the ground fills the bottom row"
    assert np.array_equal(np.isnan(v), background)
    assert np.nanmin(v) >= 0 and np.nanmax(v) <= 1
    assert set(result.gpu_ms) >= {"shadow", "gbuffer", "composite", "total"}
    assert all(ms >= 0 for ms in result.gpu_ms.values())
    passes = {k: v for k, v in result.gpu_ms.items() if k != "total"}
    assert result.gpu_ms["total"] == pytest.approx(sum(passes.values()), rel=1e-12)
    assert result.gpu_ms["total"] > max(passes.values()), "every pass takes some time"
    by_cost = result.gpu_ms_by_cost
    assert set(by_cost) == {"shadow_maps", "per_pixel", "frame"}
    assert by_cost["frame"] == result.gpu_ms["gbuffer"]
    assert by_cost["shadow_maps"] == pytest.approx(result.gpu_ms["shadow"], rel=1e-12)
    assert sum(by_cost.values()) == pytest.approx(result.gpu_ms["total"], rel=1e-12)
    frames = result.gpu_ms_per_frame
    assert set(frames) == set(result.gpu_ms)
    assert frames["total"] == pytest.approx(
        [sum(f) for f in zip(*(v for k, v in frames.items() if k != "total"))], rel=1e-12)
    assert result.parameters["bias.mode"] == "adaptive"


@pytest.mark.parametrize("technique", ["hard", "pcf[box7]", "pcss", "vsm", "sdf"])
def test_arrays_equal_the_clis_files_for_every_light_type(renderer, asset, tmp_path, technique):
    run_cli("render", asset, "-o", tmp_path, "--technique", technique, "--width", W, "--height",
            H, "--shadow-map-size", MAP, "--frames", 1, "--format", "pfm", *VIEW_ARGS)
    result = renderer.render(technique, frames=1)
    assert [l["name"] for l in result.lights] == ["light0", "light1", "bulb"]
    assert len(result.visibility) == 3  # the sun's, the spot's and the bulb's
    for i, v in enumerate(result.visibility):
        name = "visibility.pfm" if i == 0 else f"visibility_{i}.pfm"
        assert same_bits(v, read_pfm(tmp_path / name)), f"{technique}: {name}"
        lit = np.nan_to_num(v, nan=0) > 0.5
        assert lit.any() and (~lit & ~np.isnan(v)).any(), f"{technique}: light {i} shadows"
    assert same_bits(result.position, read_pfm(tmp_path / "position.pfm"))
    assert same_bits(result.normal, read_pfm(tmp_path / "normal.pfm"))


def test_metrics_equal_compares_metrics_json(renderer, asset, tmp_path):
    rows = ["hard", "pcf[box7]", "pcss"]
    run_cli("compare", asset, "-o", tmp_path, "--techniques", ",".join(rows), "--width", W,
            "--height", H, "--shadow-map-size", MAP, "--frames", 1, "--samples", 4,
            "--format", "pfm", *VIEW_ARGS)
    written = json.loads((tmp_path / "metrics.json").read_text())["techniques"]
    truth = renderer.reference(samples=4)
    for i, v in enumerate(truth.visibility):
        name = "visibility.pfm" if i == 0 else f"visibility_{i}.pfm"
        assert same_bits(v, read_pfm(tmp_path / name)), name
    for row in rows:
        ours = penumbra.metrics(renderer.render(row, frames=1), truth)
        theirs = written[row]
        assert set(ours) == set(theirs)
        times = ("gpu_ms", "gpu_ms_by_cost")  # differ from run to run; everything else is exact
        for key in ours:
            if key not in times:
                assert ours[key] == theirs[key], f"{row}: {key}"
        for key in times:
            assert set(ours[key]) == set(theirs[key]), f"{row}: {key}"
        result = renderer.render(row, frames=1)
        assert penumbra.metrics(result, truth)["gpu_ms"] == result.gpu_ms, "one total, one sum"


def test_metrics_read_the_arrays_as_they_are(renderer):
    truth = renderer.reference(samples=4)
    result = renderer.render("hard", frames=1)
    before = penumbra.metrics(result, truth)
    for v, t in zip(result.visibility, truth.visibility):
        v[...] = t  # the arrays are the result's own memory
    after = penumbra.metrics(result, truth)
    assert before["rmse"] > 0 and after["rmse"] == 0 and after["pixels"] == before["pixels"]
    kept = result.visibility[0]
    del result
    assert np.nanmax(kept) <= 1, "an array keeps its pixels alive after the result is gone"


def test_bad_input_raises_the_clis_message_before_the_device(asset, tmp_path):
    scene = penumbra.Scene.load(str(asset))
    with pytest.raises(penumbra.InputError, match="width"):
        penumbra.Renderer(scene, 0, 32)
    with pytest.raises(penumbra.InputError, match="light_angle"):
        penumbra.Renderer(scene, 8, 8, light_angle=45)
    r = penumbra.Renderer(scene, 16, 16, shadow_map_size=64, validation=True)
    with pytest.raises(penumbra.InputError, match="technique"):
        r.render("nonsense")
    with pytest.raises(penumbra.InputError, match="pcf.size"):
        r.render("pcf", pcf_size=4)  # kernel sizes are odd
    with pytest.raises(penumbra.InputError, match="pcf.size"):
        r.render("pcf", {"pcf.size": "many"})
    with pytest.raises(penumbra.InputError, match="unknown parameter 'pcf.sizes'"):
        r.render("pcf", pcf_sizes=3)
    with pytest.raises(penumbra.InputError, match="sizes"):
        r.render("pcf", sizes=3)  # no family
    with pytest.raises(ValueError):  # InputError is a ValueError
        r.render("hard", frames=1, bias_constant=-1)
    with pytest.raises(penumbra.InputError, match="samples"):
        r.reference(samples=0)
    with pytest.raises(penumbra.InputError, match="--light-pos"):
        scene.edit(light_pos={"nobody": (0, 1, 0)})
    with pytest.raises(penumbra.InputError, match="missing.gltf"):
        penumbra.Scene.load(str(tmp_path / "missing.gltf"))
    broken = tmp_path / "broken.gltf"
    broken.write_text('{"asset": {"version": "2.0"}, "meshes": [7]}')
    with pytest.raises(penumbra.InputError, match="broken.gltf"):
        penumbra.Scene.load(str(broken))
    with pytest.raises(penumbra.InputError, match="shadow"):
        penumbra.Renderer(scene, 16, 16, shadow_map_size=1 << 20)
    # The CLI says the same: the message is its error line without "error: ".
    done = subprocess.run([CLI, "render", str(asset), "-o", str(tmp_path / "o"), "--technique",
                           "pcf", "--set", "pcf.size=4"], capture_output=True, text=True)
    with pytest.raises(penumbra.InputError) as raised:
        r.render("pcf", pcf_size=4)
    assert done.stderr.strip().splitlines()[-1] == "error: " + str(raised.value)
    assert r.render("hard", frames=1).width == 16, "the renderer still works after refusals"


def test_keywords_name_parameters_as_set_does(renderer):
    r = renderer.render("msm-soft", frames=1, msm_soft_maxRadius=12, msm_soft_refine=False,
                        params={"bias.normal": 0.5}, bias_mode="fixed")
    assert r.parameters["msm-soft.maxRadius"] == "12"
    assert r.parameters["msm-soft.refine"] == "false"
    assert r.parameters["bias.normal"] == "0.5"
    assert r.parameters["bias.mode"] == "fixed"
    assert r.name == "msm-soft" and r.technique == "msm-soft"
    assert renderer.render("pcf[box7]", frames=1).parameters["pcf.size"] == "7"


def test_a_renderer_reused_for_100_renders_does_not_grow(renderer):
    techniques = ["hard", "pcf", "pcss", "vsm", "msm"]
    sizes = []
    for cycle in range(20):
        for technique in techniques:
            renderer.render(technique, frames=1)
        sizes.append((renderer.device_memory_bytes, rss_bytes()))
    # After the first cycles every technique's targets exist: device memory is flat to the byte
    # and the process's resident memory within 2% (allocator noise).
    assert len({device for device, _ in sizes[2:]}) == 1, sizes
    assert sizes[-1][1] <= sizes[2][1] * 1.02, sizes


def rss_bytes():
    pages = int(Path("/proc/self/statm").read_text().split()[1])
    return pages * 4096


@pytest.fixture(scope="module")
def busy_renderer(asset):
    # Lights with a size, so the truth traces many rays; a view large enough to take a while.
    scene = penumbra.Scene.load(str(asset))
    scene.edit(**VIEW)
    return penumbra.Renderer(scene, 160, 120, shadow_map_size=512, light_radius=0.3,
                             light_angle=3)


@pytest.mark.parametrize("work", ["render", "reference"])
def test_the_gil_is_released_while_the_device_or_embree_works(busy_renderer, work):
    call = {"render": lambda: busy_renderer.render("pcss", frames=10),
            "reference": lambda: busy_renderer.reference(samples=64)}[work]
    finished = threading.Event()
    worker = threading.Thread(target=lambda: (call(), finished.set()))
    ticks = 0
    start = time.perf_counter()
    worker.start()
    while not finished.is_set():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    elapsed = time.perf_counter() - start
    # With the GIL held through the call this loop could not run while it worked (a tick or two
    # before the call starts); released, it ticks every millisecond or so.
    assert elapsed > 0.05, "the work was too short to tell"
    assert ticks >= 20, (ticks, elapsed)


def test_generated_scenes_load_as_the_cli_names_them():
    a = penumbra.Scene.builtin("gen/spheres?seed=3", no_ground=True)
    b = penumbra.Scene.builtin("builtin:gen/spheres?seed=3", no_ground=True)
    assert a.name == "gen/spheres?seed=3" and a.triangles == b.triangles > 2
    assert a.lights == b.lights and a.cameras == ["generated"]
    assert penumbra.Scene.builtin("gen/spheres?seed=4", no_ground=True).lights != a.lights
    with pytest.raises(penumbra.InputError, match="no such generated family 'caves'"):
        penumbra.Scene.builtin("gen/caves?seed=1")


def test_techniques_are_the_clis_list():
    listed = json.loads(run_cli("techniques", "--json"))
    assert penumbra.techniques() == listed
    names = [t["name"] for t in penumbra.techniques()]
    assert {"hard", "pcf", "pcss", "vsm", "msm-soft", "sdf"} <= set(names)


def test_the_example_reproduces_a_compare_row(asset, tmp_path):
    run_cli("compare", "builtin:showcase", "-o", tmp_path, "--techniques", "pcf[box7]",
            "--width", 64, "--height", 40, "--shadow-map-size", 256, "--frames", 1,
            "--samples", 4, "--light-angle", 3)
    written = json.loads((tmp_path / "metrics.json").read_text())["techniques"]["pcf[box7]"]
    example = Path(__file__).resolve().parents[2] / "examples" / "compare_row.py"
    done = subprocess.run([sys.executable, str(example), "builtin:showcase", "pcf[box7]",
                           "--width", "64", "--height", "40", "--shadow-map-size", "256",
                           "--samples", "4", "--light-angle", "3"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    ours = json.loads(done.stdout)
    for key, value in written.items():
        if key not in ("gpu_ms", "gpu_ms_by_cost"):  # times differ from run to run
            assert ours[key] == value, key


def test_the_docs_show_the_sweep_example_as_it_is():
    root = Path(__file__).resolve().parents[2]
    example = (root / "examples" / "sweep_pcf.py").read_text()
    assert "```python\n" + example + "```" in (root / "docs" / "python.md").read_text()


def test_sdf_refuses_a_view_its_field_cannot_hold_as_the_cli_does():
    scene = penumbra.Scene.builtin("gen/long?seed=2")
    r = penumbra.Renderer(scene, 256, 144, shadow_map_size=1024, validation=True)
    with pytest.raises(penumbra.InputError, match=r"gen/long\?seed=2: sdf refuses this view"):
        r.render("sdf")
    kept = r.render("sdf", sdf_refuse=0)  # the user's decision: rendered without the audit
    assert kept.visibility[0].shape == (144, 256)


def test_translucent_layer_gives_the_light_per_channel_as_the_truth_does():
    scene = penumbra.Scene.builtin("sheets")
    r = penumbra.Renderer(scene, 48, 32, shadow_map_size=256, validation=True)
    grey = r.render("hard", frames=1)
    assert grey.transmittance == []
    result = r.render("hard", params={"translucent.method": "moments"}, frames=1)
    truth = r.reference(samples=1)
    assert len(result.transmittance) == 1 and len(truth.transmittance) == 1
    rgb, wanted = result.transmittance[0], truth.transmittance[0]
    assert rgb.shape == (32, 48, 3) and rgb.dtype == np.float32
    luminance = rgb @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)
    v = result.visibility[0]
    assert np.array_equal(np.isnan(luminance), np.isnan(v))
    assert np.nanmax(np.abs(luminance - v)) < 1e-5
    counted = ~np.isnan(wanted[..., 0]) & ~np.isnan(rgb[..., 0])
    error = np.sqrt(np.mean((rgb[counted] - wanted[counted]) ** 2, axis=0))
    opaque = np.sqrt(np.mean((grey.visibility[0][counted][:, None] - wanted[counted]) ** 2, axis=0))
    assert (error < 0.5 * opaque).all(), (error, opaque)
    # penumbra.metrics gives compare's rmse_per_channel: the layer's below half the grey row's.
    ours, greys = penumbra.metrics(result, truth), penumbra.metrics(grey, truth)
    assert len(ours["rmse_per_channel"]) == 3 and len(greys["rmse_per_channel"]) == 3
    for tinted, plain in zip(ours["rmse_per_channel"], greys["rmse_per_channel"]):
        assert tinted < 0.5 * plain, (ours["rmse_per_channel"], greys["rmse_per_channel"])
