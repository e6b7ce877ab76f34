#!/usr/bin/python3
"""The split study on the gmsh bracket: image error of splitting curved 10-node tets into linear
tets, against run time.

    PYTHONPATH=PREFIX/lib/python3/dist-packages /usr/bin/python3 examples/gmsh/split_study.py \
        [--size MM] [--levels 1 2 4] [--reference 8] [--pixels 512] [--repeat 3] [--json FILE] \
        [--out DIR] [--check MEAN MISS] [--gmsh-order]

Level 1 is tetray's own split: the 10-node tets go to tetray as VTK cells, and tetray cuts each
into 8 linear tets through its edge nodes. Levels 2, 4, ... cut each tet 2 L times along every
edge through its quadratic map here (tet_subdivision.py, with gmsh's own basis functions), the
quadratic field interpolated, and pass the 8 L^3 linear tets per cell. Each is rendered by
tetray (the field's isosurfaces, one camera) and its depth image (EXR Z) compared with the
reference level's: the mean and largest depth difference over the pixels both hit, relative to
the part's size (the diagonal of its box), the largest again leaving out the pixels beside a
silhouette or occlusion edge of the reference (where a pixel of one image can see a surface
behind the other's), and the share of the pixels either hits that one hits and the other
misses. Times: split ms is this script's subdivision plus tetray's ingest (its own split at
level 1), build and trace ms are tetray's (tetray_log.csv), medians of --repeat renders, each a
topology change (a new BVH).

--check MEAN MISS exits 1 unless level 1 is within MEAN relative mean depth error and MISS (a
fraction) hit/miss mismatch. --gmsh-order passes gmsh's node order to tetray unchanged (wrong:
gmsh's last two edge nodes are VTK's swapped), to show that the check catches it.
"""

import argparse
import csv
import json
import pathlib
import shutil
import sys
import time

import numpy as np
from mpi4py import MPI

import tetray
from exr_depth import read_depth
from quadratic_cells import VTK_QUADRATIC_TETRA, vtk_tet10

try:
    import bracket_part
    from bracket_field import ISOVALUES, distance_field
    from tet_subdivision import subdivide
except ImportError as missing_gmsh:  # fail saying what to install, never skip
    sys.exit(f"split_study.py: {missing_gmsh}")

SCENE = "split"
# The view of bracket_insitu.yaml's `shells` scene, headlight only, square.
CONFIG = """
output: {{directory: {directory}, formats: [exr], exr_compression: none, cinema: false,
         quiet: true, writer_queue_depth: 0}}
scenes:
  - name: {scene}
    field: distance
    isovalues: {isovalues}
    camera: {{eye: [165, -95, 125], look_at: [42, 30, 24], up: [0, 0, 1], fov_deg: 36}}
    image: {{width: {pixels}, height: {pixels}}}
"""


def log_rows(directory):
    with open(directory / "tetray_log.csv", newline="") as f:
        return {int(row["step"]): row for row in csv.DictReader(f)}


class Renderer:
    """One adaptor; every render is a step with a new topology, its depth read back."""

    def __init__(self, directory, pixels):
        self.directory = directory
        for old in (directory / SCENE, directory / "tetray_log.csv"):  # this study's own files
            shutil.rmtree(old, ignore_errors=True) if old.is_dir() else old.unlink(missing_ok=True)
        text = CONFIG.format(directory=directory, scene=SCENE, pixels=pixels,
                             isovalues=list(ISOVALUES))
        self.adaptor = tetray.Adaptor.from_yaml(MPI.COMM_WORLD, text)
        self.step = 0

    def render(self, points, values, tets=None, cells=None):
        self.step += 1
        self.adaptor.execute(self.step, 0.0, points, tets, {"distance": values}, cells=cells)
        row = log_rows(self.directory)[self.step]
        depth = read_depth(self.directory / SCENE / f"{SCENE}_{self.step:06d}.exr")
        times = {k: float(row[k]) for k in ("ingest_ms", "bvh_ms", "trace_ms", "blocked_ms")}
        return depth, times, int(row["tets"])

    def close(self):
        self.adaptor.finalize()


def render_level(renderer, nodes, gmsh_tets, values, level, repeat, gmsh_order):
    """(depth, tets, split ms, build ms, trace ms) of `level`, times the medians of `repeat`."""
    runs = []
    for _ in range(repeat):
        started = time.perf_counter()
        if level == 1:
            connectivity = gmsh_tets if gmsh_order else vtk_tet10(gmsh_tets)
            count = len(connectivity)
            cells = (np.full(count, VTK_QUADRATIC_TETRA, dtype=np.uint8),
                     np.arange(0, 10 * count + 1, 10, dtype=np.int64),
                     np.ascontiguousarray(connectivity.reshape(-1), dtype=np.int64))
            points, point_values, tets = nodes, values, None
        else:
            cells = None
            points, tets, point_values = subdivide(nodes, gmsh_tets, values, level)
        split_ms = 1e3 * (time.perf_counter() - started)
        depth, times, tet_count = renderer.render(points, point_values, tets=tets, cells=cells)
        runs.append((split_ms + times["ingest_ms"], times["bvh_ms"], times["trace_ms"]))
    split_ms, build_ms, trace_ms = np.median(np.array(runs), axis=0)
    return depth, tet_count, split_ms, build_ms, trace_ms


