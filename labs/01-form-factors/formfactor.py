"""Lab 1: form factors by hand. Fill in the five tasks (README.md says what each must return);
labs/check 1 tells you what is still wrong.

Polygons are (k, 3) arrays of vertices, counter-clockwise seen from their front side (the side
their normal points to). Then study.py, beside this file, prints the comparisons and draws
near-field.png.
"""
import math

import numpy as np


# ---------------------------------------------------------------------------------------------
# Task 1: the point-to-polygon form factor (Lambert's contour formula)
# ---------------------------------------------------------------------------------------------
def point_to_polygon(x, normal, polygon):
    """Form factor from a differential area at x with unit normal `normal` to the polygon,
    which must lie wholly in front of x (no clipping here)."""
    # TODO Task 1: Lambert's contour formula (README.md, "The contour integral").
    # v_k = (P_k - x)/|P_k - x|; for each edge k -> k+1 add gamma_k n.(v_k x v_k+1)/|v_k x v_k+1|,
    # gamma_k the angle between v_k and v_k+1 in radians; F = |sum| / (2 pi).
    raise NotImplementedError("Task 1: point_to_polygon (formfactor.py)")


# ---------------------------------------------------------------------------------------------
# Task 2: an n x n Gauss-Legendre rule on a parallelogram
# ---------------------------------------------------------------------------------------------
def gauss_legendre_rule(polygon, n):
    """Points (n*n, 3) and weights (n*n,) of the tensor Gauss-Legendre rule on the
    parallelogram P0 P1 P2 P3; the weights sum to its area."""
    # TODO Task 2: numpy.polynomial.legendre.leggauss(n) gives nodes t and weights on [-1, 1];
    # map them to the parallelogram x = P0 + u e1 + v e2, e1 = P1 - P0, e2 = P3 - P0, u = (t+1)/2.
    raise NotImplementedError("Task 2: gauss_legendre_rule (formfactor.py)")


def polygon_normal(polygon):
    """Unit normal by the right-hand rule (Newell's method: exact for planar polygons)."""
    P = np.asarray(polygon, dtype=float)
    n = np.cross(P, np.roll(P, -1, axis=0)).sum(axis=0)
    return n / np.linalg.norm(n)


# ---------------------------------------------------------------------------------------------
# Task 3: the patch-to-patch form factor by quadrature over patch i
# ---------------------------------------------------------------------------------------------
def form_factor(polygon_i, polygon_j, n=8):
    """F_ij, the fraction of the light leaving patch i that arrives at patch j:
    (1/A_i) * integral over A_i of point_to_polygon(x, n_i, polygon_j) dA, with the n x n
    Gauss-Legendre rule on patch i (a parallelogram)."""
    # TODO Task 3: sum weight * point_to_polygon(point, normal of patch i, polygon_j) over the
    # rule's points on patch i (polygon_normal gives the normal), divided by the area of patch i.
    raise NotImplementedError("Task 3: form_factor (formfactor.py)")


# ---------------------------------------------------------------------------------------------
# Task 4: the catalogue's closed forms (Howell C-11 and C-14)
# ---------------------------------------------------------------------------------------------
def howell_c11(a, b, c):
    """F_12 between identical, parallel, directly opposed a x b rectangles at distance c."""
    # TODO Task 4: the closed form C-11 of README.md, X = a/c, Y = b/c.
    raise NotImplementedError("Task 4: howell_c11 (formfactor.py)")


def howell_c14(l, w, h):
    """F_12 from the l x w rectangle to the l x h rectangle, perpendicular with the common
    edge of length l."""
    # TODO Task 4: the closed form C-14 of README.md, W = w/l, H = h/l.
    raise NotImplementedError("Task 4: howell_c14 (formfactor.py)")


# ---------------------------------------------------------------------------------------------
# Task 5: a few-point rule as two patches approach
# ---------------------------------------------------------------------------------------------
def unit_squares(d):
    """Directly opposed unit squares at distance d, facing each other: (lower, upper)."""
    lower = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
    upper = [[0, 0, d], [0, 1, d], [1, 1, d], [1, 0, d]]
    return lower, upper


def near_field_errors(distances, n):
    """Relative error |F_n - F| / F of the n x n rule for unit squares at each distance, F from
    Howell C-11."""
    # TODO Task 5: for each d, form_factor(*unit_squares(d), n=n) against howell_c11(1, 1, d).
    raise NotImplementedError("Task 5: near_field_errors (formfactor.py)")
