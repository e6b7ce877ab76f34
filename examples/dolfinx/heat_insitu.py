#!/usr/bin/python3
"""The heat equation on a tet box with DOLFINx 0.5, rendered in situ by tetray.

    PYTHONPATH=build/python mpirun -np 2 /usr/bin/python3 examples/dolfinx/heat_insitu.py \
        [--config FILE] [--cells N] [--steps N] [--dt DT] [--vtk DIR] [--without ghost|global_ids]

du/dt - div(grad u) = f on [0, 1]^3, u = 0 on the boundary and at t = 0, with a Gaussian source f
circling the box's vertical axis once over the run; P1 Lagrange in space, backward Euler in time.
tetray reads DOLFINx's own arrays (README "Python", "DOLFINx"): the geometry's coordinates and
dofmap without copies, the ghost cells flagged, the temperature per geometry node, and
original_cell_index as the partition-independent tet ids; `--without` leaves the flags or the
ids out (docs/coupling.md "DOLFINx" says what each does). Images go to the config's output
directory, relative to the working directory. With --vtk DIR every step is also saved as DOLFINx
writes it (DIR/temperature.pvd, one .pvtu of per-rank .vtu pieces per step), for
`tetray-replay -c CONFIG --first-step 1 DIR/temperature.pvd`.
"""

import argparse
import math
import pathlib
import time

import numpy as np
import ufl
from dolfinx import fem, io, mesh
from dolfinx.fem.petsc import LinearProblem
from mpi4py import MPI
from petsc4py import PETSc

import tetray

SOURCE_RADIUS = 0.25  # of the source's circle about the axis x = y = 0.5
SOURCE_WIDTH = 0.08   # the Gaussian's standard deviation
SOURCE_PEAK = 400.0


def dof_of_node(dofs, nodes, node_count):
    """For each geometry node, the P1 dof of the same vertex, from the function space's dofmap
    and the geometry's (flat, cell by cell, both in the cell's local vertex order)."""
    mapping = np.empty(node_count, dtype=np.int32)
    mapping[nodes] = dofs
    return mapping


class TetrayViews:
    """DOLFINx's mesh as tetray's views, and a P1 field per geometry node."""

    def __init__(self, msh, space):
        tdim = msh.topology.dim
        # (nodes, 3) float64 and (cells, 4) int32 geometry node numbers: views of DOLFINx's arrays.
        self.points = msh.geometry.x
        self.tets = msh.geometry.dofmap.array.reshape(-1, 4)
        # Cells past the owned ones are ghosts, drawn by the rank that owns them.
        self.ghost = np.zeros(len(self.tets), dtype=np.uint8)
        self.ghost[msh.topology.index_map(tdim).size_local:] = 1  # vtkGhostType DUPLICATECELL
        # The cell's index in the mesh as created, the same for any partition (unlike
        # index_map.local_range[0] + local index).
        self.global_ids = msh.topology.original_cell_index
        # A P1 dof and the geometry node of the same vertex need not have the same number.
        dofs = space.dofmap.list.array
        nodes = msh.geometry.dofmap.array
        self.dof_of_node = dof_of_node(dofs, nodes, len(self.points))
        self.same_numbering = bool(np.array_equal(dofs, nodes))

    def per_node(self, function):
        """The P1 function's values in geometry node order: the dof array itself when the two
        numberings agree (as they do for DOLFINx 0.5's affine meshes), else a gathered copy."""
        values = function.x.array
        return values if self.same_numbering else values[self.dof_of_node]


def source_center(t, period):
    angle = 2 * math.pi * t / period
    return (0.5 + SOURCE_RADIUS * math.cos(angle), 0.5 + SOURCE_RADIUS * math.sin(angle), 0.4)


