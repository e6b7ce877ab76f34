"""The field on the bracket: the distance (mm) to a point that swings along the bracket's outer
bend, evaluated at every node of the curved mesh, corners and edge nodes alike.

Its isosurfaces are spheres about that point. Spheres of radius 25-75 mm centred just outside
the bend cross the base plate and the upright, the bend's fillet and the rib, and pass through
the bolt holes and the slot, so the rim of each isosurface traces the part's curved faces; as the
point moves along y the spheres slide across the holes. The exact isosurface is known (a sphere
cut by the part), which makes a wrong picture easy to see, and the field is smooth but not
polynomial, so neither a linear nor a quadratic cell carries it exactly: the split study measures
a real interpolation error.
"""

import math

import numpy as np

from bracket_part import WIDTH

ISOVALUES = (25.0, 40.0, 55.0, 70.0)


def source_point(t):
    """The point at time t in [0, 1]: it swings once along y, outside the bend's outer edge."""
    return np.array([-6.0, WIDTH / 2 + 0.4 * WIDTH * math.sin(2 * math.pi * t), -6.0])


def distance_field(points, t):
    """(n,) float64: the distance of each point to source_point(t)."""
    return np.linalg.norm(points - source_point(t), axis=1)
