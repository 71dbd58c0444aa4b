"""The corpus gate's arithmetic and its run (tools/quality.py), with a stand-in for penumbra that
writes the metrics.json a compare would."""
import json
import math
import stat
import subprocess
import tomllib
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import quality  # noqa: E402

TOOL = Path(quality.__file__)


def row(rmse, acne=0.0, acne_of=5000, leak=0.0, leak_of=5000, misclassified=0.0):
    return {"rmse": rmse, "acne_beyond_blur": acne, "leak_beyond_blur": leak,
            "misclassified_outside_edges": misclassified,
            "counts": {"acne_beyond_blur": {"of": acne_of}, "leak_beyond_blur": {"of": leak_of}}}


def test_percentile_interpolates_between_order_statistics():
    assert quality.percentile([4, 1, 3, 2], 0.5) == 2.5
    assert math.isclose(quality.percentile([1, 2, 3, 4], 0.95), 3.85)
    assert quality.percentile([7], 0.95) == 7
    assert math.isnan(quality.percentile([], 0.5))


def test_figures_count_only_where_they_rest_on_enough_pixels():
    results = {
        ("plates", 1): {"techniques": {"hard": row(0.02), "pcss": row(0.01),
                                       "pcf": row(0.03, acne=0.004, leak=0.5, leak_of=999)}},
        ("open", 1): {"techniques": {"hard": row(0.01), "pcss": row(0.02),
                                     "pcf": row(0.01, acne=0.001, leak_of=1000,
                                                misclassified=0.002)}},
    }
    s = quality.summarize(results, {"least_pixels": 1000})
    pcf = s["pcf"]
    assert pcf["acne_beyond_blur"]["worst"] == 0.004
    assert pcf["acne_beyond_blur"]["worst_scene"] == "plates?seed=1"
    assert pcf["acne_beyond_blur"]["scenes"] == 2
    assert pcf["leak_beyond_blur"]["scenes"] == 1, "999 pixels are too few, 1000 enough"
    assert pcf["leak_beyond_blur"]["worst"] == 0.0
    assert pcf["vs_hard"]["worst"] == 1.5 and pcf["vs_hard"]["median"] == 1.25
    assert pcf["vs_pcss"]["worst"] == 3.0 and pcf["vs_pcss"]["worst_scene"] == "plates?seed=1"
    assert pcf["misclassified"]["worst"] == 0.002
    assert s["pcf @ open"]["acne_beyond_blur"]["worst"] == 0.001
    assert s["hard"]["vs_hard"]["worst"] == 1.0


def test_refused_rows_count_apart_and_leave_the_figures():
    refused = {"skipped": "gen/long?seed=2: sdf refuses this view: ..."}
    results = {
        ("plates", 1): {"techniques": {"hard": row(0.02), "sdf": row(0.01, acne=0.001)}},
        ("long", 1): {"techniques": {"hard": row(0.01), "sdf": refused}},
        ("open", 1): {"techniques": {"hard": row(0.01), "sdf": refused}},
    }
    s = quality.summarize(results, {"least_pixels": 1000})
    assert math.isclose(s["sdf"]["refused"]["share"], 2 / 3) and s["sdf"]["refused"]["scenes"] == 3
    assert s["sdf"]["vs_hard"]["scenes"] == 1 and s["sdf"]["vs_hard"]["worst"] == 0.5
    assert s["sdf"]["acne_beyond_blur"]["scenes"] == 1
    assert s["hard"]["refused"]["share"] == 0.0
    assert s["sdf @ long"]["refused"]["share"] == 1.0
    assert quality.check(s, {"sdf": {"refused.share": 0.6}}) == [
        "sdf refused.share = 0.66667 > 0.6 (worst: )"]
    assert "| sdf | 0.10 | 0.10 (1) |" in quality.markdown(s, [1])
    assert [l for l in quality.markdown(s, [1]).splitlines() if l.startswith("| sdf |")][0].endswith(
        "| 66.67 |")


def test_every_figure_past_its_bound_is_named_with_its_scene():
    summary = {"pcf": {"acne_beyond_blur": {"p95": 0.01, "worst": 0.02, "worst_scene": "a?seed=2"},
                       "vs_hard": {"median": 1.0, "worst": math.nan, "worst_scene": ""}}}
    assert quality.check(summary, {"pcf": {"acne_beyond_blur.worst": 0.02}}) == []
    failed = quality.check(summary, {"pcf": {"acne_beyond_blur.worst": 0.019,
                                             "vs_hard.worst": 0.5}})
    assert failed == ["pcf acne_beyond_blur.worst = 0.02 > 0.019 (worst: a?seed=2)"]
    assert quality.check(summary, {"sdf": {"vs_hard.median": 1}}) == ["sdf: no figures (not run?)"]


