#!/usr/bin/env python3
"""Writes the docs' generated tables from the measured data in docs/data/*.json.

Each generated table stands between two markers in a page:

    <!-- docs-table:NAME begin: bench/docs_tables.py writes this from docs/data; edit those -->
    ...
    <!-- docs-table:NAME end -->

and is a function of the data files alone (and of docs/settings.md's table, which test_settings
holds equal to renderer/scene/settings.h). The programs that measure write the data files
(`bench/one_frame_error.py --json`, `bench/walkthroughs.py`) or, for the figures no script writes
yet, they are copied into them by hand with the command and commit that measured them.

    python3 bench/docs_tables.py           # rewrite every generated table in place
    python3 bench/docs_tables.py --check   # exit 1, naming them, if any table differs

Run from anywhere: paths are the checkout's, found from this file."""

import argparse
import json
import math
import os
import re
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "docs", "data")
NOTE = "bench/docs_tables.py writes this from docs/data; edit those"
BEGIN = "<!-- docs-table:%s begin: " + NOTE + " -->"
END = "<!-- docs-table:%s end -->"
# Scene names as the pages write them, in the order the tables list them.
SCENES = {"cornell-box": "Cornell box", "sponza": "Sponza", "bunny": "bunny",
          "sibenik": "Sibenik", "conference": "conference room", "mori-knob": "Mori knob",
          "scrub-pine": "scrub pine", "cornell-box-sphere": "Cornell box, sphere",
          "cornell-box-mesh": "Cornell box, mesh"}
# What each value of indirect_method is, as docs/bounce.md names them.
BOUNCES = {0: "the thesis's gather", 1: "interleaved VPL subsets",
           2: "VPLs drawn by their flux", 3: "the world cache"}


def load(name):
    with open(os.path.join(DATA, name + ".json")) as f:
        return json.load(f)


def scene_order(names):
    order = list(SCENES)
    return sorted(names, key=lambda s: order.index(s) if s in order else len(order))


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(x) for x in r) + " |" for r in rows]
    return "\n".join(lines) + "\n"


def measured(d, commit=None):
    """The line under a table: the command and commit that measured it."""
    return "*Measured by `%s` at commit `%s` on %s.*\n" % (d["command"], commit or d["commit"],
                                                           d["device"])


def setting_default(key):
    """A setting's default, read from docs/settings.md's table (`render --list-settings`)."""
    with open(os.path.join(ROOT, "docs", "settings.md")) as f:
        for line in f:
            cells = [c.strip() for c in line.split("|")]
            if len(cells) > 3 and cells[1] == "`%s`" % key:
                return cells[3]
    raise SystemExit("error: docs/settings.md has no row for %s" % key)


def one_frame_error():
    d = load("one-frame-error")
    rows = []
    for s in scene_order(d["scenes"]):
        e = d["scenes"][s]
        rows.append(["`%s`" % s, "%.5f (%.5f–%.5f)" % (e["mean"], e["min"], e["max"]),
                     "%.5f / %.3f" % (e["frame0"], e["frame0_ssim"]),
                     "%.5f / %.3f" % (e["converged"], e["converged_ssim"]) if "converged" in e
                     else "—"])
    return (table(["scene", "one frame: mean of %d draws (range)" % d["frames"],
                   "frame 0 / SSIM", "%d cached frames / SSIM" % d["converged_frames"]], rows)
            + "\n" + measured(d) + "\n")


def walk_default_rows(d):
    """{scene: (default run's speed-up, its error, the uncached error)}."""
    out = {}
    for scene, label, ms, speed, err in d["runs"]:
        if label == "cache off":
            out.setdefault(scene, {})["off"] = err
        if label == d["default_run"]:
            out.setdefault(scene, {})["run"] = (speed, err)
    return {s: (v["run"][0], v["run"][1], v["off"]) for s, v in out.items()}


def walkthroughs_default():
    d = load("walkthroughs")
    rows = [[SCENES.get(s, s), "%.2f×" % speed, "%.4f" % err, "%.4f" % off]
            for s, (speed, err, off) in ((s, v) for s, v in walk_default_rows(d).items())]
    return (table(["camera path (%s, %d frames)" % (d["size"].replace("x", "×"), d["path_frames"]),
                   "cached frame's speed-up, default settings", "its relMSE",
                   "the uncached frame's relMSE (interleaved subsets)"], rows)
            + "\n" + measured(d) + "\n")


