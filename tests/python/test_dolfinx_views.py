"""The views examples/dolfinx/heat_insitu.py gives tetray, against DOLFINx's own mesh: DOLFINx's
arrays themselves (no copies), the field at each geometry node, the ghost cells, and tet ids that
do not depend on the partition; on any number of ranks."""

import unittest

import numpy as np
from dolfinx import fem, mesh
from mpi4py import MPI

import heat_insitu
import support

COMM = MPI.COMM_WORLD
CELLS = 4


def unit_box(comm):
    return mesh.create_box(comm, [np.zeros(3), np.ones(3)], [CELLS] * 3,
                           mesh.CellType.tetrahedron, ghost_mode=mesh.GhostMode.shared_facet)


def centroids(msh):
    return msh.geometry.x[msh.geometry.dofmap.array.reshape(-1, 4)].mean(axis=1)


def linear(x):
    return 1 + x[0] + 2 * x[1] + 3 * x[2]


class DolfinxViewsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.msh = unit_box(COMM)
        cls.space = fem.FunctionSpace(cls.msh, ("Lagrange", 1))
        cls.views = heat_insitu.TetrayViews(cls.msh, cls.space)
        cls.owned = cls.msh.topology.index_map(3).size_local

    def test_points_and_tets_are_dolfinx_arrays(self):
        self.assertTrue(np.shares_memory(self.views.points, self.msh.geometry.x))
        self.assertTrue(np.shares_memory(self.views.tets, self.msh.geometry.dofmap.array))
        self.assertEqual(self.views.points.shape[1], 3)
        self.assertEqual(self.views.tets.shape, (len(self.views.ghost), 4))

    def test_field_per_node_is_the_function_at_the_node(self):
        u = fem.Function(self.space)
        u.interpolate(linear)
        np.testing.assert_allclose(self.views.per_node(u), linear(self.views.points.T),
                                   rtol=0, atol=1e-12)

    def test_node_values_follow_any_dof_numbering(self):
        nodes = self.msh.geometry.dofmap.array
        count = len(self.views.points)
        renumber = np.random.default_rng(7).permutation(count).astype(np.int32)
        mapping = heat_insitu.dof_of_node(renumber[nodes], nodes, count)
        by_dof = np.empty(count)
        by_dof[renumber] = np.arange(count)  # dof renumber[i] holds node i's value, i
        np.testing.assert_array_equal(by_dof[mapping], np.arange(count))

    def test_cells_past_the_owned_ones_are_ghosts(self):
        ghost = self.views.ghost
        self.assertTrue(np.all(ghost[:self.owned] == 0))
        self.assertTrue(np.all(ghost[self.owned:] == 1))
        self.assertEqual(len(ghost) - self.owned, self.msh.topology.index_map(3).num_ghosts)
        total = COMM.allreduce(self.owned)
        self.assertEqual(total, 6 * CELLS**3)
        if COMM.size > 1:
            self.assertGreater(COMM.allreduce(int(ghost.sum())), 0)

    def test_ids_name_the_same_cell_for_any_partition(self):
        serial = unit_box(MPI.COMM_SELF)
        by_original = np.empty((6 * CELLS**3, 3))
        by_original[serial.topology.original_cell_index] = centroids(serial)
        here = centroids(self.msh)
        ids = self.views.global_ids
        np.testing.assert_allclose(here, by_original[ids], rtol=0, atol=1e-12)
        owned_ids = np.concatenate(COMM.allgather(ids[:self.owned]))
        np.testing.assert_array_equal(np.sort(owned_ids), np.arange(6 * CELLS**3))
        # The index map's global numbering does not name the same cells: it is why tetray gets
        # original_cell_index.
        if COMM.size > 1:
            local_range = self.msh.topology.index_map(3).local_range[0] + np.arange(self.owned)
            moved = np.any(np.abs(here[:self.owned] - by_original[local_range]) > 1e-12, axis=1)
            self.assertGreater(COMM.allreduce(int(moved.sum())), 0)


if __name__ == "__main__":
    support.run_on_every_rank()
