"""The report's tables of timed studies (half and quarter resolution, refinement, geometry tiles, ray lanes, the
screen-space marches, thickness and obscurance's falloffs) and the number formatting and
timing rules they share with plot_report.py, which turns `obscura bench` output into
docs/results.md.
"""
import math
import os
from collections import defaultdict


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


PRESET_ORDER = {"low": 0, "medium": 1, "high": 2, "ultra": 3}  # the integrators' presets, cheapest first
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
    for key, p in sorted(pairs.items(), key=by_size_and_preset):
        if len(p) != 2:
            continue
        full, half = p[key[2]], p[key[2] + "_half"]
        full_ms, half_ms = own_ms(full), own_ms(half)
        besides_ms = sum(q["median_ms"] for q in half["passes"] if q["pass"].endswith(REDUCED_RESOLUTION_PASSES))
        speedup = full_ms / half_ms if half_ms > 0 else float("nan")
        ratio = half["rmse"] / full["rmse"] if full["rmse"] > 0 else float("nan")
        lines.append(f'| {key[0]} | {key[1]} | {key[2]} | {key[3]} | {key[4]} | {fmt(full_ms)} | {fmt(half_ms)} | '
                     f'{fmt(besides_ms)} | {refined_cell(half)} | {fmt(speedup, 3)} | {fmt(full["rmse"])} | {fmt(half["rmse"])} | {fmt(ratio, 3)} | '
                     f'{"yes" if goal_met(full, half) else "**no**"} |')
    return lines


def ray_lanes(row):
    """The row's rayLanes setting (invocations per pixel's rays; 1 unless set)."""
    return int(row.get("settings", {}).get("ray_lanes", 1))


def default_runs(rows):
    """The rows of no --variant, at the default of one ray lane and with geometry tiles: the other tables
    compare those; the lanes and tiles studies have their own."""
    return [r for r in rows if not r.get("variant") and ray_lanes(r) == 1 and geometry_tiles(r)]


def variant_keys(row):
    """The settings a row's --variant sets (none for a preset's own run)."""
    return {kv.split("=")[0] for kv in row.get("variant", "").split(",") if kv}


def varying_only(rows, *keys):
    """The rows whose --variant (if any) sets only `keys`: a study of them compares those, and not a
    variant that also changes something else."""
    return [r for r in rows if variant_keys(r) <= set(keys)]


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
                     "of which tiles, filters, refinement ms | refined pixels | speed-up | full RMSE | half RMSE | "
                     "RMSE ratio | goal met |",
                     "|" + "---|" * 14]


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
            "(benchmarks/README.md). `refined pixels`: how many G-buffer pixels the refinement computed at full "
            "resolution, of those with geometry (n/a: a bench file from before they were counted); a small or thin "
            "object is mostly edges, and there the refinement redoes much of the full-resolution work.", ""] + RESOLUTION_HEADER + lines + [""]


RESOLUTIONS = ("full", "half", "quarter")  # the integrators' `resolution` (shadow techniques' is a map size)


def resolution_of(row):
    """The row's integrator resolution: its --variant's, else its preset's (full unless set); None for a
    `resolution` that is not one (a shadow map's size in texels)."""
    value = row.get("settings", {}).get("resolution", "full")
    return value if value in RESOLUTIONS else None


def by_size_and_preset(item):
    """Sort key of a table's (scene, size, preset, ...) keyed item: the presets cheapest first."""
    key = item[0]
    return key[0], key[1], PRESET_ORDER.get(key[2], 9), key[3:]


def preset_pair_runs(rows, varying, run_of):
    """The runs of each preset pair X / X_half whose --variant sets only `varying`, per (scene, size, X,
    technique, quantity, renderer: another renderer's runs are another group), each under
    run_of(row, is_half) (None: left out); sorted with the presets cheapest first."""
    runs = defaultdict(dict)
    for r in varying_only(rows, varying):
        if ray_lanes(r) != 1 or not geometry_tiles(r):
            continue
        half = r["preset"].endswith("_half")
        base = r["preset"][:-len("_half")] if half else r["preset"]
        run = run_of(r, half)
        if base in HALF_PAIRS and run is not None:
            key = (os.path.basename(r["scene"]), f'{r["width"]}x{r["height"]}', base, r["technique"], r["quantity"],
                   r.get("renderer", ""))
            runs[key][run] = r
    return sorted(runs.items(), key=by_size_and_preset)


