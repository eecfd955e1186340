"""Numbers derived from the benchmark's JSON: Pareto fronts, best configurations at time
budgets, each pass as a fraction of the ceiling probe, the still camera's ratio to its floor,
Table 4.1, memory. Every derived figure is a ratio of times measured in one process."""

import glob
import json
import os
import statistics

# The passes a converged still frame cannot avoid (the cached frame's floor): the direct light
# and the composite. The G-buffer is kept from a still camera's third frame on.
FLOOR_PASSES = ("direct", "composite")
FLOOR_LABEL = " + ".join(FLOOR_PASSES)
# The passes in the order a frame runs them (tables and charts list them so).
FRAME_ORDER = ("gbuffer", "rsm", "indirect.flux", "indirect.vpls", "indirect", "upsample",
               "indirect.filter_x", "indirect.filter_y", "indirect.temporal", "indirect.keep",
               "shadow", "shadow.temporal", "shadow.keep", "ao", "ssdo", "ao.temporal", "ao.keep",
               "ssdo.temporal", "ssdo.keep", "temporal", "direct", "composite")


def load_runs(results_dir, kind):
    """The JSON files KIND-*.json of one run (benchmark KIND's results), in name order; exits
    with an error when there are none."""
    runs = []
    for path in sorted(glob.glob(os.path.join(results_dir, kind + "-*.json"))):
        with open(path) as f:
            runs.append(json.load(f))
    if not runs:
        raise SystemExit("error: no %s-*.json in %s" % (kind, results_dir))
    return runs


def frame_order(names):
    return sorted(names, key=lambda n: (FRAME_ORDER.index(n) if n in FRAME_ORDER else 99, n))


# Every timestamp is taken as it stands: the frame graph makes them true on lavapipe too (a
# barrier after each stamp; docs/profiling.md), so no pass time is filtered out.
# Time budgets as fractions of the scene's default configuration (cache off).
BUDGETS = (0.1, 0.25, 0.5, 1.0)
# Frames at the end of a still series taken as converged.
CONVERGED_FRAMES = 5
# Bytes each bandwidth-bound pass reads and writes per pixel (formats of renderer/passes/):
# direct reads position 16, normal 8, albedo 4, shadow 8 and writes 8; composite reads those,
# AO, indirect (8 each) and writes HDR 16 + LDR 4. (The gbuffer pass is left out:
# rasterization, not bytes, bounds it on a CPU device.)
PASS_BYTES = {"direct": 44, "composite": 80}
VISIBILITY_STEPS = 6  # indirect_visibility_steps' default


def load(results_dir):
    """sweeps[scene][size] and walks[scene], from the JSON files of one run; every sweep's
    configurations get their composed "passes" and "total_ms" (compose_times)."""
    sweeps, walks = {}, {}
    for path in sorted(glob.glob(os.path.join(results_dir, "*.json"))):
        with open(path) as f:
            j = json.load(f)
        size = "%dx%d" % (j["width"], j["height"])
        if j.get("kind") == "sweep":
            compose_times(j)
            sweeps.setdefault(j["scene"], {})[size] = j
        elif j.get("kind") == "walkthrough":
            walks[j["scene"]] = j
    return sweeps, walks


def skipped(settings):
    """Passes a configuration records a timestamp for but never runs (the graph writes both
    timestamps of a disabled pass back to back): the half-res gather at full resolution."""
    thesis = settings.get("indirect_method", 0) == 0
    return {"indirect"} if thesis and settings.get("indirect_half_res", 1) == 0 else set()


def compose_times(sweep):
    """Each pass's time is the median of its frames pooled over every row that runs it with the
    same value of its axis (the passes of no axis over every row); a configuration's time is the
    sum of its passes plus the host's overhead per frame (wall clock less the sum of the
    passes)."""
    warm, rows = sweep["warmup"], sweep["rows"]
    axis_names = [a["name"] for a in sweep["axes"]]
    axis_of = {p: i for i, a in enumerate(sweep["axes"]) for p in a["passes"]}
    key = lambda row, p: (p, row["index"][axis_of[p]] if p in axis_of else None)
    pools, overheads = {}, []
    for row in rows:
        for f in range(warm, len(row["wall_ms"])):
            skip = skipped(row["settings"])
            frame = {p: v[f] for p, v in row["passes"].items() if p not in skip}
            for p, v in frame.items():
                pools.setdefault(key(row, p), []).append(v)
            overheads.append(row["wall_ms"][f] - sum(frame.values()))
    medians = {k: statistics.median(v) for k, v in pools.items()}
    overhead = statistics.median(overheads) if overheads else 0.0

    def passes_of(index):
        out = {}
        default_row = rows[sweep["row_of"][axis_names[0]][0]]
        for a, name in enumerate(axis_names):
            row = rows[sweep["row_of"][name][index[a]]]
            for p in row["passes"]:
                if p in axis_of and axis_of[p] == a and p not in skipped(row["settings"]):
                    out[p] = medians[key(row, p)]
        for p in default_row["passes"]:
            if p not in axis_of:
                out[p] = medians[key(default_row, p)]
        return out

    for c in sweep["configs"]:
        c["passes"] = passes_of(c["index"])
        c["total_ms"] = sum(c["passes"].values()) + overhead
    check = rows[sweep["check_row"]]
    sweep["timing"] = {"overhead_ms": overhead, "check_label": check["label"],
                       "check_measured_ms": statistics.median(check["wall_ms"][warm:]),
                       "check_composed_ms": sum(passes_of(check["index"]).values()) + overhead,
                       "timestamps": sum(len(v) for v in pools.values())}


