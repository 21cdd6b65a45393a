#!/usr/bin/env python3
"""Prints the README's table of the papers' claims from a demo run.

usage: scripts/claims-table.py OUT_DIR   (OUT_DIR as written by `armkit demo --out`)

One row per finding of every scenario's summary.json (claim, what armkit
measured, verdict), then the counts per verdict. The README's table is this
script's output, pasted; rerun it after a demo run to refresh it.
"""
import json
import pathlib
import sys


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    out = pathlib.Path(sys.argv[1])
    summaries = sorted(out.glob("*/summary.json"))
    if not summaries:
        print(f"{out}: no */summary.json (run `armkit demo --out {out}` first)", file=sys.stderr)
        return 1
    counts = {}
    checks = 0
    print("| scenario | the paper's claim | measured here | verdict |")
    print("|---|---|---|---|")
    for path in summaries:
        summary = json.loads(path.read_text())
        checks += summary["total"]
        for finding in summary.get("findings", []):
            cells = [summary["scenario"], finding["claim"], finding["measured"], finding["status"]]
            print("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
            counts[finding["status"]] = counts.get(finding["status"], 0) + 1
    print()
    total = sum(counts.values())
    print(
        f"{total} claims: {counts.get('reproduced', 0)} reproduced, "
        f"{counts.get('reproduced with deviation', 0)} reproduced with a stated deviation, "
        f"{counts.get('not reproduced', 0)} not reproduced; {checks} checks in the demo."
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
