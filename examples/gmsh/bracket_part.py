"""The part: an L-shaped bracket built with gmsh's OpenCASCADE kernel and meshed into 10-node
(second-order) tets whose edge nodes lie on the curved CAD surfaces.

Millimetres. The base plate lies on z = 0 (x in [0, 90], y in [0, 60], 10 thick); the upright
rises at x in [0, 10] to z = 70. A fillet of radius 12 rounds the inner bend, radius 8 the
upright's top corners and radius 10 the base plate's free corners; two bolt holes (diameter 12)
go through the base, two (diameter 10) through the upright, and a slot between the upright's holes.
A triangular rib with filleted edges stiffens the bend in the middle. Every curved face (holes,
fillets, the slot's ends) is a place where a linear tet's flat faces would cut the true surface.
"""

import numpy as np

try:
    import gmsh
except ImportError as error:  # say what to install, not only what is missing
    raise ImportError(f"{error}: the bracket is meshed by gmsh; install Debian's python3-gmsh "
                      "(apt-get install python3-gmsh) and run /usr/bin/python3") from error

LENGTH, WIDTH, THICK, HEIGHT = 90.0, 60.0, 10.0, 70.0
BEND_FILLET, TOP_FILLET, BASE_FILLET = 12.0, 8.0, 10.0
# The box the part fits in, for cameras and for errors relative to the part's size.
BOUNDS = np.array([[0.0, 0.0, 0.0], [LENGTH, WIDTH, HEIGHT]])
SIZE = float(np.linalg.norm(BOUNDS[1] - BOUNDS[0]))  # the box's diagonal, about 128 mm

# gmsh's element type of the 10-node tet, and its node order: corners 0-3, then the edges
# 01, 12, 20, 30, 32, 31 (gmsh's reference manual, "Node ordering").
GMSH_TET10 = 11


def _curves_in(box, dim=1):
    lo, hi = box
    return [tag for _, tag in gmsh.model.getEntitiesInBoundingBox(*lo, *hi, dim=dim)]


def _build_geometry():
    occ = gmsh.model.occ
    base = occ.addBox(0, 0, 0, LENGTH, WIDTH, THICK)
    upright = occ.addBox(0, 0, 0, THICK, WIDTH, HEIGHT)
    # The rib: a triangle in the plane y = WIDTH / 2, extruded across the rib's thickness.
    rib_half = 4.0
    corners = [(THICK, 0.0), (THICK + 40.0, 0.0), (THICK, 45.0)]
    points = [occ.addPoint(x, WIDTH / 2 - rib_half, THICK + z) for x, z in corners]
    lines = [occ.addLine(points[i], points[(i + 1) % 3]) for i in range(3)]
    face = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    rib = occ.extrude([(2, face)], 0, 2 * rib_half, 0)
    rib_volume = [tag for dim, tag in rib if dim == 3][0]
    (part,), _ = occ.fuse([(3, base)], [(3, upright), (3, rib_volume)])
    occ.synchronize()
    eps = 1e-3
    # The inner bend: the edge along y at x = THICK, z = THICK (split by the rib into pieces).
    bend = _curves_in(((THICK - eps, -eps, THICK - eps), (THICK + eps, WIDTH + eps, THICK + eps)))
    (part,) = occ.fillet([part[1]], bend, [BEND_FILLET])
    occ.synchronize()
    # The upright's top corners: its edges along x at z = HEIGHT, y = 0 and y = WIDTH.
    top = _curves_in(((-eps, -eps, HEIGHT - eps), (THICK + eps, eps, HEIGHT + eps)))
    top += _curves_in(((-eps, WIDTH - eps, HEIGHT - eps), (THICK + eps, WIDTH + eps, HEIGHT + eps)))
    (part,) = occ.fillet([part[1]], top, [TOP_FILLET])
    occ.synchronize()
    # The base plate's free corners: its vertical edges at x = LENGTH.
    free = _curves_in(((LENGTH - eps, -eps, -eps), (LENGTH + eps, eps, THICK + eps)))
    free += _curves_in(((LENGTH - eps, WIDTH - eps, -eps),
                        (LENGTH + eps, WIDTH + eps, THICK + eps)))
    (part,) = occ.fillet([part[1]], free, [BASE_FILLET])
    occ.synchronize()
    # Bolt holes and a slot.
    cutters = []
    for y in (15.0, WIDTH - 15.0):
        cutters.append((3, occ.addCylinder(65.0, y, -1.0, 0, 0, THICK + 2, 6.0)))
        cutters.append((3, occ.addCylinder(-1.0, y, 50.0, THICK + 2, 0, 0, 5.0)))
    slot_ends = [occ.addCylinder(-1.0, y, 30.0, THICK + 2, 0, 0, 4.0) for y in (22.0, 38.0)]
    slot_middle = occ.addBox(-1.0, 22.0, 26.0, THICK + 2, 16.0, 8.0)
    cutters += [(3, t) for t in slot_ends] + [(3, slot_middle)]
    occ.cut([part], cutters)
    occ.synchronize()


def mesh_bracket(size=6.0, verbose=False):
    """Meshes the bracket with quadratic tets of about `size` mm (smaller on tight curves).

    Returns (nodes, tets): nodes (n, 3) float64 in mm; tets (m, 10) int64 indices into nodes in
    gmsh's 10-node order, every node on the boundary placed on the CAD surface.
    """
    gmsh.initialize(["gmsh", "-nt", "1"])  # one thread: the same mesh on every run
    try:
        gmsh.option.setNumber("General.Terminal", 1 if verbose else 0)
        gmsh.model.add("bracket")
        _build_geometry()
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.option.setNumber("Mesh.MeshSizeMin", size / 4)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 16)  # elements per 2 pi of a curve
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)  # edge nodes on the CAD surfaces
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 1)  # untangle curved boundary tets
        gmsh.model.mesh.generate(3)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        _, element_nodes = gmsh.model.mesh.getElementsByType(GMSH_TET10)
        index = np.full(int(tags.max()) + 1, -1, dtype=np.int64)
        index[tags.astype(np.int64)] = np.arange(len(tags))
        tets = index[element_nodes.astype(np.int64)].reshape(-1, 10)
        used = np.unique(tets)
        # Keep only the nodes the tets use (gmsh also lists points of the construction).
        renumber = np.full(len(tags), -1, dtype=np.int64)
        renumber[used] = np.arange(len(used))
        nodes = coords.reshape(-1, 3)[used]
        return np.ascontiguousarray(nodes), renumber[tets]
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    import time

    started = time.perf_counter()
    nodes, tets = mesh_bracket()
    print(f"{len(tets)} tets, {len(nodes)} nodes in {time.perf_counter() - started:.2f} s; "
          f"bounds {nodes.min(axis=0)} {nodes.max(axis=0)}")
