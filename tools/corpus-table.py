#!/usr/bin/env python3
"""Corpus table before/after: parts, score and verify per model and method.

Usage: tools/corpus-table.py [--baseline DIR] [--after DIR] [--bin PATH] [--corpus DIR] [--jobs N]

BASELINE holds batch.json and the old ZIPs (`platener convert --method all CORPUS -o DIR --json
> DIR/batch.json`). When AFTER has no batch.json, the corpus is converted into it with BIN
first. Every ZIP of both runs is then checked with `BIN verify ZIP --model MODEL --json`
(today's verify, so old and new plans are judged by the same rules). Prints a Markdown table
and the totals; writes AFTER/table.json with every figure.
"""
import argparse
import json
import os
import subprocess
from concurrent.futures import ThreadPoolExecutor


def load(path):
    with open(path) as f:
        return json.load(f)


def verify(binary, zip_path, model):
    if not zip_path or not os.path.exists(zip_path):
        return None
    out = subprocess.run([binary, "verify", zip_path, "--model", model, "--json"],
                         capture_output=True, text=True)
    try:
        v = json.loads(out.stdout)
    except json.JSONDecodeError:
        return {"passed": False, "checks": ["error: " + out.stderr.strip()[:80]]}
    checks = sorted({f["check"] for f in v.get("failures", [])})
    return {"passed": not v.get("failures"), "checks": checks, "groups": v.get("groups"),
            "problems": v.get("problems", [])}


def rows(batch):
    out = {}
    for m in batch["models"]:
        for x in m["methods"]:
            out[(m["stem"], x["method"])] = {
                "file": m["file"], "status": x["status"], "zip": x.get("zip"),
                "parts": x.get("parts"),
                "score": (x.get("score") or {}).get("total"),
                "best": m.get("best") == x["method"],
            }
    return out


def fmt_score(s):
    return "—" if s is None else f"{s:.3f}"


def fmt_verify(v):
    if v is None:
        return "—"
    return "pass" if v["passed"] else "FAIL " + ",".join(v["checks"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--baseline", default="/tmp/baseline")
    ap.add_argument("--after", default="/tmp/score-after")
    ap.add_argument("--bin", default="target/release/platener")
    ap.add_argument("--corpus", default="/work/shared/corpus")
    ap.add_argument("--jobs", type=int, default=2)
    a = ap.parse_args()
    after_json = os.path.join(a.after, "batch.json")
    if not os.path.exists(after_json):
        os.makedirs(a.after, exist_ok=True)
        with open(after_json, "w") as f:
            subprocess.run([a.bin, "convert", "--method", "all", a.corpus, "-o", a.after, "--json"],
                           stdout=f)
    before, after = rows(load(os.path.join(a.baseline, "batch.json"))), rows(load(after_json))
    keys = sorted(k for k in set(before) | set(after)
                  if (before.get(k) or {}).get("zip") or (after.get(k) or {}).get("zip"))
    jobs = []
    for k in keys:
        for side in (before, after):
            r = side.get(k) or {}
            jobs.append((r.get("zip"), r.get("file") or (before.get(k) or after.get(k))["file"]))
    with ThreadPoolExecutor(a.jobs) as pool:
        results = list(pool.map(lambda j: verify(a.bin, *j), jobs))
    table = []
    print("| model | method | parts before → after | score before → after | verify before → after |")
    print("|---|---|---|---|---|")
    for i, k in enumerate(keys):
        b, f = before.get(k) or {}, after.get(k) or {}
        vb, va = results[2 * i], results[2 * i + 1]
        mark = lambda r: "*" if r.get("best") else ""
        print(f"| {k[0]} | {k[1]} | {b.get('parts', '—')} → {f.get('parts', '—')} | "
              f"{fmt_score(b.get('score'))}{mark(b)} → {fmt_score(f.get('score'))}{mark(f)} | "
              f"{fmt_verify(vb)} → {fmt_verify(va)} |")
        table.append({"model": k[0], "method": k[1], "before": b, "after": f,
                      "verify_before": vb, "verify_after": va})
    passed = lambda side: sum(1 for t in table if (t[side] or {}).get("passed"))
    plans = lambda side: sum(1 for t in table if t[side] is not None)
    best_fail = lambda s, v: sum(1 for t in table if t[s].get("best") and t[v] and not t[v]["passed"])
    print(f"\nplans: {plans('verify_before')} before, {plans('verify_after')} after; "
          f"verify passes {passed('verify_before')} before, {passed('verify_after')} after")
    print(f"best plans that verify fails: {best_fail('before', 'verify_before')} before, "
          f"{best_fail('after', 'verify_after')} after  (* = named best)")

    def overruled(s, v):
        # Models whose best plan fails verify while another of their plans passes.
        models = {t["model"] for t in table}
        count = 0
        for m in models:
            mine = [t for t in table if t["model"] == m]
            best = [t for t in mine if t[s].get("best")]
            if best and best[0][v] and not best[0][v]["passed"] and any(t[v] and t[v]["passed"] for t in mine):
                count += 1
        return count
    print(f"models whose best plan fails verify while another plan passes: "
          f"{overruled('before', 'verify_before')} before, {overruled('after', 'verify_after')} after")
    with open(os.path.join(a.after, "table.json"), "w") as f:
        json.dump(table, f, indent=1)


if __name__ == "__main__":
    main()
