"""The Makefile's steps: tools/timed.sh's line and exit status, and `make deps` handing every
missing package to apt-get as its own argument (SUDO=echo stands in for the install)."""
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent


def run(*cmd):
    return subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)


def test_timed_says_how_long_a_step_took_and_passes_its_status_on():
    ok = run("tools/timed.sh", "the thing done", "true")
    assert ok.returncode == 0
    # The seconds are the clock's: a loaded machine may cross a second boundary.
    assert re.fullmatch(r"penumbra: the thing done: 0 min 0[0-9] s\n", ok.stdout), ok.stdout
    failed = run("tools/timed.sh", "the thing done", "sh", "-c", "exit 3")
    assert failed.returncode == 3
    assert re.fullmatch(r"penumbra: the thing done: failed after 0 min 0[0-9] s\n",
                        failed.stderr), failed.stderr


def test_deps_installs_each_missing_package_as_one_argument():
    r = run("make", "--no-print-directory", "deps", "SUDO=echo",
            "PACKAGES=penumbra-absent-one penumbra-absent-two")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert "apt-get update -qq" in lines
    assert ("apt-get install -y -qq --no-install-recommends penumbra-absent-one "
            "penumbra-absent-two") in lines
    assert lines[-1].startswith("penumbra: the missing packages installed: ")
