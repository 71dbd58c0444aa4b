#!/usr/bin/env python3
"""Mutation testing for Penumbra: `make mutation-test`.

Applies each one-line mutation listed in tests/mutations/*.toml to a scratch copy of the tree,
rebuilds incrementally, runs the ctest labels that can see the change (stopping at the first
failing test) and reports which mutations no test caught. The working tree is never modified.

    tools/mutation_test.py [--only ID,ID...] [--label L] [--list] [--jobs N] [--keep-going]
    tools/mutation_test.py --random N [--since REV] [--seed S] [--no-rest] [--report PATH] [--list]

--random N: N mutants nobody chose, drawn in the lines changed since REV (tools/random_mutants.py),
each run on the labels tests/mutations/coverage.toml maps its file to, then (a survivor) on every
other test; the kill rate and survivors' diffs go to build/mutation/random-report.md (and .json).

The scratch tree lives in build/mutation/tree (its build in build/mutation/tree/build/release)
and is reused between runs: only files that changed are copied, so a second run rebuilds little.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import random_mutants

ROOT = Path(__file__).resolve().parent.parent
MUTATIONS = ROOT / "tests" / "mutations"
LOGS = ROOT / "build" / "mutation" / "logs"
SCRATCH = ROOT / "build" / "mutation" / "tree"
BUILD = SCRATCH / "build" / "release"
KINDS = {"sign", "compare", "off-by-one", "swap", "constant", "drop", "logic"}


class ListError(Exception):
    pass


def load_mutations(directory):
    mutations, seen = [], set()
    for path in sorted(directory.glob("*.toml")):
        with open(path, "rb") as f:
            data = tomllib.load(f)
        for m in data.get("mutation", []):
            where = f"{path.name}: {m.get('id', '<no id>')}"
            for key in ("id", "labels", "kind", "why"):
                if key not in m:
                    raise ListError(f"{where}: missing '{key}'")
            if m["id"] in seen:
                raise ListError(f"{where}: duplicate id")
            if m["kind"] not in KINDS:
                raise ListError(f"{where}: kind '{m['kind']}' is not one of {sorted(KINDS)}")
            # One edit (file/find/replace), or `edits`: the same bug in a shader and its CPU
            # mirror, which a parity test alone cannot see.
            edits = m.get("edits") or [{k: m[k] for k in ("file", "find", "replace",
                                                           "occurrence") if k in m}]
            for e in edits:
                for key in ("file", "find", "replace"):
                    if key not in e:
                        raise ListError(f"{where}: an edit is missing '{key}'")
                if e["find"] == e["replace"]:
                    raise ListError(f"{where}: find and replace are the same")
            seen.add(m["id"])
            m["edits"] = edits
            m["files"] = ", ".join(dict.fromkeys(e["file"] for e in edits))
            m["list"] = path.name
            mutations.append(m)
    return mutations


def check_labels(mutations, all_labels):
    """ListError for a label no test carries: ctest would run nothing, and the mutant survive
    unseen (coverage.toml's `all` is tests/CMakeLists.txt's labels; tests/tools checks it)."""
    for m in mutations:
        unknown = sorted(set(m["labels"]) - set(all_labels))
        if unknown:
            raise ListError(f"{m['list']}: {m['id']}: no test carries the label(s) "
                            f"{', '.join(unknown)}")


def locate(m, e, text):
    """Offset of the edit's `find` in `text`; ListError unless it is unambiguous."""
    count = text.count(e["find"])
    occurrence = e.get("occurrence")
    if occurrence is None:
        if count != 1:
            raise ListError(f"{m['id']}: 'find' occurs {count} times in {e['file']} "
                            f"(must be exactly once, or give 'occurrence')")
        return text.index(e["find"])
    if not 1 <= occurrence <= count:
        raise ListError(f"{m['id']}: occurrence {occurrence} of {count} in {e['file']}")
    at = -1
    for _ in range(occurrence):
        at = text.index(e["find"], at + 1)
    return at


def apply(m, root):
    """Applies every edit of `m` under `root`; returns the original texts to restore."""
    originals = {}
    for e in m["edits"]:
        target = root / e["file"]
        text = originals.get(target)
        if text is None:
            text = originals[target] = target.read_text(errors="surrogateescape")
        current = target.read_text(errors="surrogateescape")
        at = locate(m, e, current)
        target.write_text(current[:at] + e["replace"] + current[at + len(e["find"]):],
                          errors="surrogateescape")
    return originals


def tracked_files():
    out = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "-z"], cwd=ROOT,
                         check=True, capture_output=True).stdout
    return [Path(p.decode()) for p in out.split(b"\0") if p]


