#!/usr/bin/env python3
"""Prints the README's table of verdicts from assets/reproduce-results.jsonl."""
import json, pathlib

def fmt(x):
    return f"{x:.3g}"

rows = ["| id | paper's figures | verdict | whole relation | clauses (share of variants where it holds; paired effect median [95 % CI]) |", "|---|---|---|---|---|"]
for line in (pathlib.Path(__file__).parent.parent / "assets/reproduce-results.jsonl").open():
    d = json.loads(line)
    cl = []
    for c in d["clauses"]:
        s = f"{c['name']} {c['holds']['k']}/{c['holds']['n']}"
        e = c.get("effect")
        if e and e.get("median"):
            m = e["median"]
            pre = "×" if e["kind"] == "ratio" else ""
            unit = "" if e["unit"] in ("1", "") else " " + e["unit"]
            ci = m.get("ci95")
            s += f" ({pre}{fmt(m['median'])}{unit}" + (f" [{fmt(ci[0])}, {fmt(ci[1])}])" if ci else ")")
        cl.append(s)
    j = d["joint"]
    rows.append(f"| {d['id']} | {d['paper']} | **{d['verdict']}** | {j['k']}/{j['n']} | {'; '.join(cl)} |")
print("\n".join(rows))
