"""gmsh's 10-node tets as tetray's cells (VTK layout), and one rank's share of them.

gmsh lists a 10-node tet's edge nodes as 01, 12, 20, 30, 32, 31; VTK (VTK_QUADRATIC_TETRA, type
24) as 01, 12, 02, 03, 13, 23. The first four edges are the same edges; gmsh's last two are VTK's
last two swapped. Passing gmsh's order unchanged would put the nodes of edges 13 and 23 on each
other's edge: the tetray split would then run through points off the cell, and the image shows it
(tests/examples/gmsh.cmake checks the image against a reference that reads gmsh's order itself).
"""

import numpy as np

VTK_QUADRATIC_TETRA = 24
GMSH_TO_VTK_TET10 = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])


def vtk_tet10(gmsh_tets):
    """(m, 10) node indices in gmsh's order -> the same cells in VTK's order."""
    return np.ascontiguousarray(gmsh_tets[:, GMSH_TO_VTK_TET10])


def share_of_cells(cell_count, centroids, rank, ranks):
    """The cells rank `rank` of `ranks` takes: a contiguous run of cells sorted along the part's
    longest axis, so that each rank holds one compact piece (as a partitioner would give)."""
    axis = int(np.argmax(np.ptp(centroids, axis=0)))
    order = np.argsort(centroids[:, axis], kind="stable")
    bounds = np.linspace(0, cell_count, ranks + 1).round().astype(np.int64)
    return np.sort(order[bounds[rank]:bounds[rank + 1]])


class LocalCells:
    """One rank's cells in tetray's layout: its own points (only those its cells use, numbered
    locally) and the (types, offsets, connectivity) arrays of its 10-node tets."""

    def __init__(self, nodes, vtk_tets, cells):
        mine = vtk_tets[cells]
        self.node_ids, local = np.unique(mine, return_inverse=True)  # global node of each point
        self.points = np.ascontiguousarray(nodes[self.node_ids])
        count = len(mine)
        self.types = np.full(count, VTK_QUADRATIC_TETRA, dtype=np.uint8)
        self.offsets = np.arange(0, 10 * count + 1, 10, dtype=np.int64)
        self.connectivity = np.ascontiguousarray(local.reshape(-1).astype(np.int64))

    @property
    def cells(self):
        return self.types, self.offsets, self.connectivity