def stability_summary():
    d = load("stability")
    rows = [["cases × cache rules meeting every target", "%d of %d" % (d["pairs_met"], d["pairs"])],
            ["frames to recover after a change", "%d (%s)" % (d["recovery_frames"],
                                                             d["recovery_exception"])],
            ["changed region's error over the first 8 frames, worst case",
             "%.2f× a fresh start's" % d["first8_worst"]],
            ["changed region's error once settled, worst case",
             "%.2f× a fresh start's" % d["settled_worst"]],
            ["flicker on a still camera; NaN or Inf", "%d; %d" % (d["flicker"], d["nan"])]]
    if d.get("failing"):
        rows.append(["what misses a target", "; ".join(d["failing"])])
    return (table(["at %s, both cache rules" % d["size"].replace("x", "×"), ""], rows) + "\n" + measured(d)
            + "\n")


def significant(x, digits=2):
    """x to two significant digits, as the pages write an error (0.0068, 0.00054)."""
    return "%.*f" % (max(digits - 1 - int(math.floor(math.log10(abs(x)))), 0), x)


def span(values, fmt="%.2f", unit="×"):
    lo, hi = min(values), max(values)
    return (fmt % lo + unit) if fmt % lo == fmt % hi else (fmt % lo + "–" + fmt % hi + unit)


def bounce_note(d, method):
    """Where data were measured with another default bounce than today's, a note saying which."""
    then = d.get("indirect_method", method)
    return "" if then == method else " (measured when `indirect_method=%d` was the default)" % then


def where_it_stands():
    """The README's table: one row per headline figure, each with its page and command."""
    method = int(setting_default("indirect_method"))
    one = load("one-frame-error")
    walk = load("walkthroughs")
    settled = load("settled")
    memory = load("memory")
    stab = load("stability")
    gpu = load("gpu")
    shipped = [s for s in scene_order(one["scenes"]) if s in
               ("cornell-box", "sponza", "bunny", "sibenik", "mori-knob", "scrub-pine",
                "conference")]
    per_scene = lambda key: ", ".join(
        "%s %s" % (SCENES[s], significant(one["scenes"][s][key])) for s in shipped
        if key in one["scenes"][s])
    walks = walk_default_rows(walk)
    big = gpu["moving"]["scenes"]
    rows = [
        ["the bounce by default",
         "`indirect_method=%d`: %s" % (method, BOUNCES.get(method, "?")),
         "[settings](docs/settings.md)", "`build/render --list-settings`"],
        ["one uncached frame against the path-traced truth, relMSE (mean of %d draws, %d×%d)"
         % (one["frames"], one["size"], one["size"]),
         per_scene("mean") + bounce_note(one, method), "[accuracy](docs/accuracy.md#every-scene-against-converged-references)",
         "`bench/one_frame_error.py`"],
        ["%d cached frames of a still camera against the truth, relMSE" % one["converged_frames"],
         per_scene("converged") + bounce_note(one, method),
         "[accuracy](docs/accuracy.md#every-scene-against-converged-references)",
         "`bench/one_frame_error.py --converged 64`"],
        ["the cache's speed-up along the camera paths (%s), default settings, over the "
         "uncached frame with interleaved subsets (`--cache 0 --set indirect_method=1`)"
         % walk["size"].replace("x", "×"),
         ", ".join("%s %.2f×" % (SCENES[s], walks[s][0]) for s in walks)
         + " (relMSE %s of the uncached frame's)" % span([walks[s][1] / walks[s][2]
                                                           for s in walks])
         + bounce_note(walk, method),
         "[walkthroughs](docs/bench-walkthroughs.md#in-short)", "`build/benchmark walkthrough`"],
        ["the cache's speed-up on a still camera once settled (%s)"
         % settled["size"].replace("x", "×"),
         ", ".join("%s %.1f×" % (SCENES[s], v["speedup"])
                   for s, v in settled["scenes"].items())
         + "; the settled frame %s the cost of `direct` + `composite`"
         % span([v["over_direct_composite"] for v in settled["scenes"].values()])
         + bounce_note(settled, method),
         "[benchmarks](docs/bench.md#in-short)", settled.get("measured_by", "`bench/run.sh`")],
        ["GPU memory the frame holds at 1920×1080",
         ", ".join("%s %.1f MiB" % (SCENES[s], v["1920x1080"])
                   for s, v in memory["scenes"].items()) + bounce_note(memory, method),
         "[the frame](docs/frame.md#memory)", "`build/render --memory`"],
        ["stability: scripted failure cases (%s, both cache rules)" % stab["size"].replace("x", "×"),
         "%d of %d meet every target%s; recovery in %d frame (%s); error within %.2f× a fresh "
         "start's over 8 frames, %.2f× settled; %s, no NaN"
         % (stab["pairs_met"], stab["pairs"],
            " (not: %s)" % stab["failing_cases"] if stab.get("failing") else "",
            stab["recovery_frames"], stab["recovery_exception"], stab["first8_worst"],
            stab["settled_worst"],
            "flicker in %d" % stab["flicker"] if stab["flicker"] else "no flicker")
         + bounce_note(stab, method),
         "[stability](docs/stability.md#in-short)", "`build/stability --quick`"],
        ["%s: the cache's speed-up along the camera paths" % gpu["device"],
         "%s at 512×512, %s at 1920×1080" % (span([v["512x512"] for v in big.values()]),
                                            span([v["1920x1080"] for v in big.values()]))
         + bounce_note(gpu, method),
         "[profiling](docs/profiling-gpu.md)", "`walkthrough --timings`"],
        ["%s: a settled still frame at 1920×1080" % gpu["device"],
         "%.2f–%.2f ms, %d–%d× faster than an uncached one"
         % (gpu["settled"]["ms_min"], gpu["settled"]["ms_max"], gpu["settled"]["speedup_min"],
            gpu["settled"]["speedup_max"]) + bounce_note(gpu, method),
         "[profiling](docs/profiling-gpu.md)", "`render --warmup 40 --profile`"],
    ]
    return table(["figure", "today", "page", "measured by"], rows)


