"""The half- and quarter-resolution and refinement tables of benchmarks/report_tables.py on
made-up bench rows with distinct times and errors, so that each cell can only come from one
run (X full; X_half half, quarter, without refinement; X quarter, no blur). Decoys that must
stay out: another lane count, a shadow technique's `resolution` (a map size), and another
renderer's runs of the same key. Run with the benchmarks directory on sys.path
(tests/CMakeLists.txt)."""
import sys

import report_tables as rt


def row(preset, variant, settings, passes, rmse, technique="ao.points", renderer="llvmpipe"):
    return {"scene": "/models/engine.glb", "width": 64, "height": 48, "technique": technique, "quantity": "ao",
            "preset": preset, "variant": variant, "settings": settings, "rmse": rmse, "renderer": renderer,
            # The G-buffer is shared by every technique: it must not count in their times.
            "passes": [{"pass": "gbuffer.render", "median_ms": 100.0}] +
                      [{"pass": name, "median_ms": ms} for name, ms in passes]}


QUARTER = "resolution=quarter"
rows = [
    row("medium", "", {"rays": "16"}, [("ao.points", 8.0)], 0.1),
    dict(row("medium_half", "", {"resolution": "half", "blur_radius": "3"},
             [("ao.points", 2.0), ("ao.blur", 0.5), ("ao.upsample", 0.5)], 0.125),
         refined_pixels=12, refine_asked=12, geometry_pixels=48),
    row("medium", QUARTER, {"resolution": "quarter"}, [("ao.points", 0.5), ("ao.upsample", 0.25)], 0.25),
    row("medium_half", QUARTER, {"resolution": "quarter", "blur_radius": "3"},
        [("ao.points", 0.5), ("ao.blur", 0.25), ("ao.upsample", 0.25), ("ao.refine", 0.25)], 0.15),
    # high after medium in both tables (the presets cheapest first, not by name).
    row("high", "", {}, [("ao.points", 16.0)], 0.05),
    row("high_half", "", {"resolution": "half"}, [("ao.points", 4.0)], 0.06),
    row("high", QUARTER, {"resolution": "quarter"}, [("ao.points", 1.0)], 0.2),
    row("high_half", QUARTER, {"resolution": "quarter"}, [("ao.points", 2.0)], 0.07),
    # Decoys.
    row("medium", "ray_lanes=4", {"ray_lanes": "4"}, [("ao.points", 1000.0)], 0.9),
    row("medium", "", {"resolution": "1024"}, [("shadow.maps", 7.0)], 0.3, technique="shadow.pcf"),
    row("medium_half", QUARTER, {"resolution": "quarter"}, [("ao.points", 3000.0)], 0.7, renderer="gpu"),
]

failures = []


def expect(what, got, want):
    if got != want:
        failures.append(f"{what}: got {got!r}, want {want!r}")


def cells_of(what, line, header):
    """A table line's cells; the header above it must have as many."""
    cells = [c.strip() for c in line.strip("|").split("|")]
    expect(f"{what} header cells", len(header.strip("|").split("|")), len(cells))
    return cells


def presets_of(lines):
    return [line.split("|")[3].strip() for line in lines]


quarter = rt.quarter_lines(rows)
expect("quarter rows", len(quarter), 2)
expect("quarter presets", presets_of(quarter), ["medium", "high"])
if quarter:
    cells = cells_of("quarter", quarter[0], rt.QUARTER_HEADER[0])
    # full, half, quarter ms; tiles/filters/refinement of the quarter run; speed-ups 8/3 and
    # 8/1.25; RMSEs full, half, quarter; their ratio 0.15/0.1; the unblurred run's ms and RMSE.
    expect("quarter cells", cells, ["engine.glb", "64x48", "medium", "ao.points", "ao", "8", "3", "1.25", "0.75",
                                    "2.67", "6.4", "0.1", "0.125", "0.15", "1.5", "0.75", "0.25"])
half = rt.resolution_rows(rows)
expect("half rows", len(half), 2)
expect("half presets", presets_of(half), ["medium", "high"])
if half:
    cells = cells_of("half", half[0], rt.RESOLUTION_HEADER[0])
    expect("half cells", cells[5:], ["8", "3", "1", "12 of 48 (25%)", "2.67", "0.1", "0.125", "1.25", "yes"])
# The refinement study: X, X_half, and both with refine_threshold=0 (X's is the same full-resolution
# computation and stays out). Without the refinement X_half is 3.2x faster but at 3x the RMSE.
REFINE_OFF = "refine_threshold=0"
refine_rows = [
    row("medium", "", {}, [("ao.points", 8.0)], 0.1),
    dict(row("medium_half", "", {"resolution": "half"},
             [("ao.points", 2.0), ("ao.refine", 1.5), ("ao.upsample", 0.5)], 0.11),
         refined_pixels=40, refine_asked=40, geometry_pixels=160),
    row("medium", REFINE_OFF, {"refine_threshold": "0"}, [("ao.points", 8.5)], 0.1),
    row("medium_half", REFINE_OFF, {"resolution": "half", "refine_threshold": "0"},
        [("ao.points", 2.0), ("ao.upsample", 0.5)], 0.3),
    row("medium_half", "ray_lanes=4", {"resolution": "half", "ray_lanes": "4"}, [("ao.points", 1000.0)], 0.9),
]
refine = rt.refine_lines(refine_rows)
expect("refine rows", len(refine), 1)
if refine:
    cells = cells_of("refine", refine[0], rt.refine_section(refine_rows)[4])
    # full, half, its refinement and pixels, half without; speed-ups 8/4 and 8/2.5; RMSEs; goal met or not.
    expect("refine cells", cells[5:],
           ["8", "4", "1.5", "40 of 160 (25%)", "2.5", "2", "3.2", "0.1", "0.11", "0.3", "yes", "**no**"])
# The refined-pixels cell: an overflowed list refines none; bench files from before the counts say n/a.
expect("overflowed cell", rt.refined_cell({"refined_pixels": 0, "refine_asked": 50, "geometry_pixels": 160}),
       "none: 50 asked, over the list")
expect("old bench cell", rt.refined_cell({"rmse": 0.1}), "n/a")
for failure in failures:
    print(failure, file=sys.stderr)
sys.exit(1 if failures else 0)
