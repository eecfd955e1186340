#!/usr/bin/env python3
"""Turns one benchmark run's JSON (bench/run.sh) into CSV files, charts and Markdown tables,
and optionally writes the tables into a document between its bench-results markers.
usage: report.py --results DIR --images DIR --size WxH [--doc FILE] [--note TEXT]"""

import argparse
import csv
import math
import os
import re

import analysis
import charts

BEGIN, END = "<!-- bench-results:begin -->", "<!-- bench-results:end -->"
MIB = 1024.0 * 1024.0


def provenance(j):
    return [j["device"]["name"], j["device"]["driver"], j["commit"]]


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header + ["device", "driver", "commit"])
        w.writerows(rows)


def write_csvs(sweeps, walks, out):
    configs, series, probe, memory = [], [], [], []
    for scene, sizes in sweeps.items():
        for size, j in sizes.items():
            p = provenance(j)
            for c in j["configs"]:
                configs.append([scene, size, c["label"], c["group"], "%.3f" % c["total_ms"],
                                c.get("rel_mse", ""), c.get("ssim", ""),
                                " ".join("%s=%.3f" % kv for kv in c["passes"].items())] + p)
            for s in j.get("series", []):
                for f in range(j["series_frames"]):
                    series.append([scene, size, s["label"], f + 1,
                                   s["total_ms"][f] if "total_ms" in s else "",
                                   s["rel_mse"][f] if "rel_mse" in s else ""] + p)
            pr = j["probe"]
            probe.append([scene, size, pr["taps_local_per_ms"], pr["taps_scattered_per_ms"],
                          pr["bytes_per_ms"]] + p)
            for msize, images in j["memory"].items():
                memory += [[scene, msize, e["image"], e["bytes"]] + p for e in images]
    write_csv(os.path.join(out, "configs.csv"), ["scene", "size", "config", "group", "total_ms",
              "rel_mse", "ssim", "passes_ms"], configs)
    write_csv(os.path.join(out, "series.csv"), ["scene", "size", "method", "frame", "total_ms",
              "rel_mse"], series)
    write_csv(os.path.join(out, "probe.csv"), ["scene", "size", "taps_local_per_ms",
              "taps_scattered_per_ms", "bytes_per_ms"], probe)
    write_csv(os.path.join(out, "memory.csv"), ["scene", "size", "image", "bytes"], memory)
    walk_rows = []
    for scene, w in walks.items():
        for run in w["walkthrough"]["runs"]:
            for name, values in run["passes"].items():
                walk_rows += [[scene, run["label"], f + 1, name, ms] + provenance(w)
                              for f, ms in enumerate(values)]
    write_csv(os.path.join(out, "walkthrough.csv"), ["scene", "method", "frame", "pass", "ms"],
              walk_rows)


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(x) for x in r) + " |" for r in rows]
    return "\n".join(lines) + "\n"


def targets(sweeps, walks, size):
    """The issues' targets against what this run measured (ratios within the run)."""
    rows = []
    for scene, sizes in sweeps.items():
        j = sizes[size]
        fr = {it["what"]: it["fraction"] for it in analysis.ceiling_fractions(j)}
        for what, label in (("ao: thesis AO 8x4", "thesis AO, 32 samples (8x4)"),
                             ("indirect: 512 VPLs + visibility", "VPL gather, 512 VPLs")):
            if what in fr:
                rows.append([scene, label + ": share of the probe's tap ceiling", ">= 60%",
                             "%.0f%%" % (100 * fr[what]), "yes" if fr[what] >= 0.6 else "no"])
        for series in j.get("series", []):
            st = analysis.still_camera(j, series["label"])
            if st:
                rows.append([scene, "still camera (%s), settled frame / (%s)"
                             % (st["label"], analysis.FLOOR_LABEL), "<= 1.15", "%.3f" % st["ratio"],
                             "yes" if st["ratio"] <= 1.15 else "no"])
    for scene, w in walks.items():
        runs = analysis.walk_runs(w)
        e_off = next(err for label, _, _, err in runs if label == "cache off")
        for label, _, speed, e_on in runs:
            if label == "cache off":
                continue
            ok = speed >= 4 and (math.isnan(e_on) or e_on <= e_off)
            rows.append([scene, "camera path (%s), frame time cache off / on (wall clock); mean "
                         "relMSE" % label, ">= 4x, error on <= off",
                         "%.2fx; %.4f off, %.4f on" % (speed, e_off, e_on), "yes" if ok else "no"])
    mem = {s: analysis.memory_totals(sweeps[s][size]).get("1920x1080") for s in sweeps}
    worst = max(v for v in mem.values() if v)
    rows.append(["all", "GPU memory the frame graph holds at 1920x1080 (cache on)", "<= 256 MB",
                 "%.0f MB (%.0f MiB)" % (worst / 1e6, worst / MIB),
                 "yes" if worst <= 256e6 else "no"])
    return table(["scene", "target", "wanted", "measured", "met"], rows)


