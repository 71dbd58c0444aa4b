#!/usr/bin/env python3
"""Stored figures as data, and a worse figure as a decision (docs/testing.md, "Baselines").

The GPU tests read their stored figures from tests/baselines/TABLE/SETUP.json. Two commands:

    tools/baselines.py store [--tests BIN | --measured DIR]   (`make baselines`)
        runs the tests that own stored figures with PENUMBRA_WRITE_BASELINES (or takes DIR
        already written), prints every figure that moved and writes build/baselines/diff.md;
        stores the new figures unless one got worse past its tolerance and
        tests/accepted_regressions.toml does not name it (then nothing is stored, exit 1).
    tools/baselines.py check                                  (a test of `make test`)
        walks every version of every baseline file in git's history, and the working tree:
        each figure that got worse from one version to the next past its tolerance must be
        named in tests/accepted_regressions.toml (file, row, figure, before and after); an
        entry that names a file but no change of it fails too (a typo accepts nothing).

Tolerance of "worse": an error figure (rmse, misclassified, acne, leak) is worse when it rises by
more than 2% of itself and by more than 1e-5 (a pixel or two of the stored set-ups): stored
figures are lavapipe's, bit-identical run after run, so anything past that is the code's doing.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
STORE = "tests/baselines"
ACCEPTED = "tests/accepted_regressions.toml"
RELATIVE, ABSOLUTE = 0.02, 1e-5
# Figures are stored with six decimals: this much apart is equal (and rounding is no regression).
SAME = 5e-7
OWNERS = "QualityTest.EveryCompareRow*:BiasTest.*"
SKIP = 77  # ctest's SKIP_RETURN_CODE


def worse(before, after):
    """Whether an error figure went from `before` to `after` by more than its tolerance."""
    return after - before > max(RELATIVE * abs(before), ABSOLUTE) + SAME


def load_tree(root):
    """{relative file name: {row: {figure: value}}} of every baseline file under root."""
    tables = {}
    for path in sorted(Path(root).rglob("*.json")):
        tables[f"{STORE}/{path.relative_to(root).as_posix()}"] = json.loads(path.read_text())["rows"]
    return tables


def moves(name, old_rows, new_rows):
    """Every figure that changed between two versions of one file: (file, row, figure, before,
    after); a row or figure only one side has shows None on the other."""
    out = []
    for row in sorted(set(old_rows) | set(new_rows)):
        old, new = old_rows.get(row, {}), new_rows.get(row, {})
        for figure in sorted(set(old) | set(new)):
            before, after = old.get(figure), new.get(figure)
            if before is None or after is None or abs(after - before) > SAME:
                out.append((name, row, figure, before, after))
    return out


def regressions(changes):
    """The changes that are worse past their tolerance (a figure that disappears is not: the
    test fails on a row it does not measure, and a new figure has no before)."""
    return [c for c in changes if c[3] is not None and c[4] is not None and worse(c[3], c[4])]


def load_accepted(path):
    text = Path(path).read_text() if Path(path).exists() else ""
    return [e for e in tomllib.loads(text).get("regression", []) if "file" in e]


def accepted_by(entry, change):
    name, row, figure, before, after = change
    pair = entry.get("figures", {}).get(figure)
    return (entry["file"] == name and entry.get("row") == row and pair is not None
            and abs(pair[0] - before) <= SAME and abs(pair[1] - after) <= SAME)


def unaccepted(changes, entries, used):
    """The regressions among changes that no entry accepts; marks the entries used."""
    left = []
    for change in regressions(changes):
        hits = [i for i, e in enumerate(entries) if accepted_by(e, change)]
        used.update(hits)
        if not hits:
            left.append(change)
    return left


def describe(change):
    name, row, figure, before, after = change
    fmt = lambda v: "-" if v is None else f"{v:.6f}"
    return f"{name}: {row} {figure} {fmt(before)} -> {fmt(after)}"


def diff_markdown(changes):
    lines = ["| file | row | figure | stored | measured | change |", "|---|---|---|---|---|---|"]
    for name, row, figure, before, after in changes:
        if before is None or after is None:
            change = "new" if before is None else "gone"
        else:
            change = "worse" if worse(before, after) else ("better" if after < before else "same")
        fmt = lambda v: "-" if v is None else f"{v:.6f}"
        lines.append(f"| {name} | {row} | {figure} | {fmt(before)} | {fmt(after)} | {change} |")
    return "\n".join(lines) + "\n"


def store(args):
    measured = args.measured
    if measured is None:
        measured = args.out / "measured"
        shutil.rmtree(measured, ignore_errors=True)
        env = dict(os.environ, PENUMBRA_WRITE_BASELINES=str(measured))
        print(f"baselines: measuring ({OWNERS}); this takes minutes", flush=True)
        done = subprocess.run([str(args.tests), f"--gtest_filter={OWNERS}"], env=env)
        if done.returncode != 0:
            print(f"error: {args.tests}: the tests that measure the figures failed", file=sys.stderr)
            return 2
    old, new = load_tree(args.root / STORE), load_tree(measured)
    if not new:
        print(f"error: {measured}: no figures were written", file=sys.stderr)
        return 2
    changes = []
    for name in sorted(set(old) | set(new)):
        if name in new:
            changes += moves(name, old.get(name, {}), new[name])
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "diff.md").write_text(diff_markdown(changes))
    for change in changes:
        print(f"baselines: moved: {describe(change)}")
    entries = load_accepted(args.root / ACCEPTED)
    refused = unaccepted(changes, entries, set())
    for change in refused:
        print(f"error: {describe(change)} is worse and {ACCEPTED} does not name it",
              file=sys.stderr)
    if refused:
        print(f"baselines: nothing stored; name each in {ACCEPTED} with its reason, or fix it",
              file=sys.stderr)
        return 1
    for path in sorted(Path(measured).rglob("*.json")):
        target = args.root / STORE / path.relative_to(measured)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(path, target)
    print(f"baselines: {len(changes)} figures moved, stored; {args.out / 'diff.md'}")
    return 0


def git(root, *command):
    return subprocess.run(["git", "-C", str(root), *command], capture_output=True, text=True,
                          check=True).stdout


def versions(root, name):
    """Every committed version of one file, oldest first, then the working tree's."""
    found = []
    for commit in reversed(git(root, "log", "--format=%H", "--", name).split()):
        try:
            found.append((commit[:10], json.loads(git(root, "show", f"{commit}:{name}"))["rows"]))
        except subprocess.CalledProcessError:
            found.append((commit[:10], None))  # deleted in this commit
    path = Path(root) / name
    found.append(("working tree", json.loads(path.read_text())["rows"] if path.exists() else None))
    return found