def goal_met(full, reduced):
    """The half-resolution goal: at least 2x faster at less than 2x the RMSE."""
    return own_ms(reduced) > 0 and own_ms(full) / own_ms(reduced) >= 2.0 and reduced["rmse"] < 2.0 * full["rmse"]


def quarter_lines(rows):
    """Table lines: per scene, size, preset pair, technique and quantity, X at full resolution, X_half at
    half and at quarter resolution (--variant resolution=quarter: X_half's blur, in quarter-resolution
    pixels), and X at quarter resolution without a blur, all timed in turn by one process."""
    lines = []
    wanted = ((False, "full"), (True, "half"), (True, "quarter"), (False, "quarter"))
    for key, by_run in preset_pair_runs(rows, "resolution",
                                        lambda r, half: None if resolution_of(r) is None else (half, resolution_of(r))):
        if any(w not in by_run for w in wanted):
            continue
        full, half, quarter, bare = (by_run[w] for w in wanted)
        ms = [own_ms(full), own_ms(half), own_ms(quarter)]
        besides_ms = sum(q["median_ms"] for q in quarter["passes"] if q["pass"].endswith(REDUCED_RESOLUTION_PASSES))
        speedups = [fmt(ms[0] / t, 3) if t > 0 else "n/a" for t in ms[1:]]
        ratio = quarter["rmse"] / full["rmse"] if full["rmse"] > 0 else float("nan")
        lines.append(f"| {' | '.join(key[:5])} | " + " | ".join(fmt(t) for t in ms) + f" | {fmt(besides_ms)} | "
                     + " | ".join(speedups) + " | " + " | ".join(fmt(r["rmse"]) for r in (full, half, quarter))
                     + f" | {fmt(ratio, 3)} | {fmt(own_ms(bare))} | {fmt(bare['rmse'])} |")
    return lines


def refined_cell(r):
    """The pixels a run refined, of its geometry pixels (bench.json's refined_pixels, refine_asked and
    geometry_pixels; n/a in bench files from before they were written)."""
    if "refined_pixels" not in r or not r.get("geometry_pixels"):
        return "n/a"
    refined, asked, geometry = r["refined_pixels"], r["refine_asked"], r["geometry_pixels"]
    if refined != asked:
        return f"none: {asked} asked, over the list"
    return f"{refined} of {geometry} ({100.0 * refined / geometry:.0f}%)"


def refine_lines(rows):
    """Table lines: X at full resolution, X_half with its refinement (refine_threshold's default) and
    without (--variant refine_threshold=0), timed in turn: what the refinement costs and buys."""
    lines = []
    wanted = ((False, False), (True, False), (True, True))
    for key, by_run in preset_pair_runs(rows, "refine_threshold",
                                        lambda r, half: (half, "refine_threshold" in variant_keys(r))):
        if any(w not in by_run for w in wanted):
            continue
        full, half, bare = (by_run[w] for w in wanted)
        refine_ms = sum(q["median_ms"] for q in half["passes"] if q["pass"].endswith(".refine"))
        speedups = [fmt(own_ms(full) / own_ms(r), 3) if own_ms(r) > 0 else "n/a" for r in (half, bare)]
        lines.append(f"| {' | '.join(key[:5])} | {fmt(own_ms(full))} | {fmt(own_ms(half))} | {fmt(refine_ms)} | "
                     f"{refined_cell(half)} | {fmt(own_ms(bare))} | " + " | ".join(speedups) + " | "
                     + " | ".join(fmt(r["rmse"]) for r in (full, half, bare)) + " | "
                     + " | ".join("yes" if goal_met(full, r) else "**no**" for r in (half, bare)) + " |")
    return lines


def refine_section(rows, heading="##"):
    lines = refine_lines(rows)
    if not lines:
        return []
    return [f"{heading} Refinement at half resolution", "",
            "Presets X (full resolution) and X_half with the refinement (`refine_threshold` 0.25, the default: "
            "pass `<module>.refine` computes at full resolution the pixels the upsampling finds no similar "
            "reduced neighbour for) and without it (`--variant refine_threshold=0`: the neighbour nearest in "
            "depth fills in), timed in turn (`scripts/report.sh`), at the size of the scene tables, where "
            "the half-resolution section's misses are, on the scenes with the most edge pixels. Times are the "
            "technique's own passes; the goal is the half-resolution section's. `refined pixels` is how many "
            "G-buffer pixels the refinement computed (`lastRefinement()`), of the pixels with geometry: on a "
            "small or thin object most pixels are edges, and the refinement then recomputes a large share of "
            "the full-resolution work.", "",
            "| scene | size | preset | technique | quantity | full ms | half ms | of which refinement ms | "
            "refined pixels | half ms, no refinement | speed-up | speed-up, no refinement | full RMSE | half RMSE | "
            "half RMSE, no refinement | goal met | goal met, no refinement |",
            "|" + "---|" * 17] + lines + [""]


