#!/usr/bin/env python3
"""Nesting density against sparrow (spyrrow, the strip packer on jagua-rs) on the same parts.

Usage: tools/nesting-vs-spyrrow.py [SECONDS ...]   (default: 2 10)

1. Writes the strip sets of benches/nesting.rs (finger-jointed plates, a sphere's and an
   organic figure's stacked layers) with our strip length at each `nesting` level:
   `PLATENER_NESTING_EXPORT=FILE cargo bench -p platener --bench nesting`.
2. Installs spyrrow from PyPI into its own virtual environment (target/spyrrow-venv), never
   into the system and never in CI.
3. Packs the same cut outlines on the same 400 mm high strip with the same 2 mm separation
   and quarter-turn orientations for each time budget, and prints a Markdown table:
   density = parts' area / (400 mm × strip length); ratio = our density / sparrow's.

Our nester also puts small parts into other parts' holes; spyrrow has no holes, so its
outlines are packed as solid shapes (an advantage to us on sets with windows; the three sets
here have none worth filling).
"""
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VENV = os.path.join(ROOT, "target", "spyrrow-venv")


def spyrrow_python():
    python = os.path.join(VENV, "bin", "python")
    if not os.path.exists(python):
        subprocess.run([sys.executable, "-m", "venv", VENV], check=True)
        subprocess.run([python, "-m", "pip", "install", "-q", "spyrrow==0.9.0"], check=True)
    return python


PACK = r"""
import json, sys, spyrrow
sets, seconds = json.load(open(sys.argv[1])), int(sys.argv[2])
out = {}
for s in sets:
    items = [spyrrow.Item(str(i), [tuple(p) for p in ring], demand=1, allowed_orientations=[0, 90, 180, 270])
             for i, ring in enumerate(s["outlines"])]
    instance = spyrrow.StripPackingInstance(s["name"], strip_height=s["height"], items=items)
    config = spyrrow.StripPackingConfig(early_termination=True, total_computation_time=seconds,
                                        min_items_separation=s["spacing"], num_workers=2, seed=1)
    sol = instance.solve(config)
    out[s["name"]] = sol.width
print(json.dumps(out))
"""


def main():
    budgets = [int(a) for a in sys.argv[1:]] or [2, 10]
    with tempfile.TemporaryDirectory() as tmp:
        sets_file = os.path.join(tmp, "sets.json")
        env = dict(os.environ, PLATENER_NESTING_EXPORT=sets_file)
        subprocess.run(["cargo", "bench", "-q", "-p", "platener", "--bench", "nesting"], cwd=ROOT, env=env, check=True)
        sets = json.load(open(sets_file))
        python = spyrrow_python()
        theirs = {}
        for seconds in budgets:
            start = time.time()
            run = subprocess.run([python, "-c", PACK, sets_file, str(seconds)], capture_output=True, text=True, check=True)
            theirs[seconds] = (json.loads(run.stdout.strip().splitlines()[-1]), time.time() - start)
    levels = ["fast", "good", "best"]
    head = "| set | parts | " + " | ".join(f"ours {l}" for l in levels) + " | " + " | ".join(f"sparrow {b} s" for b in budgets) + " | good / sparrow " + f"{budgets[-1]} s |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    for s in sets:
        density = lambda length: s["area"] / (s["height"] * length)
        ours = [f"{100 * density(s['ours'][l]['length']):.1f} % ({s['ours'][l]['millis'] / 1000:.2f} s)" for l in levels]
        them = [f"{100 * density(theirs[b][0][s['name']]):.1f} %" for b in budgets]
        ratio = density(s["ours"]["good"]["length"]) / density(theirs[budgets[-1]][0][s["name"]])
        print(f"| {s['name']} | {len(s['outlines'])} | " + " | ".join(ours) + " | " + " | ".join(them) + f" | {ratio:.3f}× |")


if __name__ == "__main__":
    main()
