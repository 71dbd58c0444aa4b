#!/usr/bin/env python3
"""The CLI's parameter space, fuzzed: random commands with random `--set` values (in range, at
the ends, past them, malformed) and random option combinations. Every run must end either in
success with its outputs, or in exactly one `error:` line, exit 2 or 3 and no output; anything
else (a signal, another exit code, two error lines, a validation message, a leftover output, a
hang) is a finding, written with its command line to DIR/findings.txt.

    tools/fuzz_cli.py [--seconds S] [--seed N] [--out DIR] [--jobs N] [--cli PATH]

Images are kept small so that a run takes about a second on lavapipe; absurd sizes are among
the values tried, and the CLI must refuse them before any work.
"""
import argparse
import concurrent.futures
import json
import os
import random
import shutil
import subprocess
import sys
import time

SCENES = ["builtin:demo", "builtin:spot", "builtin:room", "builtin:showcase", "builtin:grazing",
          "builtin:nope", "missing.gltf", ""]
HOSTILE = ["", "nan", "NaN", "inf", "-inf", "1e400", "-1", "0", "-0", "1e-45", "0x10", "1,2",
           "abc", "1e9", "4294967296", "18446744073709551617", " 1", "1 ", "+1", "--", "é", "1.5.2"]


def techniques(cli):
    out = subprocess.run([cli, "techniques", "--json"], capture_output=True, text=True,
                         check=True).stdout
    return json.loads(out)


def value_for(param, rng):
    """A value for one parameter: mostly valid, sometimes an end, past an end or hostile."""
    roll = rng.random()
    if roll < 0.06:
        return rng.choice(HOSTILE)
    if param["type"] == "choice":
        return rng.choice(param["choices"]) if roll < 0.9 else rng.choice(param["choices"]) + "x"
    if param["type"] == "bool":
        return rng.choice(["true", "false", "1", "0", "on", "off", "yes", "2"])
    lo, hi = param["min"], param["max"]
    if roll < 0.3:
        edge = rng.choice([lo, hi])
        return repr(edge + rng.choice([0, 0, -1e-3, 1e-3, -1, 1]) * max(1.0, abs(edge)) * 0.5)
    value = rng.uniform(lo, hi)
    return str(int(round(value))) if param["type"] == "int" else repr(value)


def size(rng):
    return (str(rng.choice([8, 16, 24, 33, 48])) if rng.random() < 0.97
            else rng.choice(HOSTILE + ["100000", "65536"]))


def command(rng, table, out):
    """One random invocation and the outputs it would write."""
    verb = rng.choice(["render", "render", "compare", "reference", "bench", "tune"])
    technique = rng.choice(table)
    scene = rng.choice(SCENES) if rng.random() < 0.1 else rng.choice(SCENES[:5])
    args = [verb, scene] if scene else [verb]
    outputs = [out]
    if verb == "bench":
        args += ["-o", os.path.join(out, "bench.json"), "--frames", "1"]
        outputs = [os.path.join(out, "bench.json"), os.path.join(out, "bench.html")]
    else:
        args += ["-o", out]
    if verb in ("render", "tune"):
        args += ["--technique", technique["name"] if rng.random() < 0.95 else rng.choice(HOSTILE)]
    if verb in ("compare", "bench"):
        names = rng.sample([t["name"] for t in table], k=rng.randint(1, 2))
        args += ["--techniques", ",".join(names)]
    if verb in ("render",):
        args += ["--frames", "1" if rng.random() < 0.9 else rng.choice(HOSTILE)]
    if verb in ("compare", "reference", "tune"):
        args += ["--samples", "1" if rng.random() < 0.9 else rng.choice(HOSTILE)]
    args += ["--width", size(rng), "--height", size(rng)]
    if verb != "reference":
        args += ["--shadow-map-size", str(rng.choice([32, 64, 128])) if rng.random() < 0.9
                 else rng.choice(HOSTILE + ["3", "1000000"])]
    for _ in range(rng.randint(0, 4) if verb != "reference" else 0):
        param = rng.choice(technique["parameters"])
        key = param["key"] if rng.random() < 0.95 else param["key"] + rng.choice(["x", ".", ""])
        args += ["--set", f"{key}={value_for(param, rng)}"]
    if verb in ("tune", "bench") and rng.random() < 0.7:
        param = rng.choice(technique["parameters"])
        values = ",".join(value_for(param, rng) for _ in range(rng.randint(1, 3)))
        args += ["--sweep", f"{param['key']}={values}"]
    extras = [["--light-radius", rng.choice(["0.1", "0", "-1", "nan", "1e30"])],
              ["--light-angle", rng.choice(["1", "0", "180", "nan", "-3"])],
              ["--fov", rng.choice(["60", "0", "180", "nan", "1e9"])],
              ["--camera-pos", rng.choice(["0,5,10", "nan,0,0", "1,2", "0,0,0"])],
              ["--look-at", rng.choice(["0,0,0", "inf,0,0", "1,2,3,4"])],
              ["--sun-dir", rng.choice(["0,-1,0", "0,0,0", "nan,1,0"])],
              ["--camera", rng.choice(["main", "nope", ""])],
              ["--light-pos", rng.choice(["0,4,0", "nan,1,1", "0,4"])],
              ["--light-dir", rng.choice(["0,-1,0", "0,0,0"])]]
    if rng.random() < 0.4:
        for extra in rng.sample(extras, k=rng.randint(1, 2)):
            args += extra
    if verb == "compare" and rng.random() < 0.2:
        args += ["--camera-path", rng.choice(["dolly", "orbit", "sun", "spin"]), "--path-frames",
                 rng.choice(["2", "3", "0", "100000"])]
    if verb == "render" and rng.random() < 0.1:
        args += ["--field-slice", rng.choice(["0.5", "-1", "nan", "2"])]
    return args, outputs