def depth_edges(reference, size):
    """Pixels beside a jump in the reference's depth (more than 1% of the part's size to a
    neighbour, or the background): a silhouette or an occlusion edge, where an edge moved by
    a pixel sees a surface behind the other's."""
    far = np.where(np.isfinite(reference), reference.astype(np.float64), 1e30)
    padded = np.pad(far, 1, mode="edge")
    height, width = far.shape
    edges = np.zeros(far.shape, dtype=bool)
    for dy in (0, 1, 2):
        for dx in (0, 1, 2):
            edges |= np.abs(padded[dy:dy + height, dx:dx + width] - far) > 0.01 * size
    return edges


def depth_error(depth, reference, size):
    hit, reference_hit = np.isfinite(depth), np.isfinite(reference)
    both = hit & reference_hit
    error = np.zeros(depth.shape)
    error[both] = np.abs(depth[both].astype(np.float64) - reference[both]) / size
    off_edges = both & ~depth_edges(reference, size)
    either = int((hit | reference_hit).sum())
    return {
        "mean_depth_error": float(error[both].mean()) if both.any() else 0.0,
        "max_depth_error": float(error[both].max()) if both.any() else 0.0,
        "max_depth_error_off_edges": float(error[off_edges].max()) if off_edges.any() else 0.0,
        "hit_mismatch_fraction": float((hit != reference_hit).sum()) / either if either else 0.0,
        "pixels_hit": int(hit.sum()),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=float, default=5.0, help="the mesh size in mm")
    parser.add_argument("--levels", type=int, nargs="+", default=[1, 2, 4])
    parser.add_argument("--reference", type=int, default=8)
    parser.add_argument("--pixels", type=int, default=512, help="the image's width and height")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", type=pathlib.Path, default=pathlib.Path("out/gmsh_split_study"))
    parser.add_argument("--json", type=pathlib.Path)
    parser.add_argument("--check", type=float, nargs=2, metavar=("MEAN", "MISS"))
    parser.add_argument("--gmsh-order", action="store_true")
    args = parser.parse_args()
    if MPI.COMM_WORLD.size != 1:
        parser.error("run on one rank")
    if any(level < 1 or level & (level - 1) for level in args.levels + [args.reference]):
        parser.error("levels are powers of 2")
    if args.reference <= max(args.levels):
        parser.error("the reference level must be finer than every level studied")

    nodes, gmsh_tets = bracket_part.mesh_bracket(args.size)
    values = distance_field(nodes, 0.0)
    size = bracket_part.SIZE
    renderer = Renderer(args.out, args.pixels)
    try:
        reference, reference_tets, *reference_ms = render_level(
            renderer, nodes, gmsh_tets, values, args.reference, 1, False)
        rows = []
        for level in args.levels:
            depth, tets, split_ms, build_ms, trace_ms = render_level(
                renderer, nodes, gmsh_tets, values, level, args.repeat, args.gmsh_order)
            rows.append({"level": level, "tets": tets, "split_ms": split_ms,
                         "build_ms": build_ms, "trace_ms": trace_ms,
                         **depth_error(depth, reference, size)})
    finally:
        renderer.close()

    print(f"bracket: {len(gmsh_tets)} quadratic tets (--size {args.size:g} mm), "
          f"{args.pixels}x{args.pixels} px, errors relative to the part's size {size:.1f} mm, "
          f"reference level {args.reference} ({reference_tets:,} tets, "
          f"split {reference_ms[0]:.0f} ms, build {reference_ms[1]:.0f} ms, "
          f"trace {reference_ms[2]:.0f} ms)")
    print(f"{'level':>5} {'tets':>11} {'split ms':>9} {'build ms':>9} {'trace ms':>9} "
          f"{'mean depth':>11} {'max depth':>10} {'max off edges':>13} {'hit/miss':>9}")
    for r in rows:
        print(f"{r['level']:>5} {r['tets']:>11,} {r['split_ms']:>9.1f} {r['build_ms']:>9.1f} "
              f"{r['trace_ms']:>9.1f} {r['mean_depth_error']:>11.2e} "
              f"{r['max_depth_error']:>10.2e} {r['max_depth_error_off_edges']:>13.2e} "
              f"{100 * r['hit_mismatch_fraction']:>8.3f}%")
    if args.json:
        summary = {"mesh_size_mm": args.size, "quadratic_tets": len(gmsh_tets),
                   "pixels": args.pixels, "part_size_mm": size, "reference_level": args.reference,
                   "reference_tets": reference_tets, "gmsh_order": args.gmsh_order, "rows": rows}
        args.json.write_text(json.dumps(summary, indent=2) + "\n")
    if args.check:
        level1 = next((r for r in rows if r["level"] == 1), None)
        if level1 is None:
            sys.exit("--check needs level 1 among --levels")
        mean, miss = args.check
        if level1["mean_depth_error"] > mean or level1["hit_mismatch_fraction"] > miss:
            sys.exit(f"level 1 is outside the check: mean depth error "
                     f"{level1['mean_depth_error']:.2e} (at most {mean:.2e}), hit/miss "
                     f"{level1['hit_mismatch_fraction']:.4f} (at most {miss:.4f})")
        print(f"level 1 is within the check (mean depth error at most {mean:.2e}, hit/miss at "
              f"most {miss:.4f})")


if __name__ == "__main__":
    main()
