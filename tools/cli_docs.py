#!/usr/bin/env python3
"""docs/cli.md's generated regions, from the CLI's own option definitions.

`penumbra cli-reference` prints every region (the global options, each command's own options,
the option groups several commands share, the `--set` parameters), each between
`<!-- generated: NAME -->` and `<!-- end generated -->`. This tool puts them into the page in
place of the regions of the same name; the prose around them is the page's own.

  cli_docs.py --penumbra BIN --page docs/cli.md --write OUT   the page with fresh regions, to OUT
  cli_docs.py --penumbra BIN --page docs/cli.md --check       exit 1 with a diff if it is stale

`make cli-docs` refreshes docs/cli.md; the build writes the fresh page to its own directory and a
test runs --check.
"""
import argparse
import difflib
import re
import subprocess
import sys

REGION = re.compile(r"<!-- generated: ([a-z0-9-]+) -->\n(.*?)<!-- end generated -->\n", re.S)


def regions(text):
    found = {}
    for match in REGION.finditer(text):
        if match.group(1) in found:
            raise SystemExit(f"error: region {match.group(1)} appears twice")
        found[match.group(1)] = match.group(0)
    return found


def refreshed(page, generated):
    fresh = regions(generated)
    present = regions(page)
    missing = sorted(set(fresh) - set(present))
    unknown = sorted(set(present) - set(fresh))
    if missing or unknown:
        raise SystemExit("error: docs/cli.md: "
                         + (f"no place for the generated region(s) {', '.join(missing)}; add "
                            "`<!-- generated: NAME -->` / `<!-- end generated -->` lines where "
                            "each belongs" if missing else "")
                         + ("; " if missing and unknown else "")
                         + (f"region(s) {', '.join(unknown)} that the CLI no longer makes"
                            if unknown else ""))
    return REGION.sub(lambda m: fresh[m.group(1)], page)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--penumbra", required=True, help="the penumbra executable")
    parser.add_argument("--page", required=True, help="docs/cli.md")
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--write", metavar="OUT", help="write the refreshed page to OUT")
    mode.add_argument("--check", action="store_true", help="fail if the page is stale")
    args = parser.parse_args()
    generated = subprocess.run([args.penumbra, "cli-reference"], check=True,
                               capture_output=True, text=True).stdout
    with open(args.page, encoding="utf-8") as f:
        page = f.read()
    fresh = refreshed(page, generated)
    if args.write:
        with open(args.write, "w", encoding="utf-8") as f:
            f.write(fresh)
        return 0
    if fresh == page:
        return 0
    sys.stdout.writelines(difflib.unified_diff(page.splitlines(True), fresh.splitlines(True),
                                               args.page, "generated from the CLI"))
    print(f"error: {args.page} is stale: run `make cli-docs` and commit it", file=sys.stderr)
    return 1


if __name__ == "__main__":
    sys.exit(main())
