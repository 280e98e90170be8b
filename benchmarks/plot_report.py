#!/usr/bin/python3
"""Turns `obscura bench` output into error-vs-time Pareto plots and docs/results.md.

    /usr/bin/python3 benchmarks/plot_report.py out/bench/bench.json --out docs

Reads one or more bench.json files (rows + reference performance), writes
<out>/results.md and <out>/results/<scene>_<quantity>.png. Needs Debian's
python3-matplotlib, hence /usr/bin/python3 rather than whatever python3 is first on PATH.
"""
import argparse
import json
import math
import os
import re
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def measures_own_error(row):
    """False for an "indirect_unshadowed" row of a shadowed G-buffer. Before the bench emitted it
    only with shadows=0, runs compared a shadowed gathering with the unshadowed reference, which
    is not the method's own error the quantity stands for."""
    return row["quantity"] != "indirect_unshadowed" or row.get("settings", {}).get("shadows") in ("0", "false", "off")


def load(paths):
    rows, perf, voxel = [], [], {"voxelization": [], "traversal": []}
    for path in paths:
        with open(path) as f:
            doc = json.load(f)
        rows.extend(r for r in doc.get("rows", []) if measures_own_error(r))
        perf.extend(doc.get("reference_performance", []))
        for table in voxel:
            voxel[table].extend(doc.get("voxel", {}).get(table, []))
    return rows, perf, voxel


def slug(text):
    return re.sub(r"[^A-Za-z0-9]+", "_", text).strip("_").lower()


def pareto(points):
    """Indices of the points no other point beats in both time and error (lower is better)."""
    front = []
    for i, (t, e) in enumerate(points):
        dominated = any((t2 <= t and e2 <= e) and (t2 < t or e2 < e) for j, (t2, e2) in enumerate(points) if j != i)
        if not dominated:
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def plot(scene, quantity, rows, path):
    fig, ax = plt.subplots(figsize=(5.5, 3.8), dpi=110)
    points = [(own_ms(r), max(r["rmse"], 1e-12)) for r in rows]
    for r, (t, e) in zip(rows, points):
        ax.scatter([t], [e], s=30)
        ax.annotate(f'{r["technique"]} {r["preset"]}', (t, e), fontsize=7, xytext=(4, 3), textcoords="offset points")
    front = pareto(points)
    if len(front) > 1:
        ax.plot([points[i][0] for i in front], [points[i][1] for i in front], "k--", lw=0.8, label="Pareto front")
        ax.legend(fontsize=7)
    noise = max((r["ref_noise_rmse"] for r in rows), default=0.0)
    if noise > 0:
        ax.axhline(noise, color="gray", lw=0.8, ls=":")
        ax.text(ax.get_xlim()[0], noise, " reference noise", fontsize=7, color="gray", va="bottom")
    ax.set_yscale("log")
    clock = rows[0]["clock"]
    ax.set_xlabel(f"time of the technique's own passes, ms ({clock})")
    ax.set_ylabel(f"RMSE of {quantity}")
    ax.set_title(f"{scene}: {quantity}", fontsize=9)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def fmt(v, digits=4):
    if v is None:
        return "n/a"
    if isinstance(v, float):
        if v == 0:
            return "0"
        if math.isnan(v):
            return "n/a"
        if math.isinf(v):
            return "inf"
        return f"{v:.{digits}g}"
    return str(v)