QUARTER_HEADER = ["| scene | size | preset | technique | quantity | full ms | half ms | quarter ms | "
                  "of which tiles, filters, refinement ms (quarter) | half speed-up | quarter speed-up | full RMSE | "
                  "half RMSE | quarter RMSE | quarter RMSE ratio | no blur: quarter ms | quarter RMSE |",
                  "|" + "---|" * 17]


def quarter_section(rows, heading="##"):
    lines = quarter_lines(rows)
    if not lines:
        return []
    return [f"{heading} Quarter resolution", "",
            "The half-resolution study's presets once more at quarter resolution (`--variant resolution=quarter` "
            "in `scripts/report.sh` and `benchmarks/gpu/run.sh`), in the same process and timed in turn with "
            "them: X_half's rays, steps and blur at a quarter of the width and height (the blur's taps are "
            "reduced pixels, so it reaches twice as far in the image as at half resolution), and X's, which has "
            "no blur. The joint bilateral upsampling and the refinement of the pixels it finds no similar reduced "
            "neighbour for work as at half resolution. The speed-ups are X's time over X_half's and over the "
            "quarter-resolution run's; the RMSE ratio is the quarter-resolution run's over X's. The issue sets "
            "its goal (2x faster at less than 2x the error) for half resolution only. The last two columns, "
            "quarter resolution without the blur, show what the blur costs and buys.",
            ""] + QUARTER_HEADER + lines + [""]


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


# The thickness study's runs: (thickness_mode, whether the variant sets the thickness: a tenth
# of the radius in scripts/report.sh, else the presets' radius). The first two are required.
THICKNESS_RUNS = (("constant", False), ("depth_peeling", False), ("peeling_or_constant", False),
                  ("constant", True), ("peeling_or_constant", True))


def gbuffer_ms(row):
    return sum(p["median_ms"] for p in row.get("passes", []) if p["pass"].startswith("gbuffer."))


def thickness_run(row):
    return row.get("settings", {}).get("thickness_mode", "constant"), "thickness" in variant_keys(row)


def thickness_section(rows):
    """Screen-space AO with constant thickness against depth peeling and the deeper of both, time and
    error."""
    table = defaultdict(dict)
    for r in varying_only(rows, "thickness_mode", "thickness"):
        if r["quantity"] != "ao":
            continue
        key = (os.path.basename(r["scene"]), f'{r["width"]}x{r["height"]}', r["technique"], r["preset"])
        table[key][thickness_run(r)] = r
    lines = []
    for key, runs in sorted(table.items(), key=lambda kv: (kv[0][0], kv[0][1], kv[0][2], PRESET_ORDER.get(kv[0][3], 9))):
        if any(run not in runs for run in THICKNESS_RUNS[:2]):
            continue
        c, p = runs[THICKNESS_RUNS[0]], runs[THICKNESS_RUNS[1]]
        either = runs.get(THICKNESS_RUNS[2])
        rmses = [fmt(runs[run]["rmse"]) if run in runs else "" for run in THICKNESS_RUNS]
        lines.append(f"| {' | '.join(key)} | {fmt(own_ms(c))} | {fmt(own_ms(p))} | "
                     f"{fmt(own_ms(either)) if either else ''} | {fmt(gbuffer_ms(c))} | {fmt(gbuffer_ms(p))} | "
                     f"{' | '.join(rmses)} |")
    if not lines:
        return []
    return ["## Screen-space thickness", "",
            "`ao.raymarch` and `ao.points` with a constant thickness behind each depth sample (`thickness` 0: the "
            "radius, the presets' setting) against depth peeling (`thickness_mode=depth_peeling`: a sample is hidden "
            "only between the first and the second depth layer, which the G-buffer renders in a second geometry "
            "pass) and the deeper of both (`thickness_mode=peeling_or_constant`: hidden within the thickness or in "
            "front of the second layer), with the radius and with a tenth of it (`r/10`), the same samples timed "
            "in turn (`scripts/report.sh`, one bench run per scene). `own ms` is the technique's passes, "
            "`G-buffer ms` the G-buffer's (one layer, or two). A constant thickness as large as the radius counts "
            "everything behind a surface as solid, so a ray that passes behind an object is blocked: the error of "
            "the ray march levels off or rises as rays and steps grow. Peeling lets such rays through, but only two layers "
            "are known: behind the second, everything counts as open, and a march's samples or the points step "
            "over anything thinner than their spacing. Where parts are thin next to the radius and stacked "
            "(2CylinderEngine, whose second layer lies a median 0.13 radius behind the first: benchmarks/layer_gaps.sh) "
            "peeling misses occluders the reference finds. The thickness is measured along each pixel's normal, "
            "so on a face seen at a grazing angle it reaches thickness / cos far along the view ray: with the "
            "radius, the deeper of both is mostly the constant thickness; with a tenth of it, it keeps "
            "peeling's depth on thick objects and a slab of a tenth of the radius (longer at grazing angles) where "
            "the second layer is nearer.", "",
            "| scene | size | technique | preset | constant own ms | peeling own ms | deeper-of-both own ms | "
            "one-layer G-buffer ms | two-layer G-buffer ms | RMSE: constant | peeling | deeper of both | "
            "constant r/10 | deeper of both r/10 |",
            "|" + "---|" * 14] + lines + [""]


