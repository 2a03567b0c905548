"""Lab 1: form factors by hand. Reference solution.

Polygons are (k, 3) arrays of vertices, counter-clockwise seen from their front side (the side
their normal points to). `labs/01-form-factors/study.py --dir labs/instructor/solutions/01-form-factors`
runs the study on it.
"""
import math

import numpy as np


# ---------------------------------------------------------------------------------------------
# Task 1: the point-to-polygon form factor (Lambert's contour formula)
# ---------------------------------------------------------------------------------------------
def point_to_polygon(x, normal, polygon):
    """Form factor from a differential area at x with unit normal `normal` to the polygon,
    which must lie wholly in front of x (no clipping here)."""
    x = np.asarray(x, dtype=float)
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    v = np.asarray(polygon, dtype=float) - x
    v /= np.linalg.norm(v, axis=1)[:, None]          # unit vectors towards the vertices
    w = np.roll(v, -1, axis=0)                       # v_{k+1}
    c = np.cross(v, w)
    s = np.linalg.norm(c, axis=1)                    # sin(gamma_k)
    gamma = np.arctan2(s, np.einsum("ij,ij->i", v, w))  # angle, accurate for small gamma too
    # An edge whose line passes through x contributes nothing (gamma = 0 or its plane is n's).
    term = np.divide(gamma * (c @ n), s, out=np.zeros_like(s), where=s > 0)
    # The sum is negative when the polygon faces x (its vertices then run clockwise seen from
    # x); the magnitude is the projected solid angle over pi.
    return abs(term.sum()) / (2.0 * math.pi)


# ---------------------------------------------------------------------------------------------
# Task 2: an n x n Gauss-Legendre rule on a parallelogram
# ---------------------------------------------------------------------------------------------
def gauss_legendre_rule(polygon, n):
    """Points (n*n, 3) and weights (n*n,) of the tensor Gauss-Legendre rule on the
    parallelogram P0 P1 P2 P3; the weights sum to its area."""
    P = np.asarray(polygon, dtype=float)
    if len(P) != 4 or not np.allclose(P[0] + P[2], P[1] + P[3]):
        raise ValueError("gauss_legendre_rule: the polygon must be a parallelogram P0 P1 P2 P3")
    e1, e2 = P[1] - P[0], P[3] - P[0]
    t, w = np.polynomial.legendre.leggauss(n)
    u, wu = (t + 1.0) / 2.0, w / 2.0                 # [-1, 1] -> [0, 1]: the weights halve
    a, b = np.meshgrid(u, u, indexing="ij")
    points = P[0] + a.reshape(-1, 1) * e1 + b.reshape(-1, 1) * e2
    weights = np.outer(wu, wu).ravel() * np.linalg.norm(np.cross(e1, e2))
    return points, weights


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
    points, weights = gauss_legendre_rule(polygon_i, n)
    normal = polygon_normal(polygon_i)
    values = np.array([point_to_polygon(x, normal, polygon_j) for x in points])
    return float(weights @ values / weights.sum())


# ---------------------------------------------------------------------------------------------
# Task 4: the catalogue's closed forms (Howell C-11 and C-14)
# ---------------------------------------------------------------------------------------------
def howell_c11(a, b, c):
    """F_12 between identical, parallel, directly opposed a x b rectangles at distance c."""
    X, Y = a / c, b / c
    x1, y1 = math.sqrt(1 + X * X), math.sqrt(1 + Y * Y)
    return 2.0 / (math.pi * X * Y) * (
        math.log(x1 * y1 / math.sqrt(1 + X * X + Y * Y))
        + X * y1 * math.atan(X / y1) + Y * x1 * math.atan(Y / x1)
        - X * math.atan(X) - Y * math.atan(Y))


def howell_c14(l, w, h):
    """F_12 from the l x w rectangle to the l x h rectangle, perpendicular with the common
    edge of length l."""
    W, H = w / l, h / l
    W2, H2 = W * W, H * H
    R2 = W2 + H2
    R = math.sqrt(R2)
    log_term = (math.log((1 + W2) * (1 + H2) / (1 + R2))
                + W2 * math.log(W2 * (1 + R2) / ((1 + W2) * R2))
                + H2 * math.log(H2 * (1 + R2) / ((1 + H2) * R2)))
    return (W * math.atan(1 / W) + H * math.atan(1 / H) - R * math.atan(1 / R)
            + 0.25 * log_term) / (math.pi * W)


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
    errors = []
    for d in distances:
        exact = howell_c11(1.0, 1.0, d)
        errors.append(abs(form_factor(*unit_squares(d), n=n) - exact) / exact)
    return np.array(errors)