def heat_problem(msh, space, dt):
    """Backward Euler for du/dt - div(grad u) = f: the problem, the solution, the previous step
    and the source's center."""
    previous = fem.Function(space)
    solution = fem.Function(space)
    center = fem.Constant(msh, PETSc.ScalarType((0.5, 0.5, 0.4)))
    x = ufl.SpatialCoordinate(msh)
    r = x - center
    f = SOURCE_PEAK * ufl.exp(-ufl.dot(r, r) / (2 * SOURCE_WIDTH**2))
    u, v = ufl.TrialFunction(space), ufl.TestFunction(space)
    a = u * v * ufl.dx + dt * ufl.inner(ufl.grad(u), ufl.grad(v)) * ufl.dx
    rhs = (previous + dt * f) * v * ufl.dx
    boundary = mesh.locate_entities_boundary(
        msh, msh.topology.dim - 1, lambda p: np.full(p.shape[1], True))
    dofs = fem.locate_dofs_topological(space, msh.topology.dim - 1, boundary)
    bc = fem.dirichletbc(PETSc.ScalarType(0), dofs, space)
    # A tight tolerance: the solution, and so the image, must not depend on the partition.
    options = {"ksp_type": "cg", "pc_type": "jacobi", "ksp_rtol": 1e-12, "ksp_atol": 1e-14}
    problem = LinearProblem(a, rhs, bcs=[bc], u=solution, petsc_options=options)
    return problem, solution, previous, center


def main():
    here = pathlib.Path(__file__).resolve().parent
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default=here / "heat_insitu.yaml", type=pathlib.Path)
    parser.add_argument("--cells", type=int, default=10, help="cells per side (6 tets each)")
    parser.add_argument("--steps", type=int, default=24)
    parser.add_argument("--dt", type=float, default=0.005)
    parser.add_argument("--vtk", type=pathlib.Path, help="also save every step here")
    parser.add_argument("--without", choices=["ghost", "global_ids"], action="append", default=[],
                        help="leave out the ghost flags or the tet ids (to see what they do)")
    args = parser.parse_args()

    comm = MPI.COMM_WORLD
    msh = mesh.create_box(comm, [np.zeros(3), np.ones(3)], [args.cells] * 3,
                          mesh.CellType.tetrahedron, ghost_mode=mesh.GhostMode.shared_facet)
    space = fem.FunctionSpace(msh, ("Lagrange", 1))
    problem, solution, previous, center = heat_problem(msh, space, args.dt)
    views = TetrayViews(msh, space)
    period = args.steps * args.dt

    series = io.VTKFile(comm, str(args.vtk / "temperature.pvd"), "w") if args.vtk else None
    solution.name = "temperature"
    ghost = None if "ghost" in args.without else views.ghost
    global_ids = None if "global_ids" in args.without else views.global_ids
    solve_seconds, skipped_seconds = [], []
    with tetray.Adaptor(comm, args.config) as adaptor:
        for step in range(1, args.steps + 1):
            t = step * args.dt
            center.value[:] = source_center(t, period)
            started = time.perf_counter()
            problem.solve()  # also updates the ghost dofs (scatter_forward)
            solve_seconds.append(time.perf_counter() - started)
            previous.x.array[:] = solution.x.array
            if series:
                series.write_function(solution, t)
            # Called at every step: the ones the trigger skips return at once (timed here).
            rendering = adaptor.will_render(step, t)
            started = time.perf_counter()
            report = adaptor.execute(
                step, t, views.points, views.tets, {"temperature": views.per_node(solution)},
                ghost=ghost, global_ids=global_ids,
                changes=tetray.Changes(geometry=False, topology=False))
            if not rendering:
                skipped_seconds.append(time.perf_counter() - started)
                continue
            peak = comm.allreduce(float(solution.x.array.max(initial=0.0)), op=MPI.MAX)
            if comm.rank == 0:
                print(f"step {step} t={t:.3f} max u={peak:.3f} bvh={report.bvh_decision} "
                      f"blocked {1e3 * report.seconds_blocked:.1f} ms", flush=True)
    if comm.rank == 0 and skipped_seconds:
        print(f"execute on a skipped step {1e6 * np.median(skipped_seconds):.1f} us, "
              f"a solve {1e3 * np.median(solve_seconds):.1f} ms (medians, rank 0)", flush=True)
    if series:
        series.close()


if __name__ == "__main__":
    main()