FALLOFFS = ("none", "linear", "quadratic", "smooth")  # rho; the obscurance techniques' default is linear


def falloff_section(rows):
    """Obscurance with each falloff rho, each against the reference with the same rho: time and error."""
    table = defaultdict(dict)
    for r in varying_only(rows, "falloff"):
        # With falloff=none the quantity is AO_r, and the bench measures it as "ao".
        if not r["technique"].startswith("obscurance.") or r["quantity"] not in ("obscurance", "ao"):
            continue
        key = (os.path.basename(r["scene"]), f'{r["width"]}x{r["height"]}', r["technique"], r["preset"])
        table[key][r.get("settings", {}).get("falloff", "linear")] = r
    lines = []
    for key, runs in sorted(table.items(), key=lambda kv: (kv[0][0], kv[0][1], kv[0][2], PRESET_ORDER.get(kv[0][3], 9))):
        if any(f not in runs for f in FALLOFFS):
            continue
        lines.append(f"| {' | '.join(key)} | " + " | ".join(fmt(own_ms(runs[f])) for f in FALLOFFS) + " | " +
                     " | ".join(fmt(runs[f]["rmse"]) for f in FALLOFFS) + " |")
    if not lines:
        return []
    return ["## Obscurance falloffs", "",
            "The obscurance techniques with each distance weighting rho(d / d_max) (`falloff`, d_max = the radius): "
            "`none` (rho = 1 for any hit: AO_r), `linear` (d / d_max, the techniques' default, as in the scene tables "
            "above), `quadratic` ((d / d_max)^2) and `smooth` (smoothstep), each measured against the reference with "
            "the same rho, the same samples timed in turn (`scripts/report.sh`, `--variant falloff=...`). The "
            "falloff changes only how much a hit counts, not which rays are traced.", "",
            "| scene | size | technique | preset | own ms: none | linear | quadratic | smooth | "
            "RMSE: none | linear | quadratic | smooth |",
            "|" + "---|" * 12] + lines + [""]


SSDO_LIGHT_PASSES = ("ssdo.lights", "ssdo.vpls", "ssdo.views")  # what the paper's SSAO comparison leaves out


def ssdo_integrator_ms(row):
    """SSDO's integrator passes (direct, bounce and their filters), without the lights' passes."""
    return sum(p["median_ms"] for p in row.get("passes", [])
               if p["pass"].startswith("ssdo") and p["pass"] not in SSDO_LIGHT_PASSES)


def ssdo_lights_ms(row):
    return sum(p["median_ms"] for p in row.get("passes", []) if p["pass"] in SSDO_LIGHT_PASSES)