def judge(cli, args, outputs, timeout):
    for o in outputs:
        if os.path.isdir(o):
            shutil.rmtree(o)
        elif os.path.exists(o):
            os.remove(o)
    try:
        r = subprocess.run([cli, "--validation"] + args, capture_output=True, text=True,
                           timeout=timeout, errors="replace")
    except subprocess.TimeoutExpired:
        return "hang", ""
    errors = [line for line in r.stderr.splitlines() if line.startswith("error:")]
    if "vulkan validation" in r.stderr:
        return "validation message", r.stderr[-800:]
    if r.returncode == 0:
        return (None if os.path.exists(outputs[0]) else "success without output"), ""
    if r.returncode not in (2, 3):
        return f"exit {r.returncode}", r.stderr[-800:]
    if len(errors) != 1:
        return f"{len(errors)} error lines", r.stderr[-800:]
    left = [o for o in outputs if os.path.exists(o)]
    return (f"output left: {left}" if left else None), errors[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=600)
    parser.add_argument("--seed", type=int, default=int(time.time()))
    parser.add_argument("--out", default="build/fuzz-cli")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=120)
    parser.add_argument("--cli", default="build/release/apps/penumbra/penumbra")
    a = parser.parse_args()
    os.makedirs(a.out, exist_ok=True)
    table = techniques(a.cli)
    rng = random.Random(a.seed)
    start, runs, outcomes, findings = time.time(), 0, {}, []
    print(f"fuzz-cli: seed {a.seed}, {a.seconds:.0f} s, {a.jobs} jobs")

    def one(index, args, outputs):
        verdict = judge(a.cli, args, outputs, a.timeout)
        shutil.rmtree(os.path.join(a.out, "runs", str(index)), ignore_errors=True)
        return index, args, verdict

    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        pending = set()
        index = 0
        while time.time() - start < a.seconds or pending:
            while time.time() - start < a.seconds and len(pending) < a.jobs:
                args, outputs = command(rng, table, os.path.join(a.out, "runs", str(index)))
                pending.add(pool.submit(one, index, args, outputs))
                index += 1
            done, pending = concurrent.futures.wait(pending, return_when="FIRST_COMPLETED")
            for future in done:
                _, args, (problem, said) = future.result()
                runs += 1
                # The subject of the refusal ("error: --width: ..." -> "--width"), or ok.
                kind = "finding" if problem else (said.split(":")[1].strip() if said else "ok")
                outcomes[kind] = outcomes.get(kind, 0) + 1
                if problem:
                    line = f"{problem}: penumbra --validation {' '.join(args)}\n{said}\n"
                    findings.append(line)
                    with open(os.path.join(a.out, "findings.txt"), "a") as f:
                        f.write(line)
                    print("FINDING", line, flush=True)
            elapsed = time.time() - start
            if runs and runs % 50 == 0:
                print(f"fuzz-cli: {runs} runs in {elapsed:.0f} s, {len(findings)} findings",
                      flush=True)
    print(f"fuzz-cli: {runs} runs, {len(findings)} findings; outcomes by subject:")
    for kind, count in sorted(outcomes.items(), key=lambda kv: -kv[1])[:25]:
        print(f"  {count:6d}  {kind}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