def default_config(sweep):
    return next(c for c in sweep["configs"] if c["group"] == "default")


def pareto(points):
    """The points (ms, error, ...) no other point beats on both time and error, by time."""
    front, best = [], float("inf")
    for p in sorted(points, key=lambda p: (p[0], p[1])):
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def cached_points(sweep):
    """(settled frame ms: median wall clock of the series' last frames, error at its last frame,
    label) of each cached method on the still camera."""
    points = []
    for s in sweep.get("series", []):
        if "wall_ms" in s and "rel_mse" in s:
            points.append((statistics.median(s["wall_ms"][-CONVERGED_FRAMES:]), s["rel_mse"][-1],
                           s["label"] + ", settled"))
    return points


def best_at_budgets(sweep, errors_from=None):
    """For each budget: the configuration (cache off) with the least error within it."""
    errors = {c["label"]: c.get("rel_mse") for c in (errors_from or sweep)["configs"]}
    default_ms = default_config(sweep)["total_ms"]
    rows = []
    for budget in BUDGETS:
        fits = [(errors[c["label"]], c["total_ms"], c["label"]) for c in sweep["configs"]
                if c["total_ms"] <= budget * default_ms and errors.get(c["label"]) is not None]
        rows.append((budget, min(fits) if fits else None))
    return default_ms, rows


def still_camera(sweep, label=None):
    """The still camera under a cache method (the first measured, the thesis rule, unless
    `label` names another): converged frame time against its floor, both sums of per-pass
    medians of the last frames."""
    series = next((s for s in sweep.get("series", [])
                   if "total_ms" in s and label in (None, s["label"])), None)
    if not series:
        return None
    n = len(series["wall_ms"])
    tail = slice(n - CONVERGED_FRAMES, n)
    # Per frame: every pass's timestamps over the floor passes' in the same frame; the median of
    # those ratios.
    ratios = []
    for f in range(n - CONVERGED_FRAMES, n):
        frame = {p: v[f] for p, v in series["passes"].items()}
        floor_f = sum(frame.get(p, 0.0) for p in FLOOR_PASSES)
        if floor_f > 0.0:
            ratios.append(sum(frame.values()) / floor_f)
    passes = {p: statistics.median(v[tail]) for p, v in series["passes"].items()}
    converged = sum(passes.values())
    floor = sum(passes.get(p, 0.0) for p in FLOOR_PASSES)
    walls = series["wall_ms"]
    first_cheap = next((f for f, t in enumerate(walls)
                        if t <= 1.5 * statistics.median(walls[tail])), None)
    return {"label": series["label"], "converged_ms": converged, "floor_ms": floor,
            "ratio": statistics.median(ratios) if ratios else converged / floor,
            "ratio_frames": len(ratios), "converged_wall_ms": statistics.median(walls[tail]),
            "uncached_ms": default_config(sweep)["total_ms"],
            "first_frame_within_1_5x": None if first_cheap is None else first_cheap + 1,
            "frames": n, "passes": passes}


