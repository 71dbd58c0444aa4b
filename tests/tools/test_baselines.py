"""Stored figures as data (tools/baselines.py): what counts as worse, the re-store that refuses
an unnamed regression, and the history check over a scratch git repository."""
import json
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import baselines  # noqa: E402

TOOL = Path(baselines.__file__)
FILE = "tests/baselines/compare-rows/sun.json"


def write_rows(root, rows, name=FILE):
    path = Path(root) / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps({"setup": "a sun", "rows": rows}))


def accept(root, entries):
    lines = []
    for e in entries:
        lines += ["[[regression]]", f'file = "{e["file"]}"', f'row = "{e["row"]}"',
                  "figures = { " + ", ".join(f"{k} = [{a}, {b}]" for k, (a, b) in
                                             e["figures"].items()) + " }",
                  'reason = "on purpose"']
    (Path(root) / "tests").mkdir(parents=True, exist_ok=True)
    (Path(root) / baselines.ACCEPTED).write_text("\n".join(lines) + "\n")


def run(*args):
    return subprocess.run([sys.executable, str(TOOL), *args], capture_output=True, text=True)


def git(root, *args):
    subprocess.run(["git", "-C", str(root), *args], check=True, capture_output=True)


def repo(tmp_path, first):
    git(tmp_path, "init", "-q")
    git(tmp_path, "config", "user.email", "t@example.invalid")
    git(tmp_path, "config", "user.name", "t")
    write_rows(tmp_path, first)
    accept(tmp_path, [])
    commit(tmp_path, "first")
    return tmp_path


def commit(root, message):
    git(root, "add", "-A")
    git(root, "commit", "-q", "-m", message)


def test_worse_means_past_two_percent_and_past_the_floor():
    assert not baselines.worse(0.0100, 0.0102)  # 2% exactly
    assert baselines.worse(0.0100, 0.010201)
    assert not baselines.worse(0.0, 0.00001)  # the floor
    assert baselines.worse(0.0, 0.000011)
    assert not baselines.worse(0.02, 0.001), "better is not worse"


def test_moves_name_every_changed_figure_and_regressions_only_the_worse():
    old = {"hard": {"rmse": 0.02, "leak": 0.0}, "gone": {"rmse": 0.1}}
    new = {"hard": {"rmse": 0.03, "leak": 0.0}, "new": {"rmse": 0.5}}
    changes = baselines.moves("f", old, new)
    assert ("f", "hard", "rmse", 0.02, 0.03) in changes
    assert ("f", "gone", "rmse", 0.1, None) in changes
    assert ("f", "new", "rmse", None, 0.5) in changes
    assert not any(c[1] == "hard" and c[2] == "leak" for c in changes), "leak did not move"
    assert baselines.regressions(changes) == [("f", "hard", "rmse", 0.02, 0.03)]


def test_an_entry_accepts_only_its_file_row_figure_and_values():
    change = (FILE, "sdf", "rmse", 0.02769, 0.02861)
    entry = {"file": FILE, "row": "sdf", "figures": {"rmse": [0.02769, 0.02861]}}
    assert baselines.accepted_by(entry, change)
    assert not baselines.accepted_by(dict(entry, row="smrt"), change)
    assert not baselines.accepted_by(dict(entry, file="other.json"), change)
    assert not baselines.accepted_by(dict(entry, figures={"rmse": [0.02769, 0.0287]}), change)
    assert not baselines.accepted_by(dict(entry, figures={"leak": [0.02769, 0.02861]}), change)


