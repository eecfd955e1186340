"""The benchmark's charts (PNG and SVG): error against time per scene with the Pareto front,
per-pass stacked times, error and time frame by frame on a still camera, and the walkthrough
with the cache off and on."""

import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

import analysis  # noqa: E402

GROUP_STYLE = {  # group -> (colour, marker, legend)
    "default": ("black", "*",
                "defaults (horizon AO 8x4, 384 VPLs + visibility, interleaved, shadow horizons 12x6)"),
    "ao": ("tab:blue", "o", "AO / SSDO varied"),
    "indirect": ("tab:orange", "s", "indirect varied"),
    "shadow": ("tab:green", "^", "shadow varied"),
    "cheap": ("tab:purple", "D", "AO 4x2 + PCF 9, indirect varied"),
    "direct only": ("tab:gray", "v", "direct light only"),
}
# Passes in frame order, each effect in its own hue (its temporal and keep passes lighter).
PASS_COLOURS = {
    "gbuffer": "#4e79a7", "rsm": "#a0cbe8", "shadow": "#59a14f", "shadow.temporal": "#8cd17d",
    "shadow.keep": "#c7e9c0", "direct": "#b6992d", "ao": "#e15759", "ssdo": "#d37295",
    "ao.temporal": "#ff9d9a", "ao.keep": "#fcd0cf", "ssdo.temporal": "#fabfd2",
    "indirect.flux": "#d4a373", "indirect.vpls": "#e9c46a", "indirect": "#f28e2b", "upsample": "#ffbe7d", "indirect.filter_x": "#ffbe7d",
    "indirect.filter_y": "#ffd8a8", "indirect.temporal": "#f1ce63",
    "indirect.keep": "#f7e3a8", "temporal": "#bab0ac", "composite": "#79706e",
}


def device_of(j):
    return j["device"]["name"].split(" (")[0] + " (%s)" % j["device"]["driver"]


def save(fig, images_dir, name):
    fig.savefig("%s/%s.png" % (images_dir, name), dpi=110)
    fig.savefig("%s/%s.svg" % (images_dir, name))
    plt.close(fig)


def short(label):
    return (label.replace(" + visibility", "+vis").replace(" VPLs", " VPL")
            .replace("thesis AO", "thesis").replace("horizon AO", "horizon")
            .replace("Crytek AO", "Crytek").replace("no indirect", "no ind."))


def pareto_chart(scene, sweep, images_dir):
    fig, ax = plt.subplots(figsize=(9, 6.2))
    points = []
    for group, (colour, marker, legend) in GROUP_STYLE.items():
        cs = [c for c in sweep["configs"] if c["group"] == group and "rel_mse" in c]
        ax.scatter([c["total_ms"] for c in cs], [c["rel_mse"] for c in cs], c=colour,
                   marker=marker, s=110 if group == "default" else 32, label=legend, zorder=3)
        points += [(c["total_ms"], c["rel_mse"], c["label"]) for c in cs]
    cached = analysis.cached_points(sweep)
    if cached:
        ax.scatter([p[0] for p in cached], [p[1] for p in cached], c="tab:red", marker="P",
                   s=80, zorder=3, label="defaults + cache, still camera, settled (median wall "
                   "clock of frames %d-%d, error of the last)" % (
                       sweep["series_frames"] - analysis.CONVERGED_FRAMES + 1,
                       sweep["series_frames"]))
    front = analysis.pareto(points + cached)
    ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="tab:red",
            alpha=0.5, lw=1.5, label="Pareto front", zorder=2)
    for i, p in enumerate(front):
        ax.annotate(str(i + 1), (p[0], p[1]), textcoords="offset points", xytext=(4, 4),
                    fontsize=8, color="tab:red", weight="bold")
    listing = "\n".join("%d  %s" % (i + 1, short(p[2])) for i, p in enumerate(front))
    ax.text(1.02, 1.0, "Pareto front:\n" + listing, transform=ax.transAxes, fontsize=7,
            va="top", family="monospace")
    ax.set_xscale("log")
    ys = [p[1] for p in points + cached]
    if max(ys) > 5 * min(ys):
        ax.set_yscale("log")
    ax.xaxis.set_minor_locator(matplotlib.ticker.LogLocator(subs=(2, 5)))
    ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.tick_params(axis="x", which="minor", labelsize=7)
    ax.set_xlabel("frame time, ms (per-pass medians + host overhead, %dx%d; cache off unless "
                  "marked)" % (sweep["width"], sweep["height"]), fontsize=9)
    ax.set_ylabel("relMSE against the path-traced reference\n(%dx%d, pixels with geometry)"
                  % (sweep["error_width"], sweep["error_height"]), fontsize=9)
    ax.set_title("%s: error against frame time\n%s" % (scene, device_of(sweep)), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0.0, -0.12), ncol=2)
    fig.tight_layout()
    save(fig, images_dir, "bench-pareto-%s" % scene)


def selected_bars(sweep):
    """(label, passes) of a few configurations worth comparing pass by pass."""
    wanted = ["horizon AO 8x4 + 384 VPLs + visibility, interleaved + horizons 12x6",
              "horizon AO 8x4 + 384 VPLs + visibility, interleaved + PCF 49",
              "horizon AO 8x4 + 512 VPLs + visibility + horizons 12x6",
              "horizon AO 8x4 + 512 VPLs + horizons 12x6",
              "horizon AO 8x4 + 64 VPLs + visibility + horizons 12x6",
              "thesis AO 8x4 + 512 VPLs + visibility + horizons 12x6",
              "SSDO 16 + 512 VPLs + visibility + horizons 12x6",
              "horizon AO 8x4 + 512 VPLs + visibility + PCF 9",
              "thesis AO 4x2 + 256 VPLs + PCF 9",
              "no AO + no indirect + PCF 9"]
    by_label = {c["label"]: c["passes"] for c in sweep["configs"]}
    bars = [(short(w), by_label[w]) for w in wanted if w in by_label]
    still = analysis.still_camera(sweep)
    if still:
        bars.append(("defaults, cached, settled", still["passes"]))
    return bars


