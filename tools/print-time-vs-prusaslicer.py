#!/usr/bin/env python3
"""Reference print times: PrusaSlicer 2.5's own estimate for every model of the corpus.

Usage:
  tools/print-time-vs-prusaslicer.py [STL|DIR ...] [--corpus DIR] [-j N] [--out FILE]
                                     [--timeout S] [--merge]

Slices each STL with PrusaSlicer (Debian package prusa-slicer, installed with apt-get when
`prusa-slicer` is not on PATH) and the stated config tools/prusaslicer/profile.ini:

  prusa-slicer --export-gcode --load tools/prusaslicer/profile.ini --center 500,500
               --dont-arrange --output TMP/x.gcode MODEL.stl

and reads from the G-code's comments "; estimated printing time (normal mode) = 1h 2m 3s",
"; filament used [mm]" and the layers (";LAYER_CHANGE" lines, highest ";Z:"). The model's
size, volume and facet count come from `prusa-slicer --info` (the mesh as PrusaSlicer loads
and repairs it, before slicing). PrusaSlicer 2.5 writes no "filament used [mm3]" line, only
"[cm3]" to two decimals, so filament_mm3 is filament_mm times the 1.75 mm filament's section.

Default models: every *.stl under the corpus (DIR from --corpus, else $PLATENER_CORPUS,
else ../shared/corpus relative to the repo root) plus the repo's examples/*.stl. Models
are named "corpus/<path in corpus>" or "examples/<name>". A model PrusaSlicer refuses or
that does not finish within --timeout seconds (300) is kept with "error" and no seconds.

Writes the fixture (default crates/platener/tests/fixtures/prusaslicer-times.json), models
sorted by file name, each with the STL's sha256 so a test can tell the fixture is stale,
and prints a table. With --merge, entries of the existing fixture that were not re-run are
kept. Run by hand for measuring, never by CI. -j is at most 2 (the machine has 2 cores).
PrusaSlicer 2.5 is not bit-for-bit deterministic (multithreaded slicing): three runs of the
corpus differed by up to 14 s on 18.6 h and by 1 s on ten other models (< 0.03 %), so
compare with a tolerance. Standard library only (Python 3.11).
"""
import argparse
import hashlib
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PROFILE_REL = "tools/prusaslicer/profile.ini"
PROFILE = os.path.join(REPO, PROFILE_REL)
FIXTURE_REL = "crates/platener/tests/fixtures/prusaslicer-times.json"
PROFILE_SUMMARY = ("MK3S 0.20mm QUALITY-like (PrusaSlicer 2.5 bundled preset), Prusament PLA "
                   "1.75 mm, 0.4 nozzle, 0.2 mm layers, 2 perimeters (arachne), 6 top / 4 "
                   "bottom solid layers, 15 % gyroid, no supports, no skirt/brim, MK3S "
                   "normal-mode machine limits, 1000 x 1000 x 1000 mm bed, model centred at "
                   "500,500")
FILAMENT_DIAMETER = 1.75
MAX_JOBS = 2

TIME_RE = re.compile(r"^; estimated printing time \(normal mode\) = (.+)$")
FIL_MM_RE = re.compile(r"^; filament used \[mm\] = ([0-9.eE+-]+)")
FIL_CM3_RE = re.compile(r"^; filament used \[cm3\] = ([0-9.eE+-]+)")
FIL_MM3_RE = re.compile(r"^; filament used \[mm3\] = ([0-9.eE+-]+)")
Z_RE = re.compile(r"^;Z:([0-9.eE+-]+)")
LOG_PREFIX_RE = re.compile(r"^\[\d{4}-\d\d-\d\d [0-9:.]+\] \[0x[0-9a-f]+\] \[(\w+)\]\s*")


def parse_duration(text):
    """'1d 2h 3m 4s', '1h 2m 3s', '5m 6s', '7s' -> seconds."""
    units = {"d": 86400, "h": 3600, "m": 60, "s": 1}
    parts = re.findall(r"(\d+)\s*([dhms])", text)
    if not parts or re.sub(r"(\d+)\s*([dhms])", "", text).strip():
        raise ValueError(f"unrecognised duration {text!r}")
    return sum(int(n) * units[u] for n, u in parts)