def sync_scratch():
    """Copies every tracked or untracked-but-not-ignored file whose bytes differ."""
    copied = 0
    wanted = set()
    for rel in tracked_files():
        src, dst = ROOT / rel, SCRATCH / rel
        if not src.is_file():
            continue
        wanted.add(rel)
        data = src.read_bytes()
        if dst.is_file() and dst.read_bytes() == data:
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        dst.write_bytes(data)
        shutil.copymode(src, dst)
        copied += 1
    for path in SCRATCH.rglob("*"):  # files deleted from the tree since the last run
        rel = path.relative_to(SCRATCH)
        if path.is_file() and rel.parts[0] != "build" and rel not in wanted:
            path.unlink()
    return copied


def run(cmd, log, timeout=None, cwd=SCRATCH):
    with open(log, "w") as f:
        try:
            return subprocess.run(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT,
                                  timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            return 124


def build(jobs, log, targets=()):
    if not (BUILD / "CMakeCache.txt").exists():
        if run(["cmake", "--preset", "release"], log) != 0:
            return False
    command = ["cmake", "--build", "--preset", "release", "-j", str(jobs)]
    for target in targets:
        command += ["--target", target]
    return run(command, log) == 0


def targets_by_label():
    """Each label's test executables, from ctest's own description of the tests. The CLI
    tests run the `penumbra` program, which their target does not link, so it comes along."""
    out = subprocess.run(["ctest", "--test-dir", str(BUILD), "--show-only=json-v1"],
                         check=True, capture_output=True, text=True).stdout
    targets = {}
    for test in json.loads(out)["tests"]:
        executable = Path(test["command"][0]).name
        labels = next((p["value"] for p in test.get("properties", []) if p["name"] == "LABELS"),
                      [])
        built = Path(test["command"][0]).resolve().is_relative_to(BUILD.resolve())
        for label in labels:  # a test run by an interpreter (pytest) needs the whole build: None
            targets.setdefault(label, set()).add(executable if built else None)
            if executable == "penumbra_cli_tests":
                targets[label].add("penumbra")
    return targets


def label_regex(labels):
    return "^(" + "|".join(labels) + ")$"


def first_failure(log):
    """The first test that failed, in the order ctest finished them."""
    for line in Path(log).read_text(errors="replace").splitlines():
        if any(mark in line for mark in ("***Failed", "***Timeout", "***Exception", "Subprocess")):
            name = line.split(": ", 1)[-1].split(" ", 1)[0]
            return name.rstrip(".")
    return "?"


def needed_targets(labels, executables):
    """The targets to build for `labels`' tests; [] (everything) if one needs the whole build."""
    needed = {t for label in labels for t in executables.get(label, ())}
    return [] if None in needed else sorted(needed)


def run_tests(labels, jobs, log, timeout, exclude=False):
    """ctest on the tests of `labels` (None: every test); exclude: on those none of them labels."""
    select = [] if labels is None else ["-LE" if exclude else "-L", label_regex(labels)]
    env_cmd = ["ctest", "--test-dir", str(BUILD), *select, "-j", str(jobs),
               "--stop-on-failure", "--timeout", str(timeout), "--output-on-failure"]
    return run(env_cmd, log, timeout=timeout * 4)


def fmt_seconds(s):
    return f"{int(s) // 60}m{int(s) % 60:02d}s"


def eta(elapsed, done, wanted):
    """Seconds left for `wanted` mutants at the pace of the `done` ones so far."""
    return elapsed / max(done, 1) * (wanted - done)


def prepare(args, labels):
    """Syncs and builds the scratch tree; `labels`' tests (None: all) must pass on it."""
    LOGS.mkdir(parents=True, exist_ok=True)
    SCRATCH.mkdir(parents=True, exist_ok=True)
    print(f"mutation-test: scratch tree {SCRATCH.relative_to(ROOT)}: "
          f"{sync_scratch()} files copied", flush=True)
    print("mutation-test: building the unmutated tree ...", flush=True)
    if not build(args.jobs, LOGS / "baseline-build.log"):
        print(f"error: the unmutated tree does not build (see {LOGS / 'baseline-build.log'})",
              file=sys.stderr)
        return False
    what = "every test" if labels is None else "labels " + ", ".join(labels)
    print(f"mutation-test: baseline: {what} must pass unmutated ...", flush=True)
    if run_tests(labels, args.jobs, LOGS / "baseline-tests.log", args.timeout) != 0:
        print(f"error: tests fail on the unmutated tree (see {LOGS / 'baseline-tests.log'})",
              file=sys.stderr)
        return False
    return True


def try_mutant(m, args, executables, rest=False, all_labels=()):
    """(status, outcome) of mutant `m` in the scratch tree; rest: a survivor of its labels'
    tests meets every other test."""
    originals = apply(m, SCRATCH)
    labels, log, build_log = m["labels"], LOGS / f"{m['id']}.log", LOGS / f"{m['id']}.build.log"
    everything = set(labels) >= set(all_labels)
    try:
        if not build(args.jobs, build_log, needed_targets(labels, executables)):
            return "invalid", "INVALID (does not build)"
        if run_tests(labels, args.jobs, log, args.timeout) != 0:
            return "killed", f"killed by {first_failure(log)}"
        if not rest or everything:
            return "survived", "SURVIVED"
        if not build(args.jobs, build_log):
            return "invalid", "INVALID (the rest of the tree does not build)"
        if run_tests(labels, args.jobs, log, args.timeout, exclude=True) != 0:
            return "killed", f"killed by {first_failure(log)} (outside its labels)"
        return "survived", "SURVIVED (every test)"
    finally:
        for target, text in originals.items():
            target.write_text(text, errors="surrogateescape")


def random_main(args):
    try:
        mutants = random_mutants.Mutants(ROOT, args.since, args.seed, MUTATIONS / "coverage.toml")
        equivalent = random_mutants.load_equivalent(MUTATIONS / "equivalent_random.toml")
    except (subprocess.CalledProcessError, OSError, KeyError, ValueError,
            tomllib.TOMLDecodeError) as e:
        print(f"error: random mutants since {args.since}: {getattr(e, 'stderr', '') or e}",
              file=sys.stderr)
        return 2
    print(f"mutation-test: {mutants.summary()}", flush=True)
    if not mutants.candidates:
        print(f"error: no line changed since {args.since} can be mutated", file=sys.stderr)
        return 2
    if len(mutants.candidates) < args.random:
        print(f"mutation-test: warning: {len(mutants.candidates)} candidates, fewer than the "
              f"{args.random} asked for: every one is drawn", flush=True)
    try:
        source, wanted = mutants.select(args.random, args.only, args.label)
    except ValueError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.list:
        for m in random_mutants.first(source, wanted, equivalent):
            print(random_mutants.listing(m, equivalent))
        return 0

    started, all_labels = time.monotonic(), mutants.all_labels
    try:  # a report that cannot be written fails now, not after hours of mutants
        args.report.parent.mkdir(parents=True, exist_ok=True)
        with open(args.report, "a"):
            pass
    except OSError as e:
        print(f"error: --report: {args.report}: {e.strerror}", file=sys.stderr)
        return 2
    if not prepare(args, None if args.rest else mutants.labels()):
        return 2
    executables = targets_by_label()
    results, counted, invalid, loop_start = [], 0, 0, time.monotonic()
    while counted < wanted and invalid <= wanted:
        m = next(source, None)
        if m is None:
            break
        if m["id"] in equivalent:
            results.append({**m, "status": "equivalent", "outcome": equivalent[m["id"]]})
            continue
        t0 = time.monotonic()
        status, outcome = try_mutant(m, args, executables, args.rest, all_labels)
        counted += status != "invalid"
        invalid += status == "invalid"
        results.append({**m, "status": status, "outcome": outcome,
                        "seconds": time.monotonic() - t0})
        left = eta(time.monotonic() - loop_start, counted, wanted)
        k = "  -" if status == "invalid" else f"{counted:3}"  # an invalid one is replaced
        print(f"[{k}/{wanted}] {m['id']:44} {outcome} ({time.monotonic() - t0:.0f} s), "
              f"ETA {fmt_seconds(left)}", flush=True)
    build(args.jobs, LOGS / "restore-build.log")
    killed = mutants.write_report(args.report, results, wanted, args.rest)
    print(f"mutation-test: {fmt_seconds(time.monotonic() - started)} in all; report "
          f"{args.report}; {invalid} invalid (do not build), "
          f"{sum(r['status'] == 'equivalent' for r in results)} equivalent, not counted")
    for r in results:
        if r["status"] == "survived":
            print(f"  survivor: {r['id']} ({r['files']}:{r['line']})")
    rate = 100.0 * killed / counted if counted else 0.0
    print(f"mutation-test: killed {killed} of {counted} ({rate:.1f}%)")
    if args.min_rate is not None and (rate < args.min_rate or counted < wanted):
        print(f"mutation-test: below the standard: {rate:.1f}% of {counted} counted, "
              f"{args.min_rate:g}% of {wanted} required", file=sys.stderr)
        return 1
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", default="", help="comma-separated mutation ids to run")
    parser.add_argument("--label", default="", help="only mutations that name this label")
    parser.add_argument("--list", action="store_true", help="print the mutations and exit")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--timeout", type=int, default=600, help="seconds per test")
    parser.add_argument("--random", type=int, metavar="N", help="N random mutants instead")
    parser.add_argument("--since", help="random: lines changed since REV "
                        "(the working tree against it; default HEAD~1)")
    parser.add_argument("--seed", type=int, help="random: the draw's seed (1)")
    parser.add_argument("--report", type=Path, help="random: the Markdown report (JSON beside "
                        "it; default build/mutation/random-report.md)")
    parser.add_argument("--survivors-everything", dest="rest", action="store_true", default=None,
                        help="random: a survivor of its labels meets every other test (default)")
    parser.add_argument("--no-rest", dest="rest", action="store_false", help="random: no rest")
    parser.add_argument("--min-rate", type=float, metavar="P", help="random: exit 1 unless at "
                        "least P%% of N counted mutants are killed (the standard: 85, N >= 30)")
    args = parser.parse_args()
    random_only = [name for name in ("since", "seed", "report", "rest", "min_rate")
                   if getattr(args, name) is not None]
    if args.random is None and random_only:
        flag = "--" + random_only[0].replace("_", "-").replace("rest", "no-rest")
        print(f"error: {flag} goes with --random", file=sys.stderr)
        return 2
    if args.random is not None and args.random < 1:
        print(f"error: --random: {args.random} mutants; at least 1", file=sys.stderr)
        return 2
    args.since = "HEAD~1" if args.since is None else args.since
    args.seed = 1 if args.seed is None else args.seed
    args.report = args.report or ROOT / "build" / "mutation" / "random-report.md"
    args.rest = True if args.rest is None else args.rest
    os.environ.setdefault("XDG_RUNTIME_DIR", f"/tmp/penumbra-xdg-{os.getuid()}")
    Path(os.environ["XDG_RUNTIME_DIR"]).mkdir(mode=0o700, parents=True, exist_ok=True)
    if args.random is not None:
        return random_main(args)

    try:
        mutations = load_mutations(MUTATIONS)
        check_labels(mutations, random_mutants.load_coverage(MUTATIONS / "coverage.toml")[0])
        for m in mutations:  # every entry must apply to today's code before anything runs
            for e in m["edits"]:
                locate(m, e, (ROOT / e["file"]).read_text())
    except (ListError, OSError, tomllib.TOMLDecodeError) as e:
        print(f"error: tests/mutations: {e}", file=sys.stderr)
        return 2
    if args.only:
        wanted = set(args.only.split(","))
        unknown = wanted - {m["id"] for m in mutations}
        if unknown:
            print(f"error: --only: unknown mutation ids {sorted(unknown)}", file=sys.stderr)
            return 2
        mutations = [m for m in mutations if m["id"] in wanted]
    if args.label:
        mutations = [m for m in mutations if args.label in m["labels"]]
    if args.list:
        for m in mutations:
            note = " (equivalent)" if "equivalent" in m else ""
            print(f"{m['id']:44} {m['kind']:10} {','.join(m['labels']):22} {m['files']}{note}")
        return 0

    logs, started = LOGS, time.monotonic()  # build/mutation/logs
    active = [m for m in mutations if "equivalent" not in m]
    if not prepare(args, sorted({label for m in active for label in m["labels"]})):
        return 2
    print(f"mutation-test: baseline passed after {fmt_seconds(time.monotonic() - started)}; "
          f"{len(active)} mutations", flush=True)
    executables = targets_by_label()

    killed, survivors, invalid = [], [], []
    for n, m in enumerate(active, 1):
        t0 = time.monotonic()
        status, outcome = try_mutant(m, args, executables)
        {"killed": killed, "survived": survivors, "invalid": invalid}[status].append(m)
        print(f"[{n:3}/{len(active)}] {m['id']:44} {outcome} "
              f"({time.monotonic() - t0:.0f} s)", flush=True)

    # Leave the scratch build matching the unmutated tree for the next run.
    build(args.jobs, logs / "restore-build.log")
    total = len(killed) + len(survivors)
    percent = 100.0 * len(killed) / total if total else 0.0
    print(f"mutation-test: {fmt_seconds(time.monotonic() - started)} in all; logs in "
          f"{logs.relative_to(ROOT)}")
    for m in [m for m in mutations if "equivalent" in m]:
        print(f"  equivalent, not run: {m['id']}: {m['equivalent']}")
    for m in invalid:
        print(f"  invalid (fix the list): {m['id']} ({m['files']})")
    for m in survivors:
        print(f"  survivor: {m['id']} ({m['files']}): {m['why']}")
    print(f"mutation-test: killed {len(killed)} of {total} ({percent:.1f}%)")
    return 1 if invalid else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except BrokenPipeError:  # `--list | head`: the reader has what it wanted
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        sys.exit(0)
