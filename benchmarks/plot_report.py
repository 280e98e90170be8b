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

from report_tables import (PRESET_ORDER, RESOLUTION_HEADER, default_runs, falloff_section, fmt, media_filters_section, media_section, ssdo_options_section, ssdo_overhead_section,  # noqa: E402
                           lanes_section, march_section, own_ms, quarter_section, refine_section, resolution_rows,
                           resolution_section, thickness_section, tiles_section)


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
    points = [(max(own_ms(r), 1e-6), max(r["rmse"], 1e-12)) for r in rows]
    for r, (t, e) in zip(rows, points):
        ax.scatter([t], [e], s=30)
        ax.annotate(f'{r["technique"]} {r["preset"]}', (t, e), fontsize=7, xytext=(4, 3), textcoords="offset points")
    # Log time too: the presets' times span two orders of magnitude, and a linear axis piles
    # the cheap ones into one corner. (Before the noise label, which sits at the axis's left end.)
    ax.set_xscale("log")
    ax.set_yscale("log")
    front = pareto(points)
    if len(front) > 1:
        ax.plot([points[i][0] for i in front], [points[i][1] for i in front], "k--", lw=0.8, label="Pareto front")
        ax.legend(fontsize=7)
    noise = max((r["ref_noise_rmse"] for r in rows), default=0.0)
    if noise > 0:
        ax.axhline(noise, color="gray", lw=0.8, ls=":")
        ax.text(ax.get_xlim()[0], noise, " reference noise", fontsize=7, color="gray", va="bottom")
    clock = rows[0]["clock"]
    ax.set_xlabel(f"time of the technique's own passes, ms ({clock})")
    ax.set_ylabel(f"RMSE of {quantity}")
    ax.set_title(f"{scene}: {quantity}", fontsize=9)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    # The labels of the rightmost points reach past the axes: a tight bounding box keeps them,
    # where tight_layout gives up and cuts the axis label off.
    fig.savefig(path, bbox_inches="tight")
    plt.close(fig)


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


def row_key(r):
    return (os.path.basename(r["scene"]), r["technique"], r["preset"], r["quantity"], r["width"], r["height"])


def gpu_section(gpu_rows, cpu_rows, provenance=(), study_rows=()):
    """The same bench on a GPU: its half- and quarter-resolution studies, and its rows beside llvmpipe's (time and
    error)."""
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
    lines += quarter_section(list(gpu_rows), "###")
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
    for r in sorted(srows, key=lambda r: (r["scene"], r["technique"], PRESET_ORDER.get(r["preset"], 9))):
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
                 lanes_rows=(), tiles_rows=(), gpu_study_rows=(), thickness_rows=(), falloff_rows=(),
                 refine_rows=(), ssdo_rows=(), ssdo_option_rows=(), media_rows=(),
                 media_filter_rows=()):
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
    lines += quarter_section(list(study_rows))
    lines += refine_section(list(refine_rows))
    lines += tiles_section(list(tiles_rows))
    lines += lanes_section(list(lanes_rows))
    lines += march_section(list(march_rows))
    lines += thickness_section(list(thickness_rows))
    lines += falloff_section(list(falloff_rows))
    lines += ssdo_overhead_section(list(ssdo_rows))
    lines += ssdo_options_section(list(ssdo_option_rows))
    lines += media_section(list(media_rows))
    lines += media_filters_section(list(media_filter_rows))
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
                        help="bench.json of presets medium, medium_half, high and high_half at another size, and of their "
                             "--variant resolution=quarter runs (the half- and quarter-resolution tables, and "
                             "llvmpipe's side of the GPU comparison)")
    parser.add_argument("--march-study", action="append", default=[],
                        help="bench.json of ao.raymarch with march=view, texture and hiz (--set, --variant; screen-space march table only)")
    parser.add_argument("--thickness-study", action="append", default=[],
                        help="bench.json of screen-space AO with --variant thickness_mode=depth_peeling, peeling_or_constant "
                             "and thickness (thickness table only)")
    parser.add_argument("--falloff-study", action="append", default=[],
                        help="bench.json of the obscurance techniques with --variant falloff=none, quadratic and smooth "
                             "(falloff table only)")
    parser.add_argument("--refine-study", action="append", default=[],
                        help="bench.json of presets medium, medium_half, high and high_half with --variant "
                             "refine_threshold=0 (refinement table only)")
    parser.add_argument("--ssdo-overhead-study", action="append", default=[],
                        help="bench.json of ao.raymarch and ssdo (with --variant bounce=1) at the same rays and steps "
                             "(SSDO overhead table only)")
    parser.add_argument("--ssdo-options-study", action="append", default=[],
                        help="bench.json of ssdo with --variant extra_views=2 and thickness_mode=depth_peeling "
                             "(SSDO options table only)")
    parser.add_argument("--media-filters-study", action="append", default=[],
                        help="bench.json of media.raymarch and media.bounded with --variant blur_radius=2, "
                             "resolution=half and resolution=half,blur_radius=1 (media blur and half-resolution table only)")
    parser.add_argument("--media-study", action="append", default=[],
                        help="bench.json of the media techniques' presets at one size (one file per size; the "
                             "media time-against-steps table only)")
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
    sources = [shown(p) for p in args.inputs]

    def study(paths, label):
        """The rows of a study's bench.json files, each file listed among the sources with its label."""
        sources.extend(f"{shown(p)} ({label})" for p in paths)
        return load(paths)[0] if paths else []

    study_rows = study(args.resolution_study, "resolution study")
    march_rows = study(args.march_study, "march study")
    thickness_rows = study(args.thickness_study, "thickness study")
    falloff_rows = study(args.falloff_study, "falloff study")
    refine_rows = study(args.refine_study, "refinement study")
    lanes_rows = study(args.lanes_study, "lanes study")
    tiles_rows = study(args.tiles_study, "tiles study")
    ssdo_rows = study(args.ssdo_overhead_study, "SSDO overhead study")
    ssdo_option_rows = study(args.ssdo_options_study, "SSDO options study")
    media_rows = study(args.media_study, "media study")
    media_filter_rows = study(args.media_filters_study, "media filters study")
    gpu_rows = study(args.gpu, "GPU")
    gpu_study_rows = study(args.gpu_study, "GPU study")
    provenance = []
    for directory in sorted({os.path.dirname(os.path.abspath(p)) for p in args.gpu + args.gpu_study}):
        path = os.path.join(directory, "provenance.md")
        if os.path.isfile(path):
            with open(path) as f:
                provenance.append(f.read())
    write_report(rows, perf, args.out, sources, voxel, study_rows, gpu_rows, march_rows, provenance, lanes_rows, tiles_rows,
                 gpu_study_rows, thickness_rows, falloff_rows, refine_rows, ssdo_rows, ssdo_option_rows, media_rows,
                 media_filter_rows)
    print(f"wrote {os.path.join(args.out, 'results.md')} ({len(rows)} rows)")


if __name__ == "__main__":
    main()