def test_history_check_fails_on_an_unnamed_regression_and_passes_once_named(tmp_path):
    root = repo(tmp_path, {"hard": {"rmse": 0.020, "acne": 0.001}})
    write_rows(root, {"hard": {"rmse": 0.010, "acne": 0.001}})
    commit(root, "better")
    passed = run("--root", str(root), "check")
    assert passed.returncode == 0
    # Two steps: the first commit to the second, the second to the working tree.
    assert "baselines: 1 files, 2 re-stores checked" in passed.stdout
    write_rows(root, {"hard": {"rmse": 0.010, "acne": 0.002}})
    commit(root, "worse acne")
    failed = run("--root", str(root), "check")
    assert failed.returncode == 1
    assert "hard acne 0.001000 -> 0.002000" in failed.stderr
    accept(root, [{"file": FILE, "row": "hard", "figures": {"acne": [0.001, 0.002]}}])
    assert run("--root", str(root), "check").returncode == 0
    # The working tree counts too, before anything is committed.
    write_rows(root, {"hard": {"rmse": 0.011, "acne": 0.002}})
    assert "hard rmse 0.010000 -> 0.011000" in run("--root", str(root), "check").stderr


def test_history_check_refuses_an_entry_that_names_no_change(tmp_path):
    root = repo(tmp_path, {"hard": {"rmse": 0.020}})
    accept(root, [{"file": FILE, "row": "hard", "figures": {"rmse": [0.02, 0.03]}}])
    failed = run("--root", str(root), "check")
    assert failed.returncode == 1 and "names no change" in failed.stderr


def test_history_check_skips_outside_git(tmp_path):
    write_rows(tmp_path, {"hard": {"rmse": 0.02}})
    assert run("--root", str(tmp_path), "check").returncode == baselines.SKIP


def test_history_check_skips_a_copy_inside_another_repository(tmp_path):
    """A source tree copied into another repository's work tree (an ignored folder, as the
    mutation runner's scratch tree) has no history of its own: skipped, not failed."""
    outer = repo(tmp_path, {"hard": {"rmse": 0.02}})
    (outer / ".gitignore").write_text("copy/\n")
    copy = outer / "copy"
    write_rows(copy, {"hard": {"rmse": 0.03}})
    accept(copy, [{"file": FILE, "row": "hard", "figures": {"rmse": [0.02, 0.03]}}])
    assert run("--root", str(copy), "check").returncode == baselines.SKIP


def test_store_refuses_an_unnamed_regression_and_stores_nothing(tmp_path):
    root = tmp_path / "src"
    write_rows(root, {"hard": {"rmse": 0.020}, "pcf": {"rmse": 0.030}})
    accept(root, [])
    measured = tmp_path / "measured"
    write_rows(measured, {"hard": {"rmse": 0.025}, "pcf": {"rmse": 0.020}},
               name="compare-rows/sun.json")
    out = tmp_path / "out"
    refused = run("--root", str(root), "store", "--measured", str(measured), "--out", str(out))
    assert refused.returncode == 1
    assert "hard rmse 0.020000 -> 0.025000 is worse" in refused.stderr
    assert "pcf" not in refused.stderr, "a better figure is no regression"
    assert json.loads((root / FILE).read_text())["rows"]["hard"]["rmse"] == 0.020
    diff = (out / "diff.md").read_text()
    assert "| hard | rmse | 0.020000 | 0.025000 | worse |" in diff
    assert "| pcf | rmse | 0.030000 | 0.020000 | better |" in diff
    accept(root, [{"file": FILE, "row": "hard", "figures": {"rmse": [0.020, 0.025]}}])
    stored = run("--root", str(root), "store", "--measured", str(measured), "--out", str(out))
    assert stored.returncode == 0, stored.stderr
    assert json.loads((root / FILE).read_text())["rows"]["hard"]["rmse"] == 0.025


def test_the_stored_files_are_what_the_tests_read():
    """Every file under tests/baselines parses, and each row's figures are error figures."""
    tables = baselines.load_tree(baselines.ROOT / baselines.STORE)
    assert len(tables) >= 12
    for name, rows in tables.items():
        assert rows, name
        for row, figures in rows.items():
            assert set(figures) <= {"rmse", "misclassified", "acne", "leak"}, (name, row)
            assert all(0 <= v <= 1 for v in figures.values()), (name, row)