FAKE = """#!/usr/bin/env python3
import json, sys
from pathlib import Path
args = sys.argv[1:]
if args[0] == "--validation":
    args = args[1:]
    if "leaves" in args[1]:
        print("vulkan validation: an error", file=sys.stderr)
spec, out = args[1], Path(args[args.index("-o") + 1])
with open(out.parent / "calls.log", "a") as calls:
    calls.write(spec + "\\n")
if "bad" in spec:
    print("error: " + spec + ": no such generated family", file=sys.stderr)
    sys.exit(2)
seed = int(spec.split("seed=")[1])
out.mkdir(parents=True, exist_ok=True)
leak = 0.001 * seed + (0.01 if "open" in spec and seed == 2 else 0.0)
row = lambda rmse, acne, leak=0.0: {"rmse": rmse, "acne_beyond_blur": acne, "leak_beyond_blur": leak,
                          "misclassified_outside_edges": 0.0,
                          "counts": {"acne_beyond_blur": {"of": 4000},
                                     "leak_beyond_blur": {"of": 4000}}}
(out / "metrics.json").write_text(json.dumps({"techniques": {
    "hard": row(0.02, 0.0), "pcss": row(0.01, 0.0), "pcf": row(0.03, 0.001 * seed, leak)}}))
"""


def run(tmp_path, *extra):
    fake = tmp_path / "penumbra"
    fake.write_text(FAKE)
    fake.chmod(fake.stat().st_mode | stat.S_IXUSR)
    plan = tmp_path / "plan.toml"
    plan.write_text('width = 8\nheight = 8\nsamples = 4\nshadow_map_size = 64\nseeds = [1]\n'
                    'families = ["plates", "open"]\ntechniques = ["hard", "pcss", "pcf"]\n'
                    '[bounds]\npcf = { "acne_beyond_blur.worst" = 0.0025 }\n')
    return subprocess.run([sys.executable, str(TOOL), "--plan", str(plan), "--penumbra",
                           str(fake), "--out", str(tmp_path / "out"), *extra],
                          capture_output=True, text=True)


def test_a_run_writes_its_table_and_fails_past_a_bound(tmp_path):
    done = run(tmp_path, "--seeds", "1,2")
    assert done.returncode == 0, done.stderr
    assert "quality: [4/4]" in done.stdout and "left" in done.stdout
    table = (tmp_path / "out/quality.md").read_text()
    assert "| pcf | 0.20 | 0.20 (4) |" in table
    # Leak over plates 1, open 1, plates 2, open 2: 0.1, 0.1, 0.2, 1.2 (%): p95 1.05, worst 1.20.
    assert "| pcf | 0.20 | 0.20 (4) | 1.05 | 1.20 (4) |" in table, table
    figures = json.loads((tmp_path / "out/quality.json").read_text())
    assert figures["seeds"] == [1, 2] and "pcf @ open" in figures["summary"]
    past = run(tmp_path, "--seeds", "3")
    assert past.returncode == 1
    assert "pcf acne_beyond_blur.worst = 0.003 > 0.0025 (worst: " in past.stderr


def test_a_failing_scene_or_a_validation_message_stops_the_run(tmp_path):
    failed = run(tmp_path, "--families", "plates,bad")
    assert failed.returncode == 2
    assert "error: builtin:gen/bad?seed=1: no such generated family" in failed.stderr
    assert "error: builtin:gen/bad?seed=1: error:" not in failed.stderr
    spoke = run(tmp_path, "--families", "leaves", "--validation")
    assert spoke.returncode == 2 and "the validation layer spoke" in spoke.stderr
    assert run(tmp_path, "--families", "leaves").returncode == 0


def test_round_up_keeps_two_significant_digits_and_never_rounds_down():
    assert math.isclose(quality.round_up(0.01234), 0.013)
    assert math.isclose(quality.round_up(0.3), 0.3), "an exact value stays"
    assert math.isclose(quality.round_up(1.2301), 1.3)
    assert math.isclose(quality.round_up(0.00012), 0.00012)
    assert math.isclose(quality.round_up(8.61), 8.7)
    assert quality.round_up(0.0) == 0.0
    assert quality.round_up(math.nan) == 0.0