def plot_voxelization(rows, path):
    fig, ax = plt.subplots(figsize=(5.5, 3.8), dpi=110)
    for mode in sorted({r["mode"] for r in rows}):
        mrows = sorted((r for r in rows if r["mode"] == mode), key=lambda r: r["resolution"] ** 2 * r["slices"])
        ax.plot([r["resolution"] ** 2 * r["slices"] for r in mrows], [r["ms"] for r in mrows], "o-", label=mode)
        for r in mrows:
            ax.annotate(f'{r["resolution"]}²x{r["slices"]}', (r["resolution"] ** 2 * r["slices"], r["ms"]), fontsize=6,
                        xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("voxels in the grid")
    ax.set_ylabel(f'time per voxelization, ms ({rows[0]["clock"]})')
    ax.set_title(f'voxelization of {rows[0]["triangles"]} triangles', fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_traversal(rows, path):
    """Time per segment against the share of answers that differ from the exact traversal."""
    fig, ax = plt.subplots(figsize=(5.5, 3.8), dpi=110)
    for r in rows:
        t = r["ms"] * 1e6 / r["count"]
        e = max(1.0 - r["agrees_with_exact"], 1e-6)
        ax.scatter([t], [e], s=25)
        ax.annotate(f'{r["scene"]} {r["segments"]} {r["method"]}', (t, e), fontsize=6, xytext=(3, 3),
                    textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(f'time per segment, ns ({rows[0]["clock"]})')
    ax.set_ylabel("share of hit/miss answers unlike exact (floor 1e-6)")
    ax.set_title("visibility in voxel space", fontsize=9)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def shared_input(technique, pass_name):
    """Whether a pass renders an input the technique shares with the others rather than its own work:
    the G-buffer, and the shadow maps that light it, for AO, obscurance and GI; the G-buffer for the
    shadow techniques, whose maps are their own. The gbuffer and compose techniques are whole frames."""
    if technique in ("gbuffer", "compose"):
        return False
    if pass_name.startswith("gbuffer"):
        return True
    return pass_name == "shadow.maps" and not technique.startswith("shadow.")


def own_ms(row):
    """The time of the technique's own passes (see shared_input)."""
    return sum(p["median_ms"] for p in row.get("passes", []) if not shared_input(row["technique"], p["pass"]))


HALF_PAIRS = ("medium", "high")  # presets X and X_half: the same rays and steps, full and half resolution
REDUCED_RESOLUTION_PASSES = (".tiles", ".blur", ".upsample", ".refine")  # what X_half runs besides its integrator


def resolution_rows(rows):
    """Table lines of X (full resolution) against X_half (half resolution + blur), per preset pair, technique and size."""
    pairs = defaultdict(dict)
    for r in default_runs(rows):
        base = r["preset"][:-len("_half")] if r["preset"].endswith("_half") else r["preset"]
        if base in HALF_PAIRS:
            size = f'{r["width"]}x{r["height"]}'
            pairs[(r["scene"], size, base, r["technique"], r["quantity"])][r["preset"]] = r
    lines = []
    for key, p in sorted(pairs.items()):
        if len(p) != 2:
            continue
        full, half = p[key[2]], p[key[2] + "_half"]
        full_ms, half_ms = own_ms(full), own_ms(half)
        besides_ms = sum(q["median_ms"] for q in half["passes"] if q["pass"].endswith(REDUCED_RESOLUTION_PASSES))
        speedup = full_ms / half_ms if half_ms > 0 else float("nan")
        ratio = half["rmse"] / full["rmse"] if full["rmse"] > 0 else float("nan")
        ok = speedup >= 2.0 and ratio < 2.0
        lines.append(f'| {key[0]} | {key[1]} | {key[2]} | {key[3]} | {key[4]} | {fmt(full_ms)} | {fmt(half_ms)} | '
                     f'{fmt(besides_ms)} | {fmt(speedup, 3)} | {fmt(full["rmse"])} | {fmt(half["rmse"])} | {fmt(ratio, 3)} | '
                     f'{"yes" if ok else "**no**"} |')
    return lines


def ray_lanes(row):
    """The row's rayLanes setting (invocations per pixel's rays; 1 unless set)."""
    return int(row.get("settings", {}).get("ray_lanes", 1))


def default_runs(rows):
    """The rows of no --variant, at the default of one ray lane and with geometry tiles: the other tables
    compare those; the lanes and tiles studies have their own."""
    return [r for r in rows if not r.get("variant") and ray_lanes(r) == 1 and geometry_tiles(r)]


def varying_only(rows, key):
    """The rows whose --variant (if any) sets `key` alone: a study of `key` compares those, and not a
    variant that also changes something else."""
    return [r for r in rows if {kv.split("=")[0] for kv in r.get("variant", "").split(",") if kv} <= {key}]


def lanes_lines(rows):
    """Table lines: per scene, size, technique, quantity and preset, the own time at each ray-lane count
    present, and for X / X_half pairs the half-resolution speed-up at each."""
    runs = defaultdict(dict)
    for r in varying_only(rows, "ray_lanes"):
        if not geometry_tiles(r):
            continue
        runs[(os.path.basename(r["scene"]), f'{r["width"]}x{r["height"]}', r["technique"], r["quantity"],
              r["preset"])][ray_lanes(r)] = r
    counts = sorted({n for by_lanes in runs.values() for n in by_lanes})
    if len(counts) < 2:
        return [], counts
    lines = []
    for key, by_lanes in sorted(runs.items()):
        if key[4].endswith("_half") or key[4] + "_half" not in {k[4] for k in runs if k[:4] == key[:4]}:
            continue
        half = runs[key[:4] + (key[4] + "_half",)]
        cells = [fmt(own_ms(by_lanes[n])) if n in by_lanes else "" for n in counts]
        cells += [fmt(own_ms(half[n])) if n in half else "" for n in counts]
        cells += [fmt(own_ms(by_lanes[n]) / own_ms(half[n]), 3) if n in by_lanes and n in half and own_ms(half[n]) > 0 else ""
                  for n in counts]
        worst = max((abs(rs[n]["rmse"] - rs[counts[0]]["rmse"]) for rs in (by_lanes, half) for n in counts
                     if n in rs and counts[0] in rs), default=float("nan"))
        lines.append(f'| {" | ".join(key)} | ' + " | ".join(cells) + f" | {fmt(worst)} |")
    return lines, counts


def lanes_section(rows, heading="##"):
    lines, counts = lanes_lines(rows)
    if not lines:
        return []
    names = [str(n) for n in counts]
    return [f"{heading} Ray lanes", "",
            "`ray_lanes` (rayLanes): that many invocations share each pixel's rays and add their sums in shared "
            "memory, the same rays in another order. Presets X at full resolution and X_half (as in the half-"
            "resolution section), the technique's own passes at each lane count, and the half-resolution speed-up "
            "(X over X_half) at each. The last column is the largest RMSE difference from the fewest lanes, at "
            "either resolution (the order of the sums only). Lanes pay where both times fall; a speed-up that "
            "grows while both times grow only says the full-resolution pass slowed more.", "",
            "| scene | size | technique | quantity | preset | " + " | ".join(f"full ms, {n}" for n in names) + " | "
            + " | ".join(f"half ms, {n}" for n in names) + " | " + " | ".join(f"speed-up, {n}" for n in names)
            + " | RMSE change |",
            "|" + "---|" * (6 + 3 * len(counts))] + lines + [""]


RESOLUTION_HEADER = ["| scene | size | preset | technique | quantity | full ms | half ms | "
                     "of which tiles, filters, refinement ms | speed-up | full RMSE | half RMSE | RMSE ratio | goal met |",
                     "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]


def geometry_tiles(row):
    """The row's geometryTiles setting (on unless set to 0)."""
    return row.get("settings", {}).get("geometry_tiles", "1") not in ("0", "false", "off")


def tiles_section(rows, heading="##"):
    """Reduced-resolution rows over every tile (geometry_tiles=0) against the same presets with geometry
    tiles (the default), both from the study's runs (bench --variant geometry_tiles=0: timed in turn)."""
    rows = [r for r in varying_only(rows, "geometry_tiles") if ray_lanes(r) == 1]
    tiled = {(os.path.basename(r["scene"]), r["width"], r["height"], r["technique"], r["quantity"], r["preset"]): r
             for r in rows if geometry_tiles(r)}
    lines = []
    for r in sorted(rows, key=lambda r: (os.path.basename(r["scene"]), r["technique"], r["quantity"], r["preset"])):
        key = (os.path.basename(r["scene"]), r["width"], r["height"], r["technique"], r["quantity"], r["preset"])
        if geometry_tiles(r) or key not in tiled:
            continue
        t = tiled[key]
        ratio = own_ms(t) / own_ms(r) if own_ms(r) > 0 else float("nan")
        lines.append(f'| {key[0]} | {r["width"]}x{r["height"]} | {r["technique"]} | {r["quantity"]} | {r["preset"]} | '
                     f'{fmt(own_ms(r))} | {fmt(own_ms(t))} | {fmt(ratio, 3)} | {fmt(r["rmse"])} | {fmt(t["rmse"])} |')
    if not lines:
        return []
    return [f"{heading} Geometry tiles", "",
            "At half and quarter resolution the integrator, the blur and the upsampling run only over the tiles of "
            "8x8 reduced pixels that hold geometry (`geometry_tiles`, geometryTiles, on by default; the listing "
            "pass is `<module>.tiles`). Each preset ran with geometry tiles and over every tile "
            "(`--variant geometry_tiles=0`) in one process, their frames timed in turn, so that both times share the "
            "machine's drift; the times are the technique's own passes. The RMSEs must agree exactly (the results are "
            "the same bit for bit, tests/gl/test_geometry_tiles.cpp).", "",
            "| scene | size | technique | quantity | preset | every tile ms | geometry tiles ms | tiles / every tile | RMSE, every tile "
            "| RMSE, geometry tiles |",
            "|---|---|---|---|---|---|---|---|---|---|"] + lines + [""]


def resolution_section(rows):
    lines = resolution_rows(rows)
    if not lines:
        return []
    return ["## Half resolution", "",
            "Presets `medium` and `high` (full resolution, no blur) against `medium_half` and `high_half` (the same "
            "rays and steps at half resolution, a geometry-aware blur of 3 taps each side at medium and 1 at high, "
            "joint bilateral upsampling, and the pixels the upsampling finds no similar neighbour for computed at full "
            "resolution: `refine_threshold`, pass `<module>.refine`), at the "
            "size of the tables above and, where a resolution study was run (`scripts/report.sh`: 512x512), at that "
            "size. Times are the technique's own passes (the G-buffer and its shadow maps, which they share, "
            "excluded), X and X_half timed in turn, frame by frame. The goal: at "
            "least 2x faster at less than 2x the RMSE. Half resolution saves the integrator's work per pixel, but the "
            "upsampling pays again, at full resolution, what any pass pays per G-buffer pixel (reading depth and "
            "normal, writing the results), so where the integrator does little more per pixel than that, half "
            "resolution cannot be 2x faster. `of which tiles, filters, refinement ms`: what X_half runs besides its "
            "integrator at half resolution (passes "
            "`<module>.tiles`, `.blur`, `.upsample`, `.refine`); since the half-resolution integrator costs more than "
            "nothing, a row can meet the goal only where `full ms` is more than twice that. On llvmpipe each of "
            "these passes has a fixed cost however little it does, which weighs most at small sizes "
            "(benchmarks/README.md).", ""] + RESOLUTION_HEADER + lines + [""]


MARCHES = ("view", "texture", "hiz")


def march_section(rows):
    """ao.raymarch with each screen-space march on the same samples: time against error."""
    table = defaultdict(dict)
    for r in varying_only(rows, "march"):
        if r["technique"] != "ao.raymarch" or r["quantity"] != "ao":
            continue
        settings = r.get("settings", {})
        key = (os.path.basename(r["scene"]), f'{r["width"]}x{r["height"]}', r["preset"], settings.get("rays", ""),
               settings.get("steps", ""))
        table[key][settings.get("march", "view")] = r
    lines = []
    for key, runs in sorted(table.items(), key=lambda kv: (kv[0][0], kv[0][1], int(kv[0][4] or 0))):
        if any(m not in runs for m in MARCHES):
            continue
        ms = {m: own_ms(runs[m]) for m in MARCHES}
        pyramid = sum(p["median_ms"] for p in runs["hiz"].get("passes", []) if p["pass"].endswith(".hiz"))
        speedup = ms["texture"] / ms["hiz"] if ms["hiz"] > 0 else float("nan")
        lines.append(f'| {key[0]} | {key[1]} | {key[2]} | {key[3]} | {key[4]} | {fmt(ms["view"])} | {fmt(ms["texture"])} | '
                     f'{fmt(ms["hiz"])} | {fmt(pyramid)} | {fmt(speedup, 3)} | '
                     + " | ".join(fmt(runs[m]["rmse"]) for m in MARCHES) + " |")
    if not lines:
        return []
    return ["## Screen-space marches", "",
            "`ao.raymarch` with its three depth-buffer marches on the same samples (`scripts/report.sh`): `view` (3D "
            "samples projected to their pixels), `texture` (the same samples interpolated in texture space) and `hiz` "
            "(the texture-space march with runs of samples skipped through a min/max view-z pyramid, built each frame: "
            "pass `ao.hiz`, included in its time). Presets `high` (16 steps) and `ultra` (32), and `high` with 128 "
            "steps, where the pyramid has runs to skip. Times are the technique's own passes; Hi-Z's RMSE must equal "
            "the texture-space march's (the same first hit, asserted exactly by the tests), view space's may differ by "
            "the rounding at pixel edges.", "",
            "| scene | size | preset | rays | steps | view ms | texture ms | Hi-Z ms | of which pyramid ms | Hi-Z speed-up "
            "over texture | view RMSE | texture RMSE | Hi-Z RMSE |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"] + lines + [""]


def row_key(r):
    return (os.path.basename(r["scene"]), r["technique"], r["preset"], r["quantity"], r["width"], r["height"])


def gpu_section(gpu_rows, cpu_rows, provenance=(), study_rows=()):
    """The same bench on a GPU: its half-resolution study, and its rows beside llvmpipe's (time and error)."""
    if not gpu_rows and not study_rows:
        return []
    renderers = sorted({r["renderer"] for r in list(gpu_rows) + list(study_rows)})
    clocks = sorted({r["clock"] for r in list(gpu_rows) + list(study_rows)})
    lines = ["## On a GPU", "",
             f"The same code and bench on {', '.join(renderers)} (headless EGL, device platform), clock "
             f"{', '.join(clocks)}: GPU timer queries, the median of the timed frames. These runs come from "
             "`benchmarks/gpu/run.sh` on a machine lent to a session and are kept under `benchmarks/gpu/`; "
             "`scripts/report.sh` does not rerun them. Their references are the same Embree integrators "
             "rendered afresh there.", ""]
    for text in provenance:
        lines += [text.strip(), ""]
    study = resolution_rows(gpu_rows)
    if study:
        lines += ["### Half resolution on the GPU", "",
                  "As in the half-resolution section above (the techniques' own passes), timed by the GPU. There the "
                  "blur and the upsampling cost a few hundredths of a millisecond, so the goal rests on the half-"
                  "resolution integrator and the refinement. At 512x512 the GPU runs every pixel at once (132 SMs x "
                  "2048 threads hold 270k, a frame has 262k pixels), so a pass takes about as long as its slowest "
                  "threads, at any resolution: only 1920x1080 (256 spp references) shows what half resolution saves, "
                  "and only where the full-resolution pass fills the GPU.", ""]
        lines += RESOLUTION_HEADER + study + [""]
    # The studies' runs (run.sh lanes, tiles) in tables of their own: their rows repeat the
    # resolution runs' keys, timed in other processes.
    lines += lanes_section(list(study_rows), "###")
    lines += tiles_section(list(study_rows), "###")
    cpu = {row_key(r): r for r in default_runs(cpu_rows)}
    matched = [(r, cpu[row_key(r)]) for r in default_runs(gpu_rows) if row_key(r) in cpu]
    if matched:
        worst = max((abs(g["rmse"] - c["rmse"]) for g, c in matched if math.isfinite(g["rmse"]) and math.isfinite(c["rmse"])),
                    default=float("nan"))
        lines += ["### GPU beside llvmpipe", "",
                  f"Rows measured on both, same scene, size and settings: {len(matched)}; the largest RMSE "
                  f"difference between the two is {fmt(worst)}. Rows that differ by more than a few times the "
                  "reference noise mean that one machine computes something else. Times: llvmpipe's wall clock "
                  "against the GPU's timer queries.", "",
                  "| scene | technique | preset | quantity | size | llvmpipe ms | GPU ms | llvmpipe RMSE | GPU RMSE |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for g, c in sorted(matched, key=lambda m: row_key(m[0])):
            lines.append(f'| {os.path.basename(g["scene"])} | {g["technique"]} | {g["preset"]} | {g["quantity"]} | '
                         f'{g["width"]}x{g["height"]} | {fmt(c["gpu_ms"])} | {fmt(g["gpu_ms"])} | {fmt(c["rmse"])} | '
                         f'{fmt(g["rmse"])} |')
        lines.append("")
    return lines


def shadow_section(rows):
    """Hard-shadow misclassification next to time and RMSE, for the shadow techniques."""
    srows = [r for r in rows if r["quantity"] == "shadow"]
    if not srows:
        return []
    lines = ["## Shadows", "",
             "Shadow masks against the ray-traced visibility of the same light at the G-buffer's samples, over the "
             "pixels the light reaches. `false shadow` and `false light` (hard masks only) are the fractions of those "
             "pixels classified shadowed while lit (acne) and lit while shadowed (peter-panning); the filtered masks "
             "are compared with the hard reference, except on cornell_sphere and cornell_rect, whose sphere and rect "
             "lights' reference is the fraction of the area light that arrives (1024 samples): there PCSS, and the "
             "filters run on shadow.cube's maps (its presets medium_pcf .. medium_msm; a rect light always gets one "
             "paraboloid map), meet the soft target, and the hard masks from the light's centre show what a hard "
             "lookup misses. Times are all the "
             "technique's passes: the G-buffer, the maps, for the moment filters the moments and their blur, and "
             "the mask. `umbra leak` is the largest mask value over the pixels whose reference is 0 (the whole light "
             "hidden) with every pixel within 3 pixels also 0, so that blur across the shadow's edge does not count "
             "(empty: no such pixel). `memory` is what the G-buffer and the shadow-map module hold after the timed "
             "frames (maps, moments, the mask, buffers), MiB; bench.json's `memory` splits it by pass. `shimmer` (directional lights): the mean absolute change "
             "of the mask at the same receivers when the cascades are fitted to the camera moved by k/8 of a texel "
             "(k = 1..8), against the unmoved fit; 0 means the snapped cascades do not shimmer.", "",
             "| scene | technique | preset | time ms | RMSE | false shadow | false light | umbra leak | memory MiB | shimmer |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    order = {"low": 0, "medium": 1, "high": 2, "ultra": 3}
    for r in sorted(srows, key=lambda r: (r["scene"], r["technique"], order.get(r["preset"], 9))):
        fs, fl, leak = r.get("false_shadow", ""), r.get("false_light", ""), r.get("umbra_leak", "")
        memory, shimmer = r.get("memory_bytes", ""), r.get("shimmer", "")
        lines.append(f'| {r["scene"]} | {r["technique"]} | {r["preset"]} | {fmt(r["gpu_ms"])} | {fmt(r["rmse"])} | '
                     f'{fmt(fs) if fs != "" else ""} | {fmt(fl) if fl != "" else ""} | {fmt(leak) if leak != "" else ""} | '
                     f'{fmt(memory / 2**20) if memory != "" else ""} | {fmt(shimmer) if shimmer != "" else ""} |')
    return lines + [""]


def voxel_section(voxel, out_dir):
    lines = []
    if voxel["voxelization"]:
        vrows = voxel["voxelization"]
        first = vrows[0]
        lines += ["## Voxelizer", "",
                  f'Voxelization of {first["triangles"]} triangles ({first["copies"]} copies of {first["scene"]}), '
                  f'{first["frames"]} timed frames each after a warm-up, clock `{first["clock"]}`. Times are the sum '
                  "of the passes' medians; memory is the grid, its mips, the scratch grid and the mesh buffers.", "",
                  "| mode | grid | targets | time ms | passes (median ms) | GPU MiB | open columns |",
                  "|---|---|---|---|---|---|---|"]
        for r in vrows:
            passes = ", ".join(f'{p["pass"]} {fmt(p["median_ms"])}' for p in r["passes"])
            lines.append(f'| {r["mode"]} | {r["resolution"]}² x {r["slices"]} | {r["targets"]} | {fmt(r["ms"])} | '
                         f'{passes} | {fmt(r["memory_bytes"] / 2 ** 20)} | {r["open_columns"]} |')
        lines.append("")
        plot_voxelization(vrows, os.path.join(out_dir, "results", "voxelization.png"))
        lines += ["![voxelization time](results/voxelization.png)", ""]
    if voxel["traversal"]:
        trows = voxel["traversal"]
        first = trows[0]
        lines += ["## Visibility in voxel space", "",
                  f'{first["count"]} segments per row on a {first["resolution"]}² x {first["slices"]} surface grid: '
                  '"random" joins two uniform points of the grid, "short" ones are at most 16 voxels long. '
                  f'(a) march takes {max(r["march_steps"] for r in trows)} jittered samples; (b) exact and (c) '
                  "hierarchical are exact (c skips empty octree cells and finds the same first voxel as b on every segment). "
                  "Fetches are occupancy tests (texel fetches) per segment.", "",
                  "| scene | segments | method | ms | M segments/s | fetches | hits | agrees with exact |",
                  "|---|---|---|---|---|---|---|---|"]
        for r in trows:
            lines.append(f'| {r["scene"]} | {r["segments"]} | {r["method"]} | {fmt(r["ms"])} | '
                         f'{fmt(r["segments_per_second"] / 1e6)} | {fmt(r["mean_fetches"])} | {fmt(r["hit_fraction"])} | '
                         f'{fmt(r["agrees_with_exact"], 6)} |')
        lines += ["", "Texel fetches (c) saves:", ""]
        groups = defaultdict(dict)
        for r in trows:
            groups[(r["scene"], r["segments"])][r["method"]] = r["mean_fetches"]
        for (scene, kind), f in sorted(groups.items()):
            if {"march", "exact", "hierarchical"} <= f.keys():
                lines.append(f'- {scene}, {kind} segments: {fmt(100 * (1 - f["hierarchical"] / f["exact"]), 3)} % of '
                             f'(b)\'s and {fmt(100 * (1 - f["hierarchical"] / f["march"]), 3)} % of (a)\'s.')
        lines.append("")
        plot_traversal(trows, os.path.join(out_dir, "results", "traversal.png"))
        lines += ["![traversal time and agreement](results/traversal.png)", ""]
    return lines


def shown(path):
    """A source as the report names it: relative to the repository when inside it, so that the
    report does not depend on where the checkout lies."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    full = os.path.abspath(path)
    return os.path.relpath(full, root) if os.path.commonpath([full, root]) == root else path


def write_report(rows, perf, out_dir, sources, voxel, study_rows=(), gpu_rows=(), march_rows=(), gpu_provenance=(),
                 lanes_rows=(), tiles_rows=(), gpu_study_rows=()):
    os.makedirs(os.path.join(out_dir, "results"), exist_ok=True)
    lines = [
        "# Results",
        "",
        "Generated by `obscura bench` and `benchmarks/plot_report.py` (run `scripts/report.sh`); do not edit by hand.",
        "",
        "Every row compares a technique's output with CPU ground truth from `obscura::reference` (Embree) on the",
        "same pixels: quantities with a reference integrator are evaluated at the technique's own G-buffer samples;",
        "`position` and `normal` are compared with primary-ray hits. `own ms`, the time the Pareto plots use, is",
        "the technique's own passes: AO, obscurance and GI leave out the G-buffer and the shadow maps that light",
        "it, the inputs every technique shares; shadow techniques leave out the G-buffer; `gbuffer` and `compose`",
        "are whole frames. `frame ms` is every pass of the frame. Times are the median over the timed frames",
        "after a warm-up (one frame on llvmpipe; half a second of frames on a GPU, whose clocks rise from idle). On llvmpipe (no GPU) they are glFinish-bracketed wall clock (`wall_clock_finish`),",
        "because GPU timer queries under-report there by about 20x; on a GPU they are timer queries",
        "(`gpu_timer_query`). Compare times only between rows with the same clock and renderer.",
        "",
        "`ref noise RMSE` is the reference's own noise floor, sqrt(MSE(A,B)/4) from two independent halves:",
        "differences in RMSE smaller than about twice it cannot be resolved. It is 0 for exact references",
        "(hard lights, geometry).",
        "",
    ]
    renderers = sorted({r["renderer"] for r in rows})
    clocks = sorted({r["clock"] for r in rows})
    lines += [f"Renderer: {', '.join(renderers)}; clock: {', '.join(clocks)}; sources: {', '.join(sources)}.", ""]

    if perf:
        lines += ["## Reference performance", "",
                  "| scene | quantity | size | spp | rays | seconds | M rays/s | threads |",
                  "|---|---|---|---|---|---|---|---|"]
        for p in perf:
            lines.append(f'| {os.path.basename(p["scene"])} | `{p["quantity"]}` | {p["width"]}x{p["height"]} | {p["spp"]} | '
                         f'{p["rays"]} | {fmt(p["seconds"])} | {fmt(p["rays_per_second"] / 1e6)} | {p["threads"]} |')
        lines.append("")

    by_scene = defaultdict(list)
    for r in rows:
        by_scene[r["scene"]].append(r)
    for scene in sorted(by_scene):
        srows = by_scene[scene]
        lines += [f"## {scene}", "",
                  "| technique | preset | quantity | size | own ms | frame ms | cpu ms | RMSE | relMSE | SSIM | max abs | NaN/Inf | ref noise RMSE | ref spp |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in sorted(srows, key=lambda r: (r["quantity"], r["technique"], r["preset"])):
            lines.append(f'| {r["technique"]} | {r["preset"]} | {r["quantity"]} | {r["width"]}x{r["height"]} | '
                         f'{fmt(own_ms(r))} | {fmt(r["gpu_ms"])} | {fmt(r["cpu_ms"])} | {fmt(r["rmse"])} | {fmt(r["relmse"])} | '
                         f'{fmt(r["ssim"])} | {fmt(r["max_abs"])} | {r["nan_count"]}/{r["inf_count"]} | '
                         f'{fmt(r["ref_noise_rmse"])} | {r["ref_spp"]} |')
        lines.append("")
        by_quantity = defaultdict(list)
        for r in srows:
            by_quantity[r["quantity"]].append(r)
        for quantity in sorted(by_quantity):
            name = f"{slug(scene)}_{slug(quantity)}.png"
            plot(scene, quantity, by_quantity[quantity], os.path.join(out_dir, "results", name))
            lines.append(f"![{scene}: {quantity}](results/{name})")
        lines.append("")

    lines += resolution_section(list(rows) + list(study_rows))
    lines += tiles_section(list(tiles_rows))
    lines += lanes_section(list(lanes_rows))
    lines += march_section(list(march_rows))
    lines += shadow_section(rows)
    lines += voxel_section(voxel, out_dir)
    lines += gpu_section(list(gpu_rows), list(rows) + list(study_rows), gpu_provenance, gpu_study_rows)
    with open(os.path.join(out_dir, "results.md"), "w") as f:
        f.write("\n".join(lines))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("inputs", nargs="+", help="bench.json files")
    parser.add_argument("--out", default="docs", help="directory for results.md and results/*.png")
    parser.add_argument("--resolution-study", action="append", default=[],
                        help="bench.json of presets medium, medium_half, high and high_half at another size (half-resolution table only)")
    parser.add_argument("--march-study", action="append", default=[],
                        help="bench.json of ao.raymarch with march=view, texture and hiz (--set, --variant; screen-space march table only)")
    parser.add_argument("--lanes-study", action="append", default=[],
                        help="bench.json of presets X and X_half at several ray_lanes (--set, --variant; ray-lanes table only)")
    parser.add_argument("--tiles-study", action="append", default=[],
                        help="bench.json of reduced-resolution presets with --variant geometry_tiles=0 (geometry-tiles table only)")
    parser.add_argument("--gpu", action="append", default=[],
                        help="bench.json from a GPU machine (benchmarks/gpu/run.sh): its own section, with the "
                             "provenance.md beside it (when, at which commit, what ran) quoted there")
    parser.add_argument("--gpu-study", action="append", default=[],
                        help="bench.json of a lanes or tiles study from a GPU machine (run.sh lanes, tiles): "
                             "the GPU section's ray-lanes and geometry-tiles tables only")
    args = parser.parse_args()
    rows, perf, voxel = load(args.inputs)
    if not rows:
        sys.exit("plot_report.py: no rows in " + ", ".join(args.inputs))
    study_rows = load(args.resolution_study)[0] if args.resolution_study else []
    sources = [shown(p) for p in args.inputs] + [f"{shown(p)} (resolution study)" for p in args.resolution_study]
    march_rows = load(args.march_study)[0] if args.march_study else []
    sources += [f"{shown(p)} (march study)" for p in args.march_study]
    lanes_rows = load(args.lanes_study)[0] if args.lanes_study else []
    sources += [f"{shown(p)} (lanes study)" for p in args.lanes_study]
    tiles_rows = load(args.tiles_study)[0] if args.tiles_study else []
    sources += [f"{shown(p)} (tiles study)" for p in args.tiles_study]
    gpu_rows = load(args.gpu)[0] if args.gpu else []
    sources += [f"{shown(p)} (GPU)" for p in args.gpu]
    gpu_study_rows = load(args.gpu_study)[0] if args.gpu_study else []
    sources += [f"{shown(p)} (GPU study)" for p in args.gpu_study]
    provenance = []
    for directory in sorted({os.path.dirname(os.path.abspath(p)) for p in args.gpu + args.gpu_study}):
        path = os.path.join(directory, "provenance.md")
        if os.path.isfile(path):
            with open(path) as f:
                provenance.append(f.read())
    write_report(rows, perf, args.out, sources, voxel, study_rows, gpu_rows, march_rows, provenance, lanes_rows, tiles_rows,
                 gpu_study_rows)
    print(f"wrote {os.path.join(args.out, 'results.md')} ({len(rows)} rows)")


if __name__ == "__main__":
    main()
