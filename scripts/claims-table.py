#!/usr/bin/env python3
"""Prints the README's table of the papers' claims from a demo run.

usage: scripts/claims-table.py OUT_DIR   (OUT_DIR as written by `armkit demo --out`)

One row per finding of every scenario's summary.json (claim, what armkit
measured, verdict), then the counts per verdict, then the invariants apart
(checks true by construction: never evidence for a claim). The README's table is this
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
    invariants = 0
    duplicates = 0
    print("| scenario | the paper's claim | measured here | verdict |")
    print("|---|---|---|---|")
    for path in summaries:
        summary = json.loads(path.read_text())
        checks += summary["total"]
        invariants += len(summary.get("invariants", []))
        for finding in summary.get("findings", []):
            verdict = finding["status"]
            if finding.get("same_evidence_as"):
                verdict += f" (same evidence as {finding['same_evidence_as']}; not counted)"
                duplicates += 1
            else:
                counts[finding["status"]] = counts.get(finding["status"], 0) + 1
            cells = [summary["scenario"], finding["claim"], finding["measured"], verdict]
            print("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    rows = []
    for path in summaries:
        summary = json.loads(path.read_text())
        for check in summary.get("invariants", []):
            value = f"{check['value']:.3g} {check['comparison']} {check['threshold']:.3g} {check['unit']}".strip()
            rows.append([summary["scenario"], check["name"], value])
    print()
    total = sum(counts.values())
    print(
        f"{total} claims: {counts.get('reproduced', 0)} reproduced, "
        f"{counts.get('reproduced with deviation', 0)} reproduced with a stated deviation, "
        f"{counts.get('not reproduced', 0)} not reproduced, "
        f"{counts.get('not attempted', 0)} not attempted ({duplicates} more rows restate counted "
        f"evidence); {checks} checks and {invariants} invariants (true by construction, not "
        f"evidence) in the demo."
    )
    if rows:
        print()
        print("Invariants of the implementation (true by construction; kept as tests, not counted as evidence):")
        print()
        print("| scenario | invariant | value |")
        print("|---|---|---|")
        for cells in rows:
            print("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
