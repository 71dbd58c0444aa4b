#!/usr/bin/env python3
"""Where the shared code names one technique: `make coupling`.

The frame should ask no technique-specific question (docs/architecture.md, "The technique list
and the modules"). This counts the lines of C++ outside src/shadows (src/, apps/, python/,
include/) that do:

- name a technique: `Technique::Sdf`, a string literal that is a technique's name ("pcss") or
  one of its own parameter keys ("pcss.maxRadius"), a module function (`smrtModule()`);
- read a one-technique capability: a TechniqueModule field that exactly one module of
  src/shadows sets (`.footprintFollowsLight`, ...). Declarations are not capabilities: a list
  (`std::vector<...Decl>`: `maps`, `depthPasses`, `postPasses`) or an optional one
  (`std::optional<...Decl>`: `tracedField`, the field built once per scene). The frame runs the
  passes and builds any module declares there, with the module's own shaders and parameter keys,
  without asking which one did.

Comments are skipped. With --check it exits 1 unless the count is the one tests/
technique_coupling.txt records (ctest's Tools.TechniqueCoupling: a change that adds a place
fails; one that removes places lowers the figure there).
"""
import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RECORD = "tests/technique_coupling.txt"
SCANNED = ["src", "apps", "python", "include"]
EXCLUDED = ["src/shadows"]


def techniques():
    """(Enum name, module function, CLI name) per line of the technique list."""
    rows = []
    text = (ROOT / "shaders/include/technique_list.h").read_text()
    registry = (ROOT / "src/shadows").glob("*.cpp")
    names = {}
    for path in registry:  # the CLI name a module registers: .name = "msm-soft"
        for m in re.finditer(r'Module\(\)\s*\{.*?\.name\s*=\s*"([a-z-]+)"', path.read_text(),
                             re.S):
            names[path.stem] = m.group(1)
    for m in re.finditer(r"^PENUMBRA_TECHNIQUE\(\d+,\s*(\w+),\s*(\w+),\s*\w+\)", text, re.M):
        enum, module = m.group(1), m.group(2)
        stem = re.sub(r"(?<!^)(?=[A-Z])", "_", module).lower()
        rows.append((enum, module, names.get(stem, stem.replace("_", "-"))))
    if not rows:  # a list this parser no longer reads would count no coupling at all
        raise SystemExit("error: shaders/include/technique_list.h: no PENUMBRA_TECHNIQUE line "
                         "read (id, Name, module, shader)")
    return rows


def module_fields(declarations=True):
    """The fields of struct TechniqueModule (without those whose type is a declaration)."""
    text = (ROOT / "src/shadows/technique.h").read_text()
    body = text[text.index("struct TechniqueModule {"):]
    body = body[:body.index("\n};")]
    fields = []
    for line in body.splitlines():
        line = line.split("//")[0].strip()
        m = re.search(r"\(\*(\w+)\)\(", line) or re.search(r"(\w+)(\s*=.*)?;$", line)
        if m and (declarations or not re.search(r"std::(vector|optional)<\w+Decl>", line)):
            fields.append(m.group(1))
    return fields


def one_technique_fields():
    """Module fields, declarations aside, that exactly one file of src/shadows sets."""
    setters = {}
    for path in sorted((ROOT / "src/shadows").glob("*.cpp")):
        text = path.read_text()
        for field in module_fields(declarations=False):
            if re.search(rf"\.{field}\s*=", text):
                setters.setdefault(field, set()).add(path.name)
    return sorted(f for f, files in setters.items() if len(files) == 1)


def code_of(line, in_block):
    """The line without comments; whether a block comment is still open after it."""
    out, i = "", 0
    while i < len(line):
        if in_block:
            end = line.find("*/", i)
            if end < 0:
                return out, True
            i, in_block = end + 2, False
        elif line.startswith("//", i):
            break
        elif line.startswith("/*", i):
            in_block = True
            i += 2
        else:
            out += line[i]
            i += 1
    return out, in_block


def places():
    rows = techniques()
    patterns = []
    for enum, module, name in rows:
        patterns.append((rf"\bTechnique::{enum}\b", f"Technique::{enum}"))
        patterns.append((rf"\b{module}Module\b", f"{module}Module"))
        patterns.append((rf'"{re.escape(name)}(\.\w+)?"', f'"{name}"'))
    for field in one_technique_fields():
        patterns.append((rf"(\.|->){field}\b", f".{field}"))
    found = []
    for top in SCANNED:
        for path in sorted((ROOT / top).rglob("*")):
            rel = path.relative_to(ROOT).as_posix()
            if path.suffix not in (".cpp", ".h") or any(rel.startswith(e) for e in EXCLUDED):
                continue
            in_block = False
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                code, in_block = code_of(line, in_block)
                hits = sorted({what for pattern, what in patterns if re.search(pattern, code)})
                if hits:
                    found.append((rel, number, hits))
    return found


def recorded(root):
    """The count tests/technique_coupling.txt records (its first line that is not a comment)."""
    for line in (root / RECORD).read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            return int(line.split()[0])
    raise ValueError(f"{RECORD}: no count")


def main(argv=None):
    global ROOT
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help=f"exit 1 unless the count is the one {RECORD} records")
    parser.add_argument("--quiet", action="store_true", help="the count alone")
    parser.add_argument("--root", type=Path, default=ROOT, help="the source tree (tests)")
    args = parser.parse_args(argv)
    ROOT = args.root
    found = places()
    if not args.quiet:
        print("one-technique fields: " + ", ".join(one_technique_fields()))
        for rel, number, hits in found:
            print(f"{rel}:{number}: {', '.join(hits)}")
    files = len({rel for rel, _, _ in found})
    print(f"{len(found)} places in {files} files outside src/shadows name a technique or a "
          f"one-technique field")
    if args.check:
        try:
            expected = recorded(ROOT)
        except (OSError, ValueError) as e:
            print(f"error: {e}", file=sys.stderr)
            return 2
        if len(found) != expected:
            advice = (f"lower the figure in {RECORD}" if len(found) < expected else
                      "a change named a technique outside src/shadows: ask the module instead")
            print(f"error: {len(found)} places, {RECORD} records {expected}: {advice}",
                  file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
