"""Finer linear splits of curved 10-node tets, for the split study: at `level` L each tet is cut
2 L times along every edge, into 8 L^3 linear tets, through its quadratic map, the quadratic
field interpolated at the new points.

Level 1 is what tetray does to a 10-node tet: one red refinement, 8 tets through the edge nodes.
Level 2^k repeats the red refinement k more times in the reference tet. The new points are
placed by gmsh's own Lagrange basis functions in gmsh's node order
(gmsh.model.mesh.getBasisFunctions), not by the VTK reordering the example passes to tetray: a
reference made here would disagree with tetray's image if that reordering were wrong. A point
shared by neighbouring tets (on an edge or face) is made once, from one tet, so the finer mesh is
watertight.
"""

import numpy as np

from bracket_part import GMSH_TET10  # first: it says what to install when gmsh is missing
import gmsh


def red_refinement(cuts):
    """The sub-tets of the reference tet cut `cuts` (a power of 2) times along each edge:
    (cuts^3, 4, 4) integer barycentric coordinates (weights of corners 0-3) summing to cuts,
    each sub-tet oriented as the reference tet."""
    if cuts < 1 or cuts & (cuts - 1):
        raise ValueError(f"the cuts per edge must be a power of 2, not {cuts}")
    tets = np.array([cuts * np.eye(4, dtype=np.int64)])
    while len(tets) < cuts**3:
        a, b, c, d = (tets[:, i] for i in range(4))
        ab, ac, ad, bc, bd, cd = ((a + b) // 2, (a + c) // 2, (a + d) // 2, (b + c) // 2,
                                  (b + d) // 2, (c + d) // 2)
        children = [
            (a, ab, ac, ad), (ab, b, bc, bd), (ac, bc, c, cd), (ad, bd, cd, d),
            # The inner octahedron, cut along its diagonal ab-cd into 4 tets, as tetray cuts
            # a 10-node tet (so level 2 refines each of tetray's level-1 tets).
            (ab, cd, bc, ac), (ab, cd, ac, ad), (ab, cd, ad, bd), (ab, cd, bd, bc),
        ]
        tets = np.concatenate([np.stack(child, axis=1) for child in children])
    # Sub-tets that come out inverted: swap their last two corners.
    edges = tets[:, 1:, 1:] - tets[:, :1, 1:]
    inverted = np.linalg.det(edges.astype(np.float64)) < 0
    tets[inverted] = tets[inverted][:, [0, 1, 3, 2]]
    return tets


def gmsh_tet10_basis(barycentric):
    """(p, 10): gmsh's quadratic Lagrange basis at the points given by barycentric weights
    (p, 4), in gmsh's node order. gmsh's reference tet has corners 0, e_u, e_v, e_w."""
    uvw = np.ascontiguousarray(barycentric[:, 1:], dtype=np.float64).reshape(-1)
    gmsh.initialize(["gmsh", "-nt", "1"])  # a session of its own (bracket_part's has ended)
    try:
        _, values, _ = gmsh.model.mesh.getBasisFunctions(GMSH_TET10, list(uvw), "Lagrange")
    finally:
        gmsh.finalize()
    return np.asarray(values).reshape(len(barycentric), 10)


def subdivide(nodes, gmsh_tets, values, level):
    """Each 10-node tet (gmsh's order) as 8 level^3 linear tets on the same quadratic map.

    Returns (points (q, 3), tets (m * 8 level^3, 4) int32, values (q,)): the values interpolated by
    the quadratic basis; points on shared edges and faces made once."""
    if level < 1 or level & (level - 1):
        raise ValueError(f"the level must be a power of 2, not {level}")
    cuts = 2 * level
    sub = red_refinement(cuts)
    lattice, local = np.unique(sub.reshape(-1, 4), axis=0, return_inverse=True)
    basis = gmsh_tet10_basis(lattice / cuts)  # (p, 10)
    count = len(gmsh_tets)
    # A lattice point of tet t is named by its corners' global numbers and weights, the same
    # in every tet that shares it: corner * (cuts + 1) + weight, -1 where the weight is 0,
    # sorted. Rows of equal names are one point.
    corners = gmsh_tets[:, :4].astype(np.int64)
    names = corners[:, None, :] * (cuts + 1) + lattice[None, :, :]
    names = np.where(lattice[None, :, :] > 0, names, -1)
    names = np.sort(names, axis=2).reshape(-1, 4)
    order = np.lexsort(names.T[::-1])
    sorted_names = names[order]
    first = np.ones(len(order), dtype=bool)
    first[1:] = np.any(sorted_names[1:] != sorted_names[:-1], axis=1)
    point_of_sorted = np.cumsum(first) - 1
    point_of_row = np.empty(len(order), dtype=np.int32)
    point_of_row[order] = point_of_sorted
    maker = order[first]  # one (tet, lattice point) row per new point
    tet_of, lattice_of = np.divmod(maker, len(lattice))
    points = np.empty((len(maker), 3))
    point_values = np.empty(len(maker))
    for block in range(0, len(maker), 1 << 20):  # in blocks: (q, 10, 3) at once is gigabytes
        part = slice(block, block + (1 << 20))
        weights, cell_nodes = basis[lattice_of[part]], gmsh_tets[tet_of[part]]  # (b, 10) each
        points[part] = np.einsum("qk,qkd->qd", weights, nodes[cell_nodes])
        point_values[part] = np.einsum("qk,qk->q", weights, values[cell_nodes])
    rows = point_of_row.reshape(count, len(lattice))
    tets = rows[:, local.reshape(-1, 4)].reshape(-1, 4)
    return np.ascontiguousarray(points), np.ascontiguousarray(tets), point_values