def walkthrough_tables(scene, w, title):
    """One walkthrough's tables: per pass, cache off and on (the thesis's Tables 4.1-4.4), the
    error along the path, and every run against the uncached one."""
    md = []
    pass_rows, off, on, wall, errors = analysis.table_4_1(w)
    md.append("\n### %s on %s: the camera path (%d frames, %dx%d) with and without "
              "the cache\n\n" % (title, scene, w["walkthrough"]["frames"], w["width"], w["height"]))
    fmt = lambda v: "—" if v is None else "%.1f" % v
    ratio = lambda a, b: "—" if a is None or b is None else (
        "%.2f" % (a / b) if b >= 0.05 else "skipped when on")
    rows = [[n, fmt(a), fmt(b), ratio(a, b)] for n, a, b in pass_rows]
    rows.append(["**sum of passes**", fmt(off), fmt(on), "**%.2f**" % (off / on)])
    rows.append([wall[0], fmt(wall[1]), fmt(wall[2]), "%.2f" % (wall[1] / wall[2])])
    md.append("Means over the frames after the first; passes by GPU timestamps, the total "
              "by their sum, and the host's wall clock around each frame.\n\n")
    md.append(table(["pass", "off, ms", "on, ms", "off / on"], rows))
    if errors:
        md.append("\nError (relMSE against the reference at %dx%d) along the path:\n\n" %
                  (w["error_width"], w["error_height"]) + table(
                      ["frame", "cache off", "cache on"],
                      [[f + 1, "%.4f" % a, "%.4f" % b] for f, a, b in errors]))
    # Any other cached run of the same walkthrough (the thesis's cheap frames), against
    # the uncached one: frame time ratio and mean error.
    runs = analysis.walk_runs(w)
    if any(label not in ("cache off", "cache: thesis rule") for label, *_ in runs):
        rows = [[label, "%.1f" % ms, "%.2f" % speed, "%.4f" % err]
                for label, ms, speed, err in runs]
        md.append("\nEvery run of the walkthrough (wall clock, mean over the frames after the "
                  "first; mean relMSE over the error frames):\n\n" + table(
                      ["run", "frame, ms", "cache off / run", "mean relMSE"], rows))
    return "".join(md)