def check(args):
    # The history is the source tree's own: a copy inside another repository's work tree (a
    # tarball unpacked in one, the mutation runner's scratch tree) has none.
    try:
        top = Path(git(args.root, "rev-parse", "--show-toplevel").strip()).resolve()
    except (OSError, subprocess.CalledProcessError):
        top = None
    if top != Path(args.root).resolve():
        print(f"baselines: {args.root} is not a git checkout of its own: no history to check")
        return SKIP
    names = set(git(args.root, "log", "--format=", "--name-only", "--", STORE).split())
    names |= set(load_tree(args.root / STORE))
    entries = load_accepted(args.root / ACCEPTED)
    used, failures, steps = set(), [], 0
    for name in sorted(names):
        history = [(at, rows) for at, rows in versions(args.root, name) if rows is not None]
        for (_, old), (at, new) in zip(history, history[1:]):
            steps += 1
            failures += [(at, c) for c in unaccepted(moves(name, old, new), entries, used)]
    for at, change in failures:
        print(f"error: {describe(change)} (at {at}) is worse and {ACCEPTED} does not name it",
              file=sys.stderr)
    stale = [e for i, e in enumerate(entries) if i not in used]
    for e in stale:
        print(f"error: {ACCEPTED}: the entry for {e['file']} row {e.get('row')} names no change "
              "any version of the file made", file=sys.stderr)
    shallow = git(args.root, "rev-parse", "--is-shallow-repository").strip() == "true"
    print(f"baselines: {len(names)} files, {steps} re-stores checked"
          + (" (a shallow clone: only the history it has)" if shallow else ""))
    return 1 if failures or stale else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", type=Path, default=ROOT, help="the source tree")
    sub = parser.add_subparsers(dest="command", required=True)
    s = sub.add_parser("store", help="measure, show what moved, store unless refused")
    s.add_argument("--tests", type=Path, default=ROOT / "build/release/tests/penumbra_gpu_tests")
    s.add_argument("--measured", type=Path, help="figures already written (skips measuring)")
    s.add_argument("--out", type=Path, default=ROOT / "build/baselines")
    sub.add_parser("check", help="every re-store in git's history is accepted")
    args = parser.parse_args()
    return store(args) if args.command == "store" else check(args)


if __name__ == "__main__":
    sys.exit(main())
