"""The thesis's Tables 4.1-4.4: the camera-path walkthroughs (bunny, Sponza, Sibenik, the
conference room) with the cache off and on, from `bench/run.sh --walkthroughs`'s JSON files.
Writes the per-frame chart and the tables between the walkthrough-results markers of a doc.

    bench/walkthroughs.py --results out/bench/walk --images docs/images \
        --doc docs/bench-walkthroughs.md [--data docs/data/walkthroughs.json]

With --data it also writes every run's summary (frame time, speed-up over the uncached run,
mean relMSE) with the command, commit and device, and bench/docs_tables.py rewrites the tables
made from it (the README's and the walkthroughs page's "In short"). --default-run names the run
measured at the default settings (default: the cached run of the default bounce, "cache: world
cache" where docs/settings.md's indirect_method is 3, "cache: thesis rule" otherwise).
"""

import argparse
import json
import os
import sys

import analysis
import charts
import report

BEGIN, END = "<!-- walkthrough-results:begin -->", "<!-- walkthrough-results:end -->"
# The thesis's table of each scene's walkthrough.
TABLES = {"bunny": "Table 4.1", "sponza": "Table 4.2", "sibenik": "Table 4.3",
          "conference": "Table 4.4"}


def tables(walks):
    scenes = sorted(walks, key=lambda s: TABLES.get(s, "Table 9"))
    first = walks[scenes[0]]
    md = ["Device: **%s**, driver %s, Vulkan %s; commit `%s`; %s.\n" % (
        first["device"]["name"], first["device"]["driver"], first["device"]["api"],
        first["commit"], first["date"])]
    rows = []
    for scene in scenes:
        for label, ms, speed, err in analysis.walk_runs(walks[scene]):
            rows.append([scene, label, "%.0f" % ms, "%.2f" % speed, "%.4f" % err])
    md.append("\n### Summary: every run against the uncached one\n\n")
    md.append("Wall clock per frame, mean over the frames after the first; mean relMSE over the "
              "error frames against the path-traced reference.\n\n")
    md.append(report.table(["scene", "run", "frame, ms", "cache off / run", "mean relMSE"],
                           rows))
    for scene in scenes:
        md.append(report.walkthrough_tables(scene, walks[scene], TABLES.get(scene, "Walk")))
    md.append("\n![Frame time along each camera path](images/bench-walkthroughs.png)\n")
    return "".join(md)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--results", required=True)
    ap.add_argument("--images", required=True)
    ap.add_argument("--doc")
    ap.add_argument("--data", help="also write the runs' summary there (docs/data/walkthroughs.json)")
    ap.add_argument("--default-run", help="the label of the run at the default settings")
    a = ap.parse_args()
    if a.default_run is None:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import docs_tables
        method = int(docs_tables.setting_default("indirect_method"))
        a.default_run = "cache: world cache" if method == 3 else "cache: thesis rule"
    _, walks = analysis.load(a.results)
    if not walks:
        raise SystemExit("error: no walkthrough results in %s" % a.results)
    os.makedirs(a.images, exist_ok=True)
    scenes = sorted(walks, key=lambda s: TABLES.get(s, "Table 9"))
    charts.walkthrough_chart(walks, a.images, "bench-walkthroughs", scenes)
    report.write_tables(tables(walks), a.results, "walkthroughs.md", a.doc, BEGIN, END)
    if a.data:
        write_data(walks, scenes, a.data, a.default_run, a.results)


def write_data(walks, scenes, path, default_run, results="out/bench/walk"):
    """The runs' summary as bench/docs_tables.py reads it; then the tables made from it."""
    first = walks[scenes[0]]
    runs = [[scene, label, round(ms), round(speed, 2), round(err, 4)]
            for scene in scenes for label, ms, speed, err in analysis.walk_runs(walks[scene])]
    if default_run not in {r[1] for r in runs}:
        raise SystemExit("error: no run labelled %r (--default-run)" % default_run)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import docs_tables
    data = {"what": "the camera-path walkthroughs (the thesis's Tables 4.1-4.4): the wall clock "
                    "of a frame along each scene's camera_path, every run interleaved frame by "
                    "frame, and its mean relMSE against path-traced references",
            "command": "bench/walkthroughs.py --results %s --data %s, from `build/benchmark "
                       "walkthrough`'s JSON (bench/run.sh --walkthroughs runs both)"
                       % (results, path),
            "commit": first["commit"], "device": first["device"]["name"],
            "indirect_method": int(docs_tables.setting_default("indirect_method")),
            "date": first["date"][:10],
            "size": "%dx%d" % (first["width"], first["height"]),
            "path_frames": first["walkthrough"]["frames"], "default_run": default_run,
            "runs": runs}
    with open(path, "w") as f:
        json.dump(data, f, indent=2)
        f.write("\n")
    print("summary: %s" % path)
    for page in docs_tables.run(check=False):
        print("rewrote %s" % page)

if __name__ == "__main__":
    main()