def tables(sweeps, walks, size, note):
    md = []
    first = next(iter(sweeps.values()))[size]
    md.append("Device: **%s**, driver %s, Vulkan %s; commit `%s`; %s. %s\n" % (
        first["device"]["name"], first["device"]["driver"], first["device"]["api"],
        first["commit"], first["date"], note))
    refs = ["%s %d spp (noise %.2f%%, so its own relMSE about %.5f)" % (
        scene, sz[size]["reference"]["samples"], 100 * sz[size]["reference"]["noise"],
        sz[size]["reference"]["noise"] ** 2)
        for scene, sz in sweeps.items() if "reference" in sz.get(size, {})]
    if refs:
        md.append("\nThe references of the error figures (each the path tracer's `full` image at "
                  "the error size, to 1%% estimated noise or 16,384 samples): %s.\n" %
                  "; ".join(refs))
    md.append("\n### Targets (issues 5 and 6), %s\n\n" % size)
    md.append(targets(sweeps, walks, size))
    md.append("\n### Best configuration at a time budget (cache off), %s\n\n" % size)
    md.append("Budgets are fractions of the scene's default frame (horizon AO 8x4, 384 VPLs + "
              "visibility, interleaved, shadow horizons 12x6) in the same run; error is relMSE "
              "against the reference.\n\n")
    rows = []
    for scene, sizes in sweeps.items():
        j = sizes[size]
        default_ms, best = analysis.best_at_budgets(j)
        for budget, b in best:
            rows.append([scene, "%d%% (%.0f ms)" % (budget * 100, budget * default_ms)] +
                        (["%s" % b[2], "%.2f" % (b[1] / default_ms), "%.4f" % b[0]] if b
                         else ["nothing fits", "", ""]))
    md.append(table(["scene", "budget", "least error", "its time / default", "relMSE"], rows))

    md.append("\n### Passes as a fraction of the ceiling probe, %s\n\n" % size)
    md.append("Fraction = time the probe kernels need for the pass's fetches (tap-bound "
              "passes: local taps against the local probe, the VPL gather's RSM taps against "
              "the scattered one) or bytes (the others) / the pass's time. Taps are counted "
              "without early rejections, so tap fractions are upper bounds.\n\n")
    fractions = {s: analysis.ceiling_fractions(sweeps[s][size]) for s in sweeps}
    order, cells = [], {}
    for scene, items in fractions.items():
        for it in items:
            if it["what"] not in order:
                order.append(it["what"])
            cells[(it["what"], scene)] = "%.0f%%" % (100 * it["fraction"])
    sources = {it["what"]: it["kind"] for items in fractions.values() for it in items}
    md.append(table(["pass", "bound by"] + list(sweeps),
                    [[k, sources[k]] + [cells.get((k, s), "") for s in sweeps] for k in order]))
    probe_rows = [[s, "%.3g" % sweeps[s][size]["probe"]["taps_local_per_ms"],
                   "%.3g" % sweeps[s][size]["probe"]["taps_scattered_per_ms"],
                   "%.2f" % (sweeps[s][size]["probe"]["bytes_per_ms"] / 1e6)] for s in sweeps]
    md.append("\nThe probe itself (taps per ms; GB/s):\n\n" + table(
        ["scene run", "local taps/ms", "scattered taps/ms", "bandwidth GB/s"], probe_rows))

    md.append("\n### Still camera, cache on, %s\n\n" % size)
    rows = []
    for scene, sizes in sweeps.items():
        for series in sizes[size].get("series", []):
            st = analysis.still_camera(sizes[size], series["label"])
            if st:
                rows.append([scene, st["label"][len("cache: "):], "%.2f" % st["ratio"],
                             "%.1f" % (st["uncached_ms"] / st["converged_wall_ms"]),
                             st["first_frame_within_1_5x"], st["frames"]])
    md.append("Settled = the last %d of the frames; the first ratio is per frame, all passes' "
              "timestamps over those of %s in the same frame (median over the frames); the "
              "second is the composed cache-off frame over the settled frame's wall clock.\n\n"
              % (analysis.CONVERGED_FRAMES, analysis.FLOOR_LABEL))
    md.append(table(["scene", "method", "settled frame / (%s)" % analysis.FLOOR_LABEL,
                     "cache off / settled", "first frame within 1.5x of settled",
                     "frames"], rows))

    for scene, w in walks.items():
        md.append(walkthrough_tables(scene, w, "Table 4.1"))

    md.append("\n### GPU memory the frame graph holds (cache on; transient images share one "
              "block), MiB\n\n")
    sizes_seen = sorted(next(iter(sweeps.values()))[size]["memory"],
                        key=lambda z: int(z.split("x")[0]) * int(z.split("x")[1]))
    md.append(table(["scene"] + sizes_seen, [
        [s] + ["%.1f" % (analysis.memory_totals(sweeps[s][size])[m] / MIB) for m in sizes_seen]
        for s in sweeps]))
    scene0 = next(iter(sweeps))
    per = analysis.memory_by_resource(sweeps[scene0][size]["memory"]["1920x1080"])
    md.append("\nPer resource at 1920x1080 (%s):\n\n" % scene0 + table(
        ["image", "MiB"], [[n, "%.1f" % (b / MIB)] for n, b in per]))

    md.append("\n### Check of the composed frame times\n\n")
    md.append("A configuration's time is composed from per-pass medians pooled over the rows "
              "plus the host's overhead per frame; the check row is one configuration away from "
              "every default, also timed whole (host wall clock).\n\n")
    md.append(table(["scene", "size", "configuration timed whole", "composed / measured",
                     "host overhead, ms", "timestamps"], [
        [s, z, j["timing"]["check_label"],
         "%.2f" % (j["timing"]["check_composed_ms"] / j["timing"]["check_measured_ms"]),
         "%.1f" % j["timing"]["overhead_ms"],
         "%d" % j["timing"]["timestamps"]]
        for s in sweeps for z, j in sorted(sweeps[s].items())]))
    other = sorted({z for s in sweeps for z in sweeps[s] if z != size})
    for z in other:
        md.append("\n### Default configuration per pass, %s against %s\n\n" % (z, size))
        rows = []
        for s in sweeps:
            if z in sweeps[s]:
                a = analysis.default_config(sweeps[s][size])["passes"]
                b = analysis.default_config(sweeps[s][z])["passes"]
                ratio = (analysis.default_config(sweeps[s][z])["total_ms"] /
                         analysis.default_config(sweeps[s][size])["total_ms"])
                rows.append([s] + ["%.2f" % (b[p] / a[p]) if a.get(p) and p in b else "—"
                                   for p in ("gbuffer", "shadow", "ao", "indirect", "upsample",
                                             "composite")] + ["%.2f" % ratio])
        md.append(table(["scene", "gbuffer", "shadow", "ao", "indirect", "upsample", "composite",
                         "frame (model)"], rows))
        md.append("\nBest configuration at a time budget, %s (error from the %s run):\n\n" %
                  (z, size))
        rows = []
        for s in sweeps:
            if z in sweeps[s]:
                default_ms, best = analysis.best_at_budgets(sweeps[s][z], sweeps[s][size])
                rows += [[s, "%d%%" % (budget * 100)] + ([b[2], "%.2f" % (b[1] / default_ms),
                                                         "%.4f" % b[0]] if b else ["—", "", ""])
                         for budget, b in best]
        md.append(table(["scene", "budget", "least error", "its time / default", "relMSE"], rows))
    return "".join(md)


def write_tables(md, results, name, doc_path, begin, end):
    """The tables as results/NAME, and in place of what stands between the markers begin and end
    of the doc, when one is given."""
    with open(os.path.join(results, name), "w") as f:
        f.write(md)
    if doc_path:
        with open(doc_path) as f:
            doc = f.read()
        pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
        doc = pattern.sub(lambda _: begin + "\n" + md + end, doc)
        with open(doc_path, "w") as f:
            f.write(doc)
    print("tables: %s" % os.path.join(results, name))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--results", required=True)
    ap.add_argument("--images", required=True)
    ap.add_argument("--size", default="512x512")
    ap.add_argument("--doc")
    ap.add_argument("--note", default="")
    a = ap.parse_args()
    sweeps, walks = analysis.load(a.results)
    sweeps = {s: z for s, z in sweeps.items() if a.size in z}
    os.makedirs(a.images, exist_ok=True)
    write_csvs(sweeps, walks, a.results)
    charts.draw_all(sweeps, walks, a.size, a.images)
    write_tables(tables(sweeps, walks, a.size, a.note), a.results, "tables.md", a.doc,
                 BEGIN, END)


if __name__ == "__main__":
    main()
