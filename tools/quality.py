#!/usr/bin/env python3
"""The generated scene corpus as a gate (docs/testing.md, "The corpus gate"): `penumbra compare`
on every family of builtin:gen/ for each seed, every technique at its defaults; per technique,
over the corpus and per family: the 95th percentile and the worst of acne and leak beyond blur
(each counted only on scenes where it rests on at least --least-pixels pixels), the median
and worst RMSE as a multiple of hard's and of pcss's on the same scene, and the worst share
misclassified away from edges, and the share of scenes whose row was refused (sdf.refuse) or
skipped, which the other figures leave out. Writes quality.json and quality.md into --out and checks the
figures against the plan's [bounds]: exit 1 naming every figure past its bound.

    tools/quality.py [--plan bench/plans/quality.toml] [--seeds 1,2] [--families a,b]
                     [--penumbra BIN] [--out DIR] [--jobs N] [--validation] [--propose-bounds F]

--propose-bounds F prints a [bounds] block for the plan: each bounded figure of each technique's
defaults row at F times its value over this run, rounded up to two significant digits.
"""
import argparse
import concurrent.futures
import json
import math
import os
import subprocess
import sys
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ["acne_beyond_blur", "leak_beyond_blur"]


def percentile(values, q):
    """The q-quantile by linear interpolation between order statistics (NumPy's default)."""
    ordered = sorted(values)
    if not ordered:
        return math.nan
    at = q * (len(ordered) - 1)
    low = math.floor(at)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (at - low)


# The statistics each figure has (summarize), which a plan's bounds may name.
STATS = {**{f: ("p95", "worst") for f in FIGURES + ["misclassified"]},
         "vs_hard": ("median", "worst"), "vs_pcss": ("median", "worst"), "refused": ("share",)}


def validate_plan(plan):
    """The plan's keys and types, checked before any compare runs: a ValueError naming the first
    problem."""
    for key in ("width", "height", "samples", "shadow_map_size"):
        if not isinstance(plan.get(key), int) or isinstance(plan[key], bool) or plan[key] < 1:
            raise ValueError(f"`{key}` must be a whole number of at least 1")
    for key, kind in (("techniques", str), ("families", str), ("seeds", int)):
        values = plan.get(key)
        if not isinstance(values, list) or not values or \
                not all(isinstance(v, kind) and not isinstance(v, bool) for v in values):
            raise ValueError(f"`{key}` must be a list of {'names' if kind is str else 'seeds'}")
    least = plan.get("least_pixels", 1000)
    if not isinstance(least, (int, float)) or isinstance(least, bool) or \
            not math.isfinite(least) or least < 0:
        raise ValueError("`least_pixels` must be a number of at least 0")
    bounds = plan.get("bounds", {})
    if not isinstance(bounds, dict):
        raise ValueError("`bounds` must be a table of techniques")
    for technique, limits in bounds.items():
        if not isinstance(limits, dict):
            raise ValueError(f"bounds of `{technique}` must be a table of FIGURE.STAT = number")
        for name, bound in limits.items():
            figure, _, stat = name.rpartition(".")
            if stat not in STATS.get(figure, ()):
                raise ValueError(f"bound `{technique}` `{name}`: no such figure (FIGURE.STAT: "
                                 + ", ".join(f"{f}.{t}" for f, ts in STATS.items() for t in ts)
                                 + ")")
            if not isinstance(bound, (int, float)) or isinstance(bound, bool) or \
                    not math.isfinite(bound) or bound < 0:
                raise ValueError(f"bound `{technique}` `{name}` must be a finite number of at "
                                 "least 0")


def unique(values):
    """values without repeats, in their order: a seed or family given twice runs once."""
    return list(dict.fromkeys(values))


def run_scene(penumbra, spec, out, plan, validation):
    """One compare; its metrics.json, or an error line naming the scene (a message of the
    validation layer is one)."""
    args = [penumbra] + (["--validation"] if validation else []) + ["compare", spec, "-o", str(out), "--width", str(plan["width"]),
            "--height", str(plan["height"]), "--samples", str(plan["samples"]),
            "--shadow-map-size", str(plan["shadow_map_size"]), "--frames", "1",
            "--techniques", ",".join(plan["techniques"])]
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode != 0:
        lines = done.stderr.strip().splitlines() or ["(no output)"]
        last = lines[-1].removeprefix("error: ")  # penumbra's own line names the scene already
        raise RuntimeError(last if last.startswith(spec) else f"{spec}: {last}")
    if "vulkan validation" in done.stderr:
        raise RuntimeError(f"{spec}: the validation layer spoke: {done.stderr.strip()[:400]}")
    return json.loads((out / "metrics.json").read_text())