def ssdo_overhead_section(rows):
    """The paper's Table 1: ao.raymarch against ssdo and ssdo with its bounce, the same rays and steps."""
    table = defaultdict(dict)
    for r in rows:
        kind = {"ao.raymarch": "ao", "ssdo": "ssdo"}.get(r["technique"])
        if kind is None or r["quantity"] not in ("ao", "direct"):
            continue
        if kind == "ssdo" and r.get("variant") == "bounce=1":
            kind = "bounce"
        scene = os.path.basename(r["scene"]).split("+")[0]
        settings = r.get("settings", {})
        key = (scene, f'{r["width"]}x{r["height"]}', int(settings.get("rays", 0)), settings.get("steps", ""))
        table[key][kind] = r
    lines = []
    for key, runs in sorted(table.items(), key=lambda kv: (kv[0][0], int(kv[0][1].split("x")[0]), kv[0][2])):
        if any(k not in runs for k in ("ao", "ssdo", "bounce")):
            continue
        ao = own_ms(runs["ao"])
        cells = [fmt(ao)]
        for k in ("ssdo", "bounce"):
            ms = ssdo_integrator_ms(runs[k])
            cells += [fmt(ms), f"{100.0 * (ms - ao) / ao:+.1f} %" if ao > 0 else ""]
        cells.append(fmt(ssdo_lights_ms(runs["ssdo"])))
        lines.append(f"| {key[0]} | {key[1]} | {key[2]} | {key[3]} | " + " | ".join(cells) + " |")
    if not lines:
        return []
    return ["## SSDO overhead over AO", "",
            "As the paper's Table 1: `ao.raymarch` against `ssdo` (direct light from the environment) and `ssdo` with "
            "`bounce=1`, the same rays (N) and steps at full resolution (`scripts/report.sh`; the two ssdo runs timed "
            "in turn, `--variant bounce=1`, the AO run in its own process just before them). The SSDO columns are its "
            "integrator passes (`ssdo.direct`, `ssdo.bounce`), which the paper compares with SSAO; the lights' pass "
            "(`ssdo.lights`: the Cornell box's point light, its cube shadow map looked up and corrected by a 16-sample "
            "march) is the last column. Our targets: at most +10 % for SSDO and +30 % with the bounce. SSDO's direct "
            "pass reads the environment's cube once per open direction; the bounce is a second pass that marches the "
            "same directions again and reads each occluder's pixel.",
            "",
            "| scene | size | N | steps | AO ms | SSDO ms | over AO | SSDO + bounce ms | over AO | lights pass ms |",
            "|---|---|---|---|---|---|---|---|---|---|"] + lines + [""]


SSDO_OPTIONS = ("", "extra_views=2", "thickness_mode=depth_peeling")


def ssdo_options_section(rows):
    """SSDO with each option on and off: the same preset, timed in turn (--variant)."""
    table = defaultdict(dict)
    for r in rows:
        if r["technique"] != "ssdo" or r["quantity"] not in ("direct", "direct_r"):
            continue
        key = (os.path.basename(r["scene"]), f'{r["width"]}x{r["height"]}', r["preset"])
        table[key][(r.get("variant", ""), r["quantity"])] = r
    lines = []
    for key, runs in sorted(table.items()):
        if any((v, "direct_r") not in runs for v in SSDO_OPTIONS):
            continue
        cells = []
        for v in SSDO_OPTIONS:
            cells += [fmt(own_ms(runs[(v, "direct_r")])), fmt(runs[(v, "direct_r")]["rmse"]), fmt(runs[(v, "direct")]["rmse"])]
        lines.append(f"| {' | '.join(key)} | " + " | ".join(cells) + " |")
    if not lines:
        return []
    return ["## SSDO options", "",
            "`ssdo` with two extra views (`extra_views=2`: eyes moved right and left by a quarter of the scene's radius, "
            "at half resolution) and with depth peeling (`thickness_mode=depth_peeling`), against the preset alone, "
            "timed in turn (`scripts/report.sh`, `--variant`). `direct_r` is the method's own error (occluders of the "
            "environment within r_max), `direct` the error against full visibility.", "",
            "| scene | size | preset | own ms | RMSE direct_r | RMSE direct | own ms: 2 views | direct_r | direct | "
            "own ms: peeling | direct_r | direct |",
            "|" + "---|" * 12] + lines + [""]


MEDIA_METHODS = ("media.raymarch", "media.bounded", "media.froxel", "media.analytic")


def media_steps(row):
    """What a media row's preset spends: its steps, or "table" for the analytic table."""
    settings = row.get("settings", {})
    if row["technique"] == "media.analytic" and settings.get("integral") == "table":
        return "table"
    return str(settings.get("steps", ""))


