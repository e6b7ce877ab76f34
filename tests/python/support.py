"""Shared pieces of the Python tests: a tet box mesh, the pixels a camera on the z axis sees of a
square, PNG decoding, and unittest on every rank of MPI.COMM_WORLD."""

import itertools
import math
import sys
import unittest

import numpy as np
import png
from mpi4py import MPI


def box_mesh(cells, lo=-1.0, hi=1.0):
    """The cube [lo, hi]^3 as cells^3 hexahedra of 6 Kuhn tets each (docs/architecture.md §6),
    positively oriented: points (N, 3) float64 and tets (6 cells^3, 4) int64."""
    g = np.linspace(lo, hi, cells + 1)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    points = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    i, j, k = (a.ravel() for a in np.meshgrid(*[np.arange(cells)] * 3, indexing="ij"))

    def corner(offset):
        return ((k + offset[2]) * (cells + 1) + j + offset[1]) * (cells + 1) + i + offset[0]

    blocks = []
    for axes in itertools.permutations(range(3)):  # one path from (0,0,0) to (1,1,1) per tet
        offset = [0, 0, 0]
        vertices = [corner(offset)]
        for axis in axes:
            offset[axis] += 1
            vertices.append(corner(offset))
        blocks.append(np.stack(vertices, axis=1))
    tets = np.concatenate(blocks).astype(np.int64)
    a, b, c, d = (points[tets[:, v]] for v in range(4))
    negative = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) < 0
    tets[np.ix_(negative, [2, 3])] = tets[np.ix_(negative, [3, 2])]
    return points, tets


def box_hexahedra(cells):
    """The cubes of box_mesh(cells) as VTK hexahedra (type 12, VTK's node order): the cells tuple
    (types (c,) uint8, offsets (c + 1,) int64, connectivity (8 c,) int64) of Adaptor.execute."""
    i, j, k = (a.ravel() for a in np.meshgrid(*[np.arange(cells)] * 3, indexing="ij"))
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1),
               (0, 1, 1)]
    nodes = [((k + dz) * (cells + 1) + j + dy) * (cells + 1) + i + dx for dx, dy, dz in corners]
    connectivity = np.stack(nodes, axis=1).astype(np.int64).ravel()
    count = cells ** 3
    types = np.full(count, 12, dtype=np.uint8)
    return types, np.arange(0, 8 * count + 1, 8, dtype=np.int64), connectivity


def square_coverage(width, height, eye_z, plane_z, fov_deg, half_side=1.0, margin=1e-3):
    """For a camera at (0, 0, eye_z) looking at the origin with up +y and vertical field of view
    fov_deg (render/scene/camera.cpp: rays through pixel centers), and the square
    |x|, |y| <= half_side at z = plane_z: (sure, possible) boolean (height, width) masks of the
    pixels whose ray hits it farther than `margin` inside its edge, and at most `margin` outside.
    Also the x coordinate where each pixel's ray meets the plane."""
    tan_half = math.tan(math.radians(fov_deg) / 2)
    u = (2 * (np.arange(width) + 0.5) / width - 1) * tan_half * width / height
    v = (1 - 2 * (np.arange(height) + 0.5) / height) * tan_half
    distance = eye_z - plane_z
    x = np.broadcast_to(distance * u, (height, width))
    y = np.broadcast_to(distance * v[:, None], (height, width))
    reach = np.maximum(np.abs(x), np.abs(y))
    return reach < half_side - margin, reach <= half_side + margin, x


def read_png(path):
    """The PNG at `path` as a (height, width, 4) uint8 RGBA array."""
    with open(path, "rb") as file:
        width, height, rows, _ = png.Reader(file=file).asRGBA8()
        return np.array([np.frombuffer(bytes(r), dtype=np.uint8) for r in rows]).reshape(
            height, width, 4)


def run_on_every_rank():
    """Runs the unittest tests of __main__ on every rank; exits non-zero on every rank when a test
    failed on any."""
    comm = MPI.COMM_WORLD
    verbosity = 2 if comm.rank == 0 else 1
    result = unittest.main(exit=False, verbosity=verbosity).result
    failed = comm.allreduce(not result.wasSuccessful(), op=MPI.LOR)
    sys.exit(1 if failed else 0)
