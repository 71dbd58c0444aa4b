"""tools/translucent_methods.py, the generated stacks that chose the translucent layer's default
method (docs/translucency.md, "Which method"): its scenes load as the kinds it names, its sheets
are what its docstring promises, and a run orders the methods as the docs report."""
import json
import sys
from pathlib import Path

import pytest

import penumbra

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import translucent_methods as methods  # noqa: E402


def test_stacks_load_as_their_kinds_in_turn_with_two_to_five_translucent_sheets(tmp_path):
    kinds = []
    for seed in range(9):
        path, kind, _ = methods.generated(seed, tmp_path)
        scene = penumbra.Scene.load(str(path))
        (light,) = scene.lights
        assert light["type"] == kind
        if kind != "directional":
            assert light["position"] == pytest.approx([0, 6, 0])
        kinds.append(kind)
        doc = json.loads(path.read_text())
        sheets = doc["materials"][1:]
        ground = doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"]]
        assert (ground["min"], ground["max"]) == ([-8, 0.0, -8], [8, 0.0, 8])
        assert doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] == [0.7] * 3 + [1]
        assert 2 <= len(sheets) <= 5 and len(doc["meshes"]) == len(sheets) + 1
        assert scene.triangles == 2 * len(doc["meshes"])
        for m in sheets:
            factor = m.get("extensions", {}).get("KHR_materials_transmission", {}).get(
                "transmissionFactor", 0.0)
            if m.get("alphaMode") == "BLEND":
                assert 0.3 <= m["pbrMetallicRoughness"]["baseColorFactor"][3] <= 0.9
                assert factor == 0.0 or 0.5 <= factor <= 1.0
            else:
                assert 0.5 <= factor <= 1.0
    assert kinds == ["directional", "spot", "point"] * 3


def test_a_run_prints_each_seed_and_finds_both_methods_far_below_opaque_sheets(capsys):
    assert methods.main(["--seeds", "7300:7303", "--width", "48", "--height", "32",
                         "--shadow-map-size", "256", "--validation"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[:3] for line in lines[:3]] == [
        ["seed", "7300", "spot"], ["seed", "7301", "point"], ["seed", "7302", "directional"]]
    errors = [[float(x) for x in line.split()[4::2]] for line in lines[:3]]
    for off, coloured, moments in errors:
        assert coloured < 0.5 * off and moments < 0.5 * off, errors
    means = [sum(e[i] for e in errors) / 3 for i in range(3)]
    assert lines[3].startswith("3 scenes, luminance RMSE mean / worst: off ")
    assert f"coloured {means[1]:.4f} / {max(e[1] for e in errors):.4f}" in lines[3]
    counts = [int(w) for w in lines[4].replace(",", "").split() if w.isdigit()]
    assert len(counts) == 3 and sum(counts) == 3


def test_the_defaults_are_the_run_the_docs_report():
    args = methods.arguments([])
    first, end = (int(s) for s in args.seeds.split(":"))
    docs = (Path(__file__).resolve().parents[2] / "docs" / "translucency.md").read_text()
    run = " ".join(docs.split("### Which method", 1)[1].split())
    assert (f"`tools/translucent_methods.py` at its defaults: seeds {first} to {end - 1}, "
            f"{args.width} x {args.height}, {args.shadow_map_size} maps; {end - first} scenes") in run
    assert not args.validation