def python_sweep():
    """docs/python.md's sweep: one Renderer against a Renderer per value, per setting."""
    runs = load("python-sweep")
    rows = []
    for r in runs:
        per_value = statistics.median(r["per_value_s"])  # as python_sweep.py's ratio takes them
        together = statistics.median(r["one_renderer_s"])
        rows.append(["`%s` (%s)" % (r["setting"], ", ".join(str(v) for v in r["values"])),
                     "%.2f s" % per_value, "%.2f s" % together, "%.2f×" % r["ratio"]])
    first = runs[0]
    commits = sorted({r["commit"] for r in runs})
    return (table(["setting (values)", "a Renderer per value", "one Renderer", "faster"], rows) +
            "\n*Measured by `python3 bench/python_sweep.py --setting NAME --values ... --json "
            "docs/data/python-sweep.json` at commit%s `%s` on %s (%s, %dx%d, medians of %d rounds"
            "%s).*\n" % ("s" if len(commits) > 1 else "", "`, `".join(commits), first["device"],
                          first["scene"], first["size"][0], first["size"][1], first["rounds"],
                          ", the validation layer on" if first["validation"] else
                          ", no validation layer"))


# Each generated table: (the page, the marker's name, the function that writes it).
TABLES = [
    ("README.md", "where-it-stands", where_it_stands),
    ("docs/accuracy.md", "one-frame-error", one_frame_error),
    ("docs/bench-walkthroughs.md", "walkthroughs-default", walkthroughs_default),
    ("docs/stability.md", "stability-summary", stability_summary),
    ("docs/python.md", "python-sweep", python_sweep),
]


def block(name, body):
    return BEGIN % name + "\n" + body + END % name


def rewrite(text, name, body):
    """The page's text with the block NAME replaced; None when the page has no such block."""
    pattern = re.compile(re.escape(BEGIN % name) + ".*?" + re.escape(END % name), re.S)
    if not pattern.search(text):
        return None
    return pattern.sub(lambda _: block(name, body), text)


def run(check):
    stale = []
    for page, name, write in TABLES:
        path = os.path.join(ROOT, page)
        with open(path) as f:
            text = f.read()
        new = rewrite(text, name, write())
        if new is None:
            raise SystemExit("error: %s has no docs-table:%s markers" % (page, name))
        if new != text:
            stale.append("%s (%s)" % (page, name))
            if not check:
                with open(path, "w") as f:
                    f.write(new)
    return stale


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true",
                    help="write nothing; exit 1 if a generated table differs from its data")
    a = ap.parse_args()
    stale = run(a.check)
    for s in stale:
        print(("differs from its data: %s" if a.check else "rewrote %s") % s)
    if a.check and stale:
        print("run python3 bench/docs_tables.py (and edit docs/data/, not the tables)",
              file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
