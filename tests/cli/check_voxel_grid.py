"""Checks an `obscura voxelize` output directory: grid.json keys, grid.u8 size and values,
the x-fastest order (the Cornell box's floor is the y = 0 slice of voxels), and grid.ply's
header against its size. Usage: check_voxel_grid.py DIR [--cornell]"""
import json
import pathlib
import sys

import numpy as np


def fail(message):
    sys.exit(f"check_voxel_grid: {message}")


def check_ply(path):
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    if header[:2] != ["ply", "format binary_little_endian 1.0"]:
        fail(f"{path}: not a binary little-endian PLY: {header[:2]}")
    counts = {line.split()[1]: int(line.split()[2]) for line in header if line.startswith("element")}
    # Vertices: 3 floats + 3 bytes; faces: a count byte + 3 uint32.
    expected = end + counts["vertex"] * 15 + counts["face"] * 13
    if len(data) != expected or counts["face"] == 0:
        fail(f"{path}: {len(data)} bytes, the header promises {expected} ({counts})")


def main():
    out = pathlib.Path(sys.argv[1])
    meta = json.loads((out / "grid.json").read_text())
    for key in ("dims", "box_min", "box_max", "order"):
        if key not in meta:
            fail(f"grid.json lacks {key}")
    if meta["order"] != "x-fastest":
        fail(f"order is {meta['order']}")
    nx, ny, nz = meta["dims"]
    if not all(lo < hi for lo, hi in zip(meta["box_min"], meta["box_max"])):
        fail(f"box {meta['box_min']} .. {meta['box_max']} is empty")
    grid = np.fromfile(out / "grid.u8", dtype=np.uint8)
    if grid.size != nx * ny * nz:
        fail(f"grid.u8 has {grid.size} bytes for dims {meta['dims']}")
    if not np.isin(grid, (0, 1)).all():
        fail("grid.u8 holds values other than 0 and 1")
    if int(grid.sum()) != meta["voxels_set"]:
        fail(f"grid.u8 sets {int(grid.sum())} voxels, grid.json says {meta['voxels_set']}")
    voxels = grid.reshape(nz, ny, nx)  # x fastest: index (z * ny + y) * nx + x
    if "--cornell" in sys.argv:
        # The floor (world y = 0, a margin above the box's bottom) fills the y = 0 slice of
        # the interior columns (95 %: the published floor is not quite a rectangle); the middle
        # of the room (y = ny / 2) is mostly empty air.
        floor = voxels[2:-2, 0, 2:-2].mean()
        middle = voxels[2:-2, ny // 2, 2:-2].mean()
        if not (floor > 0.95 and middle < 0.2):
            fail(f"not x-fastest with y up: floor slice {floor:.3f} set, middle slice {middle:.3f}")
    if (out / "grid.ply").exists():
        check_ply(out / "grid.ply")
    print(f"{out}: {meta['dims']} voxels, {meta['voxels_set']} set, order and values check out")


main()