def summarize(results, plan):
    """Per technique (and per technique and family): the figures the gate reads."""
    least = plan.get("least_pixels", 1000)
    groups = {}
    for (family, seed), metrics in sorted(results.items()):
        rows = metrics["techniques"]
        hard = rows.get("hard", {}).get("rmse")
        pcss = rows.get("pcss", {}).get("rmse")
        for technique, row in rows.items():
            for key in (technique, f"{technique} @ {family}"):
                g = groups.setdefault(key, {f: [] for f in FIGURES + ["vs_hard", "vs_pcss",
                                                                     "misclassified", "refused"]})
                g["refused"].append("skipped" in row)
                if "skipped" in row:  # refused (sdf.refuse) or past the device: no figures
                    continue
                for f in FIGURES:
                    if row["counts"][f]["of"] >= least:
                        g[f].append((row[f], f"{family}?seed={seed}"))
                if hard and hard > 0:
                    g["vs_hard"].append((row["rmse"] / hard, f"{family}?seed={seed}"))
                if pcss and pcss > 0:
                    g["vs_pcss"].append((row["rmse"] / pcss, f"{family}?seed={seed}"))
                g["misclassified"].append((row["misclassified_outside_edges"],
                                           f"{family}?seed={seed}"))
    summary = {}
    for key, g in groups.items():
        s = {}
        for f in FIGURES + ["misclassified"]:
            values = [v for v, _ in g[f]]
            worst = max(g[f], default=(math.nan, ""))
            s[f] = {"p95": percentile(values, 0.95), "worst": worst[0], "worst_scene": worst[1],
                    "scenes": len(values)}
        for f in ("vs_hard", "vs_pcss"):
            values = [v for v, _ in g[f]]
            worst = max(g[f], default=(math.nan, ""))
            s[f] = {"median": percentile(values, 0.5), "worst": worst[0],
                    "worst_scene": worst[1], "scenes": len(values)}
        s["refused"] = {"share": sum(g["refused"]) / max(len(g["refused"]), 1),
                        "scenes": len(g["refused"])}
        summary[key] = s
    return summary


def check(summary, bounds):
    """Every figure past its bound, as lines: TECHNIQUE FIGURE.STAT = VALUE > BOUND (SCENE)."""
    failures = []
    for technique, limits in sorted(bounds.items()):
        if technique not in summary:
            failures.append(f"{technique}: no figures (not run?)")
            continue
        for name, bound in sorted(limits.items()):
            figure, stat = name.rsplit(".", 1)
            value = summary[technique][figure][stat]
            if not math.isnan(value) and value > bound:
                where = summary[technique][figure].get("worst_scene", "")
                failures.append(f"{technique} {name} = {value:.5g} > {bound:g} (worst: {where})")
    return failures


# The figures a plan's bounds hold, per technique at its defaults (the row named as the technique):
# worsts only, which no subset of the scenes exceeds (a 95th percentile or a median of the CI's
# nine scenes may lie above the same figure over hundreds).
BOUNDED = ["acne_beyond_blur.worst", "leak_beyond_blur.worst", "vs_hard.worst",
           "misclassified.worst"]
# Figures a plan bounds by hand, never proposed: the share of scenes a technique refuses
# (sdf.refuse), which a change may push to every scene while the kept ones' figures improve.
HAND_BOUNDED = ["refused.share"]


def round_up(value, digits=2):
    """value rounded up to `digits` significant digits (0 stays 0)."""
    if value <= 0 or math.isnan(value):
        return 0.0
    scale = 10 ** (math.floor(math.log10(value)) - digits + 1)
    return math.ceil(round(value / scale, 9)) * scale


def propose_bounds(summary, techniques, factor):
    """A [bounds] block: every bounded figure of each technique's row at factor times its value;
    a figure that rests on no scene is left out."""
    lines = ["[bounds]"]
    for technique in techniques:
        if technique not in summary:
            continue
        figures = []
        for name in BOUNDED:
            figure, stat = name.rsplit(".", 1)
            value = summary[technique][figure][stat]
            if summary[technique][figure]["scenes"] and not math.isnan(value):
                figures.append(f'"{name}" = {round_up(factor * value):.2g}')
        lines.append(f'"{technique}" = {{ {", ".join(figures)} }}')
    return "\n".join(lines) + "\n"


