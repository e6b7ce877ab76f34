#!/usr/bin/python3
"""A CAD bracket meshed by gmsh into curved 10-node tets, rendered in situ by tetray.

    PYTHONPATH=PREFIX/lib/python3/dist-packages mpirun -np 2 /usr/bin/python3 \
        examples/gmsh/bracket_insitu.py [--config FILE] [--steps N] [--size MM]

Rank 0 builds and meshes the part (bracket_part.py) and sends the mesh to the others; each rank
then takes a share of the cells and only the points they use, as a solver's partition would hold
them, and passes its cells to tetray as VTK quadratic tets (quadratic_cells.py). At every step the
field (bracket_field.py: the distance to a point swinging along the bend) is evaluated at every
node, corners and edge nodes, and tetray draws its isosurfaces (bracket_insitu.yaml). Images go
to the config's output directory, relative to the working directory. At the end rank 0 prints the
median time of the example's own work per step beside tetray's blocked time per rendered step.
"""

import argparse
import pathlib
import sys
import time

import numpy as np
from mpi4py import MPI

import tetray
from quadratic_cells import LocalCells, share_of_cells, vtk_tet10

try:
    import bracket_part
    from bracket_field import distance_field
except ImportError as missing_gmsh:  # fail saying what to install, never skip
    sys.exit(f"bracket_insitu.py: {missing_gmsh}")


def mesh_on_rank_zero(comm, size):
    """The quadratic mesh on every rank: made once on rank 0 (gmsh is not run per rank)."""
    mesh = None
    if comm.rank == 0:
        started = time.perf_counter()
        nodes, tets = bracket_part.mesh_bracket(size)
        print(f"gmsh: {len(tets)} quadratic tets, {len(nodes)} nodes in "
              f"{time.perf_counter() - started:.2f} s", flush=True)
        mesh = (nodes, tets)
    return comm.bcast(mesh, root=0)


def main():
    here = pathlib.Path(__file__).resolve().parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default=here / "bracket_insitu.yaml", type=pathlib.Path)
    parser.add_argument("--steps", type=int, default=8)
    parser.add_argument("--size", type=float, default=5.0, help="the mesh size in mm")
    args = parser.parse_args()
    if args.steps < 1 or args.size <= 0:
        parser.error("--steps must be at least 1 and --size above 0")

    comm = MPI.COMM_WORLD
    nodes, gmsh_tets = mesh_on_rank_zero(comm, args.size)
    vtk_tets = vtk_tet10(gmsh_tets)
    centroids = nodes[gmsh_tets[:, :4]].mean(axis=1)
    local = LocalCells(nodes, vtk_tets, share_of_cells(len(vtk_tets), centroids, comm.rank,
                                                       comm.size))

    work_seconds, blocked_seconds = [], []
    with tetray.Adaptor(comm, args.config) as adaptor:
        for step in range(args.steps):
            t = step / args.steps
            started = time.perf_counter()
            distance = distance_field(local.points, t)  # the example's own work this step
            work_seconds.append(time.perf_counter() - started)
            report = adaptor.execute(step, t, local.points, None, {"distance": distance},
                                     cells=local.cells,
                                     changes=tetray.Changes(geometry=False, topology=False))
            if report.rendered:
                blocked_seconds.append(report.seconds_blocked)
    if comm.rank == 0:
        print(f"per step (medians, rank 0 of {comm.size}): the field "
              f"{1e3 * np.median(work_seconds):.2f} ms, tetray blocked "
              f"{1e3 * np.median(blocked_seconds):.1f} ms per rendered step "
              f"({len(blocked_seconds)} rendered)", flush=True)


if __name__ == "__main__":
    main()