def pass_bars_chart(sweeps, size, images_dir):
    scenes = [s for s in sweeps if size in sweeps[s]]
    fig, axes = plt.subplots(len(scenes), 1, figsize=(9, 2.7 * len(scenes)), squeeze=False)
    names = set()
    for s in scenes:
        for _, passes in selected_bars(sweeps[s][size]):
            names |= set(passes)
    names = analysis.frame_order(names)
    colours = {n: PASS_COLOURS.get(n, "#bab0ac") for n in names}
    for ax, scene in zip(axes[:, 0], scenes):
        bars = selected_bars(sweeps[scene][size])
        for y, (label, passes) in enumerate(bars):
            left = 0.0
            for name in names:
                ms = passes.get(name, 0.0)
                if ms > 0:
                    ax.barh(y, ms, left=left, color=colours[name], edgecolor="white", lw=0.3,
                            label=name)
                left += ms
        ax.set_yticks(range(len(bars)))
        ax.set_yticklabels([b[0] for b in bars], fontsize=7)
        ax.invert_yaxis()
        ax.set_title("%s, %s" % (scene, size), fontsize=9, loc="left")
        ax.grid(True, axis="x", alpha=0.3)
        ax.tick_params(axis="x", labelsize=7)
    axes[-1, 0].set_xlabel("ms per pass (GPU timestamps, medians; cache off unless marked)")
    fig.suptitle("Per-pass frame time  —  %s" % device_of(sweeps[scenes[0]][size]), fontsize=10)
    seen = {}
    for ax in axes[:, 0]:
        for h, label in zip(*ax.get_legend_handles_labels()):
            seen.setdefault(label, h)
    labels = [n for n in names if n in seen]
    fig.legend([seen[n] for n in labels], labels, fontsize=7, ncol=8, loc="lower center")
    fig.tight_layout(rect=(0, 0.06, 1, 0.97))
    save(fig, images_dir, "bench-passes")


def series_charts(sweeps, size, images_dir):
    scenes = [s for s in sweeps if size in sweeps[s] and sweeps[s][size].get("series")]
    if not scenes:
        return
    fig, axes = plt.subplots(2, len(scenes), figsize=(4.2 * len(scenes), 6.4), squeeze=False)
    for k, scene in enumerate(scenes):
        sweep = sweeps[scene][size]
        err_ax, time_ax = axes[0, k], axes[1, k]
        for s in sweep["series"]:
            if "rel_mse" in s:
                err_ax.plot(range(1, len(s["rel_mse"]) + 1), s["rel_mse"], label=s["label"])
            if "wall_ms" in s:
                time_ax.plot(range(1, len(s["wall_ms"]) + 1), s["wall_ms"], label=s["label"])
        default = analysis.default_config(sweep)
        if "rel_mse" in default:
            err_ax.axhline(default["rel_mse"], color="gray", ls="--", label="cache off")
        time_ax.axhline(default["total_ms"], color="gray", ls="--", label="cache off")
        still = analysis.still_camera(sweep)
        if still:
            time_ax.axhline(still["floor_ms"], color="black", ls=":",
                            label="%s (timestamps)" % analysis.FLOOR_LABEL)
        err_ax.set_title(scene, fontsize=10)
        err_ax.set_ylabel("relMSE vs reference (%dx%d)" % (sweep["error_width"],
                                                            sweep["error_height"]))
        time_ax.set_ylabel("frame ms (host wall clock), %s" % size, fontsize=8)
        time_ax.set_yscale("log")
        time_ax.set_xlabel("frame index (still camera)")
        for ax in (err_ax, time_ax):
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=6.5)
    fig.suptitle("Temporal cache on a still camera: error and frame time per frame  —  %s"
                 % device_of(sweeps[scenes[0]][size]), fontsize=10)
    fig.tight_layout()
    save(fig, images_dir, "bench-convergence")


def walkthrough_chart(walks, images_dir, name="bench-walkthrough", scenes=None):
    scenes = scenes or sorted(walks)
    if not scenes:
        return
    fig, axes = plt.subplots(1, len(scenes), figsize=(max(8, 5 * len(scenes)), 4),
                             squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        w = walks[scene]
        for run in w["walkthrough"]["runs"]:
            totals = run["wall_ms"]
            ax.plot(range(1, len(totals) + 1), totals,
                    label="%s (mean %.0f ms)" % (run["label"], statistics.mean(totals[1:])))
        ax.set_ylim(bottom=0)
        ax.set_xlabel("frame along the camera path")
        ax.set_ylabel("frame ms (host wall clock), %dx%d" % (w["width"], w["height"]),
                      fontsize=8)
        ax.set_title(scene, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("The camera path with the cache off and on (frames alternated)\n%s"
                 % device_of(walks[scenes[0]]), fontsize=10)
    fig.tight_layout()
    save(fig, images_dir, name)


def draw_all(sweeps, walks, size, images_dir):
    for scene in sweeps:
        if size in sweeps[scene] and any("rel_mse" in c for c in sweeps[scene][size]["configs"]):
            pareto_chart(scene, sweeps[scene][size], images_dir)
    pass_bars_chart(sweeps, size, images_dir)
    series_charts(sweeps, size, images_dir)
    walkthrough_chart(walks, images_dir)