def ensure_prusaslicer():
    if shutil.which("prusa-slicer"):
        return
    print("prusa-slicer not on PATH: apt-get install -y prusa-slicer", file=sys.stderr)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    subprocess.run(["apt-get", "install", "-y", "prusa-slicer"], check=True, env=env)
    if not shutil.which("prusa-slicer"):
        sys.exit("prusa-slicer still not on PATH after apt-get install")


def prusaslicer_version():
    try:
        out = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", "prusa-slicer"],
                             capture_output=True, text=True)
        if out.returncode == 0 and out.stdout.strip():
            return out.stdout.strip()
    except FileNotFoundError:
        pass
    out = subprocess.run(["prusa-slicer", "--help"], capture_output=True, text=True, env=slicer_env())
    m = re.search(r"PrusaSlicer-(\S+)", out.stdout + out.stderr)
    return m.group(1) if m else "unknown"


def slicer_env():
    # The CLI needs no display; keep Qt/GTK from looking for one.
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    return env


def run(cmd, timeout):
    """Runs cmd in its own process group; returns (rc, stdout, stderr), rc None on timeout."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         errors="replace", env=slicer_env(), start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
        return p.returncode, out, err
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        return None, out, err


def first_error_line(stderr, stdout=""):
    """PrusaSlicer's own first message line (stderr, then stdout). Boost-log lines are
    skipped, except that the first [error]/[warning] one is appended in brackets, without
    its timestamp, when it says more (e.g. why loading failed)."""
    plain, logged = None, None
    for line in stderr.splitlines() + stdout.splitlines():
        line = line.strip()
        if not line or re.match(r"^\d+ => ", line):  # progress lines on stdout
            continue
        m = LOG_PREFIX_RE.match(line)
        if m:
            if m.group(1) not in ("trace", "debug", "info") and logged is None:
                logged = line[m.end():]
        elif plain is None:
            plain = line
    if plain and logged:
        return f"{plain} [{logged}]"
    return plain or logged or "no message"


def model_info(stl, timeout):
    rc, out, err = run(["prusa-slicer", "--loglevel", "1", "--info", stl], timeout)
    info = {}
    for line in out.splitlines():
        if "=" in line:
            k, v = (s.strip() for s in line.split("=", 1))
            info[k] = v
    if "size_x" not in info:
        return None
    return {
        "size_mm": [round(float(info[k]), 3) for k in ("size_x", "size_y", "size_z")],
        "volume_mm3": round(float(info.get("volume", "nan")), 3),
        "facets": int(info.get("number_of_facets", 0)),
        "manifold": info.get("manifold") == "yes",
        "parts": int(info.get("number_of_parts", "0").strip() or 0),
    }


def parse_gcode(path):
    res = {"layers": 0}
    max_z = None
    cm3 = None
    with open(path, errors="replace") as f:
        for line in f:
            if line[0] != ";":
                continue
            if line.startswith(";LAYER_CHANGE"):
                res["layers"] += 1
                continue
            m = Z_RE.match(line)
            if m:
                z = float(m.group(1))
                max_z = z if max_z is None else max(max_z, z)
                continue
            if not line.startswith("; "):
                continue
            if m := TIME_RE.match(line.rstrip("\n")):
                res["seconds"] = parse_duration(m.group(1))
            elif m := FIL_MM_RE.match(line):
                res["filament_mm"] = float(m.group(1))
            elif m := FIL_MM3_RE.match(line):
                res["filament_mm3"] = float(m.group(1))
            elif m := FIL_CM3_RE.match(line):
                cm3 = float(m.group(1))
    if max_z is not None:
        res["max_z"] = round(max_z, 3)
    if "filament_mm" in res and "filament_mm3" not in res:
        area = math.pi * (FILAMENT_DIAMETER / 2) ** 2
        res["filament_mm3"] = round(res["filament_mm"] * area, 2)
    if cm3 is not None and "filament_mm3" in res and abs(cm3 * 1000 - res["filament_mm3"]) > 10:
        print(f"warning: {path}: filament [cm3] {cm3} vs {res['filament_mm3']} mm3",
              file=sys.stderr)
    return res


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def slice_one(name, stl, timeout):
    entry = {"file": name, "sha256": sha256(stl)}
    t0 = time.monotonic()
    info = model_info(stl, 60)
    if info:
        entry.update(info)
    with tempfile.TemporaryDirectory(prefix="ps-time-") as tmp:
        gcode = os.path.join(tmp, "x.gcode")
        cmd = ["prusa-slicer", "--export-gcode", "--load", PROFILE, "--center", "500,500",
               "--dont-arrange", "--output", gcode, stl]
        rc, out, err = run(cmd, timeout)
        wall = time.monotonic() - t0
        if rc is None:
            entry["error"] = f"timeout after {timeout} s"
        elif rc != 0 or not os.path.exists(gcode):
            msg = first_error_line(err, out).replace(os.path.abspath(stl), name).replace(stl, name)
            entry["error"] = msg + ("" if rc == 0 else f" (exit {rc})")
        else:
            g = parse_gcode(gcode)
            if "seconds" not in g:
                entry["error"] = "no '; estimated printing time (normal mode)' in the G-code"
            entry.update({k: g[k] for k in ("seconds", "filament_mm3", "filament_mm",
                                            "layers", "max_z") if k in g})
    return entry, wall


def default_models(corpus):
    models = []
    if os.path.isdir(corpus):
        for root, _, files in os.walk(corpus):
            for fn in files:
                if fn.lower().endswith(".stl"):
                    p = os.path.join(root, fn)
                    models.append(("corpus/" + os.path.relpath(p, corpus).replace(os.sep, "/"), p))
    else:
        print(f"warning: corpus {corpus} not found", file=sys.stderr)
    ex = os.path.join(REPO, "examples")
    for fn in sorted(os.listdir(ex)) if os.path.isdir(ex) else []:
        if fn.lower().endswith(".stl"):
            models.append(("examples/" + fn, os.path.join(ex, fn)))
    return models


def name_for(path, corpus):
    ap = os.path.abspath(path)
    for prefix, root in (("corpus", corpus), ("examples", os.path.join(REPO, "examples"))):
        root = os.path.abspath(root)
        if ap.startswith(root + os.sep):
            return prefix + "/" + os.path.relpath(ap, root).replace(os.sep, "/")
    return os.path.basename(ap)


def flags(e):
    out = []
    if "error" in e:
        return ["FAILED"]
    if e.get("seconds", 1) == 0:
        out.append("zero-time")
    if e.get("layers", 1) <= 1:
        out.append(f"{e.get('layers')}-layer")
    size = e.get("size_mm")
    if size:
        if max(size) > 1000:
            out.append("larger-than-bed")
        elif max(size) > 250:
            out.append("larger-than-MK3S")
        if max(size) < 10:
            out.append("tiny(<10mm: inches/units?)")
    return out


def fmt_time(s):
    if s is None:
        return "-"
    h, r = divmod(int(s), 3600)
    m, sec = divmod(r, 60)
    return f"{h}h{m:02d}m{sec:02d}s" if h else f"{m}m{sec:02d}s"


def print_table(models):
    print(f"| {'file':60} | {'seconds':>8} | {'h:m:s':>10} | {'fil mm3':>9} | {'layers':>6} "
          f"| {'size mm (x y z)':>24} | flags / error |")
    print("|" + "|".join("-" * w for w in (62, 10, 12, 11, 8, 26, 15)) + "|")
    for e in models:
        size = " x ".join(f"{v:g}" for v in e["size_mm"]) if e.get("size_mm") else "-"
        note = e["error"] if "error" in e else ", ".join(flags(e))
        sec = e.get("seconds")
        fil = f"{e['filament_mm3']:.0f}" if "filament_mm3" in e else "-"
        print(f"| {e['file']:60} | {sec if sec is not None else '-':>8} | {fmt_time(sec):>10} "
              f"| {fil:>9} | {e.get('layers', '-'):>6} | {size:>24} | {note} |")


def dump_fixture(fixture):
    """Pretty JSON with one line per model, so a re-run diffs line by line."""
    head = {k: v for k, v in fixture.items() if k != "models"}
    lines = ["{"] + [f" {json.dumps(k)}: {json.dumps(v)}," for k, v in head.items()]
    lines.append(' "models": [')
    rows = [f"  {json.dumps(m)}" for m in fixture["models"]]
    lines.append(",\n".join(rows))
    lines += [" ]", "}"]
    text = "\n".join(lines) + "\n"
    assert json.loads(text) == fixture
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("paths", nargs="*", help="STL files or folders (default: corpus + examples)")
    ap.add_argument("--corpus", default=os.environ.get("PLATENER_CORPUS")
                    or os.path.join(REPO, "..", "shared", "corpus"))
    ap.add_argument("-j", "--jobs", type=int, default=1)
    ap.add_argument("--timeout", type=int, default=300, help="seconds per model (300)")
    ap.add_argument("--out", default=os.path.join(REPO, FIXTURE_REL))
    ap.add_argument("--merge", action="store_true",
                    help="keep entries of the existing fixture that were not re-run")
    args = ap.parse_args()
    if not 1 <= args.jobs <= MAX_JOBS:
        ap.error(f"-j must be 1..{MAX_JOBS}")
    corpus = os.path.normpath(args.corpus)

    if args.paths:
        models = []
        for p in args.paths:
            if os.path.isdir(p):
                for root, _, files in os.walk(p):
                    models += [(name_for(os.path.join(root, f), corpus), os.path.join(root, f))
                               for f in files if f.lower().endswith(".stl")]
            else:
                models.append((name_for(p, corpus), p))
    else:
        models = default_models(corpus)
    models.sort()
    if not models:
        sys.exit("no STL to slice")

    ensure_prusaslicer()
    version = prusaslicer_version()
    print(f"PrusaSlicer {version}, {len(models)} models, -j {args.jobs}, "
          f"timeout {args.timeout} s", file=sys.stderr)

    t0 = time.monotonic()
    results = {}

    def job(item):
        name, path = item
        entry, wall = slice_one(name, path, args.timeout)
        status = entry.get("error") or f"{entry.get('seconds')} s"
        print(f"  [{wall:6.1f} s wall] {name}: {status}", file=sys.stderr, flush=True)
        return name, entry

    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for name, entry in pool.map(job, models):
            results[name] = entry

    if args.merge and os.path.exists(args.out):
        with open(args.out) as f:
            for e in json.load(f).get("models", []):
                results.setdefault(e["file"], e)

    ordered = [results[k] for k in sorted(results)]
    fixture = {
        "prusaslicer": version,
        "profile": PROFILE_REL,
        "profile_summary": PROFILE_SUMMARY,
        "command": "prusa-slicer --export-gcode --load tools/prusaslicer/profile.ini "
                   "--center 500,500 --dont-arrange --output x.gcode MODEL.stl",
        "seconds_from": "; estimated printing time (normal mode)",
        "note": "PrusaSlicer's estimate varies by < 0.03 % (a few seconds) between runs; "
                "size_mm is the mesh as PrusaSlicer loads it (file units taken as mm, "
                "orientation as in the file); filament_mm3 = filament_mm x 1.75 mm section",
        "models": ordered,
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        f.write(dump_fixture(fixture))

    print_table(ordered)
    failed = [e["file"] for e in ordered if "error" in e]
    print(f"\n{len(ordered)} models, {len(ordered) - len(failed)} sliced, {len(failed)} failed; "
          f"{time.monotonic() - t0:.0f} s; wrote {os.path.relpath(args.out, REPO)}")


if __name__ == "__main__":
    main()
