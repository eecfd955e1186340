"""The thesis's Tables 4.1-4.4: the camera-path walkthroughs (bunny, Sponza, Sibenik, the
conference room) with the cache off and on, from `bench/run.sh --walkthroughs`'s JSON files.
Writes the per-frame chart and the tables between the walkthrough-results markers of a doc.

    bench/walkthroughs.py --results out/bench/walk --images docs/images \
        --doc docs/bench-walkthroughs.md
"""

import argparse
import os

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
    a = ap.parse_args()
    _, walks = analysis.load(a.results)
    if not walks:
        raise SystemExit("error: no walkthrough results in %s" % a.results)
    os.makedirs(a.images, exist_ok=True)
    scenes = sorted(walks, key=lambda s: TABLES.get(s, "Table 9"))
    charts.walkthrough_chart(walks, a.images, "bench-walkthroughs", scenes)
    report.write_tables(tables(walks), a.results, "walkthroughs.md", a.doc, BEGIN, END)

if __name__ == "__main__":
    main()