def value_taps(axis, settings):
    """(local taps, scattered taps) the pass of an axis value fetches per computed pixel, at
    most (early rejections skip some, so a fraction computed from these is an upper bound)."""
    if axis == "ao" and settings.get("ssdo"):
        return settings["ssdo_samples"], 0
    if axis == "ao" and settings.get("ao"):
        n = settings["ao_directions"] * settings["ao_steps"]
        return (2 * n if settings["ao_variant"] == 2 else n), 0  # horizon: both sides
    if axis == "shadow":
        if settings.get("shadow_variant") == 1:  # horizons: each direction's origin + steps
            return settings["shadow_directions"] * (settings["shadow_steps"] + 1), 0
        taps = settings["shadow_taps"]
        return (1 if taps == 1 else 2 * taps), 0  # blocker search + filter
    if axis == "indirect" and settings.get("indirect"):
        vpls = settings["indirect_vpls"]
        method = settings.get("indirect_method", 0)
        if method in (1, 2):  # interleaved: a k x k block shares them
            k = settings.get("indirect_interleave", 4)
            vpls = max(1, vpls // (k * k))
        marched = vpls  # VPLs whose visibility is tested
        if method == 2:  # importance: the flux's VPLs beside them, a few of all tested
            vpls += max(1, settings.get("indirect_flux_vpls", 64) // (k * k))
            marched = min(vpls, settings.get("indirect_visibility_tests", 6))
        # Each of the RSM's VPLs one 16-byte texel (rsm_vpl.glsl); method 2's VPL map its
        # position, normal and flux in three images. The visibility march in the G-buffer.
        scattered = 3 * vpls if method == 2 else vpls
        return VISIBILITY_STEPS * marched * settings["indirect_visibility"], scattered
    return None


def ceiling_fractions(sweep):
    """Each axis value's pass, and the bandwidth-bound passes of the defaults, as a fraction of
    what the probe says the device can do: the probe's time for the same fetches or bytes over
    the pass's time (composed as for the configurations)."""
    probe = sweep["probe"]
    w, h = sweep["width"], sweep["height"]
    geometry = sweep["geometry_fraction"]
    by_label = {c["label"]: c for c in sweep["configs"]}
    default = default_config(sweep)
    out = []
    for a, axis in enumerate(sweep["axes"]):
        for value in axis["values"]:
            taps = value_taps(axis["name"], value["settings"])
            if not taps:
                continue
            label = " + ".join(value["label"] if i == a else v["values"][0]["label"]
                               for i, v in enumerate(sweep["axes"]))
            passes = by_label[label]["passes"]
            name = next(p for p in axis["passes"] if p in passes)
            half = name == "indirect" and value["settings"].get("indirect_method", 0) == 0
            pixels = geometry * w * h / (4 if half else 1)
            ideal = pixels * (taps[0] / probe["taps_local_per_ms"] +
                              taps[1] / probe["taps_scattered_per_ms"])
            out.append({"what": "%s: %s" % (name, value["label"]), "ms": passes[name],
                        "kind": "taps", "fraction": ideal / passes[name]})
    for name, per_pixel in PASS_BYTES.items():
        ms = default["passes"].get(name)
        if ms:
            out.append({"what": name, "ms": ms, "kind": "bandwidth",
                        "fraction": w * h * per_pixel / probe["bytes_per_ms"] / ms})
    return out


def walk_runs(walk):
    """Every run of a walkthrough against the uncached one, in order: (label, wall-clock ms as a
    mean over the frames after the first, cache off / run, mean relMSE over the error frames;
    nan where a run has none)."""
    runs = walk["walkthrough"]["runs"]
    mean = lambda v: sum(v) / len(v) if v else float("nan")
    off_ms = mean(next(r for r in runs if r["label"] == "cache off")["wall_ms"][1:])
    out = []
    for r in runs:
        ms = mean(r["wall_ms"][1:])
        out.append((r["label"], ms, off_ms / ms, mean(r.get("rel_mse", []))))
    return out


def table_4_1(walk):
    """Per pass: mean ms over the frames after the first, cache off and on, and their ratio."""
    runs = {r["label"]: r for r in walk["walkthrough"]["runs"]}
    off, on = runs["cache off"], runs["cache: thesis rule"]
    names = frame_order(set(off["passes"]) | set(on["passes"]))
    def mean(values):  # over the frames after the first
        v = values[1:] if len(values) > 1 else values
        return statistics.mean(v) if v else 0.0
    rows = []
    for name in names:
        a = mean(off["passes"][name]) if name in off["passes"] else None
        b = mean(on["passes"][name]) if name in on["passes"] else None
        rows.append((name, a, b))
    total_off = sum(a for _, a, _ in rows if a)
    total_on = sum(b for _, _, b in rows if b)
    wall = ("frame wall clock (host)", mean(off["wall_ms"]), mean(on["wall_ms"]))
    errors = list(zip(walk["walkthrough"]["error_frames"], off.get("rel_mse", []),
                      on.get("rel_mse", [])))
    return rows, total_off, total_on, wall, errors


def memory_totals(sweep):
    """What the frame graph holds: every image not in the transient images' shared block, and the
    block (a run before the block existed lists neither)."""
    return {size: sum(e["bytes"] for e in images if not e.get("shared"))
            for size, images in sweep["memory"].items()}


def memory_by_resource(images):
    """History pairs (both sides of pair X) summed under X, largest first; an image in the shared
    block is marked, its bytes counted in the block's row."""
    grouped = {}
    for e in images:
        name = e["history"] + " (pair)" if e.get("history") else e["image"]
        if e.get("shared"):
            name += " (in the shared block)"
        grouped[name] = grouped.get(name, 0) + e["bytes"]
    return sorted(grouped.items(), key=lambda kv: -kv[1])