def media_section(rows):
    """The volumetric-lighting thesis's table: each method's own ms against its steps at two or more
    sizes, and the analytic form's speed-up over 200-step marching."""
    table = defaultdict(dict)
    sizes = set()
    for r in rows:
        if r["technique"] not in MEDIA_METHODS or r["quantity"] != "scattering":
            continue
        size = f'{r["width"]}x{r["height"]}'
        sizes.add(size)
        table[(os.path.basename(r["scene"]), r["technique"], media_steps(r))][size] = own_ms(r)
    if not table:
        return []
    sizes = sorted(sizes, key=lambda s: int(s.split("x")[0]))

    def order(key):
        scene, technique, steps = key
        return (scene, MEDIA_METHODS.index(technique), -1 if steps == "table" else int(steps or 0))

    lines = []
    for key in sorted(table, key=order):
        lines.append(f"| {key[0]} | {key[1]} | {key[2]} | " + " | ".join(fmt(table[key].get(s)) for s in sizes) + " |")
    ratios = []
    for scene in sorted({k[0] for k in table}):
        march = table.get((scene, "media.raymarch", "200"), {})
        for steps in ("table", "16", "64"):
            analytic = table.get((scene, "media.analytic", steps), {})
            cells = [f"{march[s] / analytic[s]:.1f}x" if march.get(s) and analytic.get(s) else "" for s in sizes]
            if any(cells):
                ratios.append(f"| {scene} | analytic {steps} | " + " | ".join(cells) + " |")
        # Bounded marching at the same steps (the same integrand within the lit span only).
        for steps in ("50", "200"):
            bounded = table.get((scene, "media.bounded", steps), {})
            marched = table.get((scene, "media.raymarch", steps), {})
            cells = [f"{marched[s] / bounded[s]:.1f}x" if marched.get(s) and bounded.get(s) else "" for s in sizes]
            if any(cells):
                ratios.append(f"| {scene} | bounded {steps} (vs marching {steps}) | " + " | ".join(cells) + " |")
    out = ["## Participating media: time against steps", "",
           "As the volumetric-lighting thesis's table (ms against steps at two resolutions): each media method's own "
           "passes (`own ms`: the froxel method's inject, integrate and resolve together) at its presets, steps "
           "20, 50, 100 and 200 for marching and froxels (slices), the analytic form's table and its quadrature "
           "with 16, 64 and 256 intervals (`scripts/report.sh`, one process per size; their errors are in the "
           "scene tables above at 128x128). Bounded marching takes the same steps within the spot lights' shadow volumes; "
           "with a point light (`cornell_fog`) it is the plain march. Our target: the analytic form at least 10x faster than 200-step "
           "marching, at most 1 % relative error where it applies (no shadows: `scattering_unshadowed`).",
           "",
           "| scene | technique | steps | " + " | ".join(f"{s} ms" for s in sizes) + " |",
           "|---|---|---|" + "---|" * len(sizes)] + lines + [""]
    if ratios:
        out += ["Speed-up of the analytic form over 200-step marching, and of bounded over plain marching:", "",
                "| scene | method | " + " | ".join(sizes) + " |", "|---|---|" + "---|" * len(sizes)] + ratios + [""]
    return out


MEDIA_FILTER_VARIANTS = ("", "blur_radius=2", "resolution=half", "resolution=half,blur_radius=1")


def media_filters_section(rows):
    """Marching (plain and bounded) as run, blurred, at half resolution, and both: the same preset,
    timed in turn (--variant)."""
    table = defaultdict(dict)
    for r in rows:
        if r["technique"] not in ("media.raymarch", "media.bounded") or r["quantity"] != "scattering":
            continue
        key = (os.path.basename(r["scene"]), r["technique"], r["preset"])
        table[key][r.get("variant", "")] = r
    lines = []
    for key in sorted(table, key=lambda k: (k[0], k[1], PRESET_ORDER.get(k[2], 99))):
        runs = table[key]
        if any(v not in runs for v in MEDIA_FILTER_VARIANTS):
            continue
        cells = []
        for v in MEDIA_FILTER_VARIANTS:
            cells += [fmt(own_ms(runs[v])), fmt(runs[v]["relmse"])]
        lines.append(f"| {' | '.join(key)} | " + " | ".join(cells) + " |")
    if not lines:
        return []
    return ["## Participating media: blur and half resolution", "",
            "Ray marching and bounded marching at each preset as run, with the depth-aware blur of the jitter "
            "(`blur_radius=2`), at half resolution with depth-aware upsampling (`resolution=half`), and both "
            "(`resolution=half,blur_radius=1`), timed in turn at 128x128 (`scripts/report.sh`, `--variant`). "
            "`own ms` counts the march, the optical depth, the blur and the upsampling; relMSE of `scattering` "
            "against the reference.", "",
            "| scene | technique | preset | own ms | relMSE | blurred ms | relMSE | half ms | relMSE | "
            "half, blurred ms | relMSE |",
            "|" + "---|" * 11] + lines + [""]