def test_proposed_bounds_hold_the_run_they_come_from_and_name_only_default_rows():
    results = {
        ("plates", 1): {"techniques": {"hard": row(0.02), "pcss": row(0.01, leak=0.004),
                                       "pcss[fast]": row(0.05, leak=0.5)}},
        ("open", 1): {"techniques": {"hard": row(0.01), "pcss": row(0.03, acne=0.002,
                                                                   misclassified=0.001),
                                     "pcss[fast]": row(0.05)}},
    }
    summary = quality.summarize(results, {"least_pixels": 1000})
    text = quality.propose_bounds(summary, ["hard", "pcss"], 1.25)
    bounds = tomllib.loads(text)["bounds"]
    assert set(bounds) == {"hard", "pcss"}, "variants are not bounded"
    assert set(bounds["pcss"]) == set(quality.BOUNDED)
    assert math.isclose(bounds["pcss"]["leak_beyond_blur.worst"], 0.005)
    assert math.isclose(bounds["pcss"]["acne_beyond_blur.worst"], 0.0025)
    assert math.isclose(bounds["pcss"]["vs_hard.worst"], 3.8)  # 3.0 x 1.25 = 3.75
    assert math.isclose(bounds["pcss"]["misclassified.worst"], 0.0013)  # 0.00125 rounded up
    assert quality.check(summary, bounds) == []
    # A figure 1.3 times as bad passes no bound made at 1.25.
    worse = dict(results)
    worse[("long", 1)] = {"techniques": {"hard": row(0.01), "pcss": row(0.01, leak=0.0052)}}
    failed = quality.check(quality.summarize(worse, {"least_pixels": 1000}), bounds)
    assert failed == ["pcss leak_beyond_blur.worst = 0.0052 > 0.005 (worst: long?seed=1)"]


def test_the_plans_bounds_name_every_technique_and_only_bounded_figures():
    plan = tomllib.loads((Path(quality.ROOT) / "bench/plans/quality.toml").read_text())
    assert set(plan["bounds"]) == set(plan["techniques"])
    for technique, limits in plan["bounds"].items():
        assert set(limits) <= set(quality.BOUNDED + quality.HAND_BOUNDED), technique
        assert all(v >= 0 for v in limits.values()), technique


def test_a_failing_scene_stops_the_compares_still_queued(tmp_path):
    failed = run(tmp_path, "--families", "bad,plates,open,spheres", "--seeds", "1,2",
                 "--jobs", "1")
    assert failed.returncode == 2
    calls = (tmp_path / "out/calls.log").read_text().split()
    assert calls[0] == "builtin:gen/bad?seed=1" and len(calls) <= 2, calls


def test_a_bad_plan_is_one_error_line_before_any_compare(tmp_path):
    good = ('width = 8\nheight = 8\nsamples = 4\nshadow_map_size = 64\nseeds = [1]\n'
            'families = ["plates"]\ntechniques = ["hard"]\n')
    fake = tmp_path / "penumbra"
    fake.write_text(FAKE)
    fake.chmod(fake.stat().st_mode | stat.S_IXUSR)
    cases = {
        "no dot": good + '[bounds]\nhard = { "worst" = 1 }\n',
        "unknown figure": good + '[bounds]\nhard = { "foo.worst" = 1 }\n',
        "unknown stat": good + '[bounds]\nhard = { "acne_beyond_blur.median" = 1 }\n',
        "string bound": good + '[bounds]\nhard = { "vs_hard.worst" = "1" }\n',
        "nan bound": good + '[bounds]\nhard = { "vs_hard.worst" = nan }\n',
        "negative bound": good + '[bounds]\nhard = { "vs_hard.worst" = -1 }\n',
        "bounds not a table": good + 'bounds = 3\n',
        "technique not a table": good + '[bounds]\nhard = 3\n',
        "least pixels text": good + 'least_pixels = "x"\n',
        "techniques a string": good.replace('techniques = ["hard"]', 'techniques = "hard"'),
        "no width": good.replace("width = 8\n", ""),
        "zero samples": good.replace("samples = 4", "samples = 0"),
        "seeds of text": good.replace("seeds = [1]", 'seeds = ["1"]'),
    }
    for name, text in cases.items():
        plan = tmp_path / f"{name.replace(' ', '_')}.toml"
        plan.write_text(text)
        done = subprocess.run([sys.executable, str(TOOL), "--plan", str(plan), "--penumbra",
                               str(fake), "--out", str(tmp_path / "out")],
                              capture_output=True, text=True)
        assert done.returncode == 2, (name, done.stderr)
        lines = done.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith(f"error: {plan}: "), (name, done.stderr)
        assert not (tmp_path / "out/calls.log").exists(), name
    # Repeats run once; a missing binary and an unwritable output are error lines too.
    plan = tmp_path / "good.toml"
    plan.write_text(good)
    once = subprocess.run([sys.executable, str(TOOL), "--plan", str(plan), "--penumbra", str(fake),
                           "--out", str(tmp_path / "out"), "--seeds", "1,1", "--families",
                           "plates,plates"], capture_output=True, text=True)
    assert once.returncode == 0, once.stderr
    assert (tmp_path / "out/calls.log").read_text().split() == ["builtin:gen/plates?seed=1"]
    for extra, says in ((["--penumbra", str(tmp_path / "none")], "no penumbra binary"),
                        (["--penumbra", str(fake), "--out", str(plan / "sub")], "cannot write")):
        done = subprocess.run([sys.executable, str(TOOL), "--plan", str(plan), *extra],
                              capture_output=True, text=True)
        assert done.returncode == 2 and says in done.stderr, done.stderr
        assert done.stderr.startswith("error: ") and len(done.stderr.strip().splitlines()) == 1
