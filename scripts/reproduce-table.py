#!/usr/bin/env python3
"""Prints the README's table of verdicts from assets/reproduce-results.jsonl.

Every share carries its Wilson 95 % interval (as percentages); the last
column is the family's sensitivity summary (reproduce/sensitivity.rs).
With --diff OLD.jsonl it prints, instead, the experiments whose verdict
differs between OLD and the current file."""
import json, pathlib, sys

ROOT = pathlib.Path(__file__).parent.parent


def fmt(x):
    return f"{x:.3g}"


def share(s):
    lo, hi = s["ci95"]
    return f"{s['k']}/{s['n']} [{round(100 * lo)}–{round(100 * hi)} %]"


def load(p):
    return [json.loads(l) for l in pathlib.Path(p).open() if l.strip()]


if len(sys.argv) == 3 and sys.argv[1] == "--diff":
    old = {d["id"]: d for d in load(sys.argv[2])}
    for d in load(ROOT / "assets/reproduce-results.jsonl"):
        o = old.get(d["id"])
        if o and o["verdict"] != d["verdict"]:
            print(f"{d['id']}: {o['verdict']} {o['joint']['k']}/{o['joint']['n']} -> {d['verdict']} {share(d['joint'])}")
    sys.exit(0)

rows = [
    "| id | paper's figures | verdict | whole relation [Wilson 95 %] | clauses (share of variants where it holds [Wilson 95 %]; paired effect median [95 % CI]) | most sensitive to |",
    "|---|---|---|---|---|---|",
]
for d in load(ROOT / "assets/reproduce-results.jsonl"):
    cl = []
    for c in d["clauses"]:
        s = f"{c['name']} {share(c['holds'])}"
        e = c.get("effect")
        if e and e.get("median"):
            m = e["median"]
            pre = "×" if e["kind"] == "ratio" else ""
            unit = "" if e["unit"] in ("1", "") else " " + e["unit"]
            ci = m.get("ci95")
            s += f" ({pre}{fmt(m['median'])}{unit}" + (f" [{fmt(ci[0])}, {fmt(ci[1])}])" if ci else ")")
        cl.append(s)
    sens = d.get("sensitivity", {}).get("summary", "")
    rows.append(
        f"| {d['id']} | {d['paper']} | **{d['verdict']}** | {share(d['joint'])} | {'; '.join(cl)} | {sens} |"
    )
print("\n".join(rows))