def markdown(summary, seeds):
    lines = [f"Generated corpus, seeds {', '.join(map(str, seeds))}: acne and leak beyond blur "
             "in percent (p95 / worst, scenes counted), RMSE as a multiple of hard's and pcss's "
             "(median / worst), misclassified away from edges in percent (worst), scenes whose "
             "row was refused or skipped in percent (the other figures leave them out).", "",
             "| technique | acne>b p95 | acne>b worst | leak>b p95 | leak>b worst | "
             "x hard | x pcss | misclass. worst | refused |",
             "|---|---|---|---|---|---|---|---|---|"]
    for key in sorted(k for k in summary if "@" not in k):
        s = summary[key]
        pct = lambda v: "-" if math.isnan(v) else f"{100 * v:.2f}"
        ratio = lambda v: "-" if math.isnan(v) else f"{v:.2f}"
        lines.append(
            f"| {key} | {pct(s['acne_beyond_blur']['p95'])} | "
            f"{pct(s['acne_beyond_blur']['worst'])} ({s['acne_beyond_blur']['scenes']}) | "
            f"{pct(s['leak_beyond_blur']['p95'])} | "
            f"{pct(s['leak_beyond_blur']['worst'])} ({s['leak_beyond_blur']['scenes']}) | "
            f"{ratio(s['vs_hard']['median'])} / {ratio(s['vs_hard']['worst'])} | "
            f"{ratio(s['vs_pcss']['median'])} / {ratio(s['vs_pcss']['worst'])} | "
            f"{pct(s['misclassified']['worst'])} | {pct(s['refused']['share'])} |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plan", type=Path, default=ROOT / "bench/plans/quality.toml")
    parser.add_argument("--seeds", help="comma-separated seeds (default: the plan's)")
    parser.add_argument("--families", help="comma-separated families (default: the plan's)")
    parser.add_argument("--penumbra", default=str(ROOT / "build/release/apps/penumbra/penumbra"))
    parser.add_argument("--out", type=Path, default=ROOT / "build/quality")
    parser.add_argument("--jobs", type=int, default=1, help="compares at once")
    parser.add_argument("--validation", action="store_true",
                        help="the Khronos validation layer on; any message fails the run")
    parser.add_argument("--propose-bounds", type=float, metavar="F",
                        help="print bounds at F times this run's figures (a plan's [bounds])")
    args = parser.parse_args()
    try:
        plan = tomllib.loads(args.plan.read_text())
        validate_plan(plan)
        seeds = unique(int(s) for s in args.seeds.split(",")) if args.seeds else unique(
            plan["seeds"])
        families = unique(args.families.split(",")) if args.families else unique(
            plan["families"])
    except (OSError, ValueError, KeyError, tomllib.TOMLDecodeError) as e:
        print(f"error: {args.plan}: {e}", file=sys.stderr)
        return 2
    if not (os.path.isfile(args.penumbra) and os.access(args.penumbra, os.X_OK)):
        print(f"error: {args.penumbra}: no penumbra binary there (--penumbra; `make build`)",
              file=sys.stderr)
        return 2
    try:
        args.out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        print(f"error: {args.out}: cannot write the results there ({e.strerror})",
              file=sys.stderr)
        return 2
    jobs = [(f, s) for s in seeds for f in families]
    results, started = {}, time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(args.jobs, 1)) as pool:
        futures = {pool.submit(run_scene, args.penumbra, f"builtin:gen/{f}?seed={s}",
                               args.out / f"{f}-{s}", plan, args.validation): (f, s)
                   for f, s in jobs}
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            family, seed = futures[future]
            try:
                results[(family, seed)] = future.result()
            except RuntimeError as e:
                print(f"error: {e}", file=sys.stderr)
                # The compares still queued do not run; those running finish.
                pool.shutdown(wait=True, cancel_futures=True)
                return 2
            spent = time.monotonic() - started
            eta = spent / done * (len(jobs) - done)
            print(f"quality: [{done}/{len(jobs)}] {family}?seed={seed} "
                  f"({spent:.0f} s, about {eta:.0f} s left)", flush=True)
    summary = summarize(results, plan)
    (args.out / "quality.json").write_text(json.dumps(
        {"seeds": seeds, "families": families, "summary": summary}, indent=1, sort_keys=True))
    table = markdown(summary, seeds)
    (args.out / "quality.md").write_text(table)
    print(table)
    if args.propose_bounds:
        print(propose_bounds(summary, plan["techniques"], args.propose_bounds))
    failures = check(summary, plan.get("bounds", {}))
    for line in failures:
        print(f"quality: past its bound: {line}", file=sys.stderr)
    print(f"quality: {len(jobs)} scenes, {len(failures)} figures past their bounds; "
          f"{args.out / 'quality.md'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
