"""Lab 8's geometry, written for you (not a file you edit): the two unit squares of
data/parallel-squares.json and their quadtrees, the exact factor from a floor point to a lamp
element, the floor's exact radiosity, and the L1 error that the study and the check measure.

The scene: a floor ("lower", z = 0, facing up, reflectance 0.5) under a lamp ("upper", z = 1,
facing down, black, emitting 1 W/m²), both the unit square [0, 1]². The lamp reflects nothing,
so its radiosity is E everywhere and the floor's is exactly B(x) = ρ E F(x → lamp): Howell B-3
at every point, Howell C-11 for the floor's mean.
"""
import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.integrate import fixed_quad

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # labs/, for pyradkit
from pyradkit import howell_b3  # noqa: E402

RHO = 0.5          # the floor's reflectance ("grey" in data/parallel-squares.json)
EMISSION = 1.0     # the lamp's exitance, W/m² (its radiosity too: it is black)
HEIGHT = 1.0       # the lamp above the floor
MIN_SIZE = 1 / 256  # elements are not split below this side (radkit: --min-area)
# Howell C-11 at X = Y = 1 (docs/oracles.md): F between the unit squares one apart.
C11 = 0.19982489569838746


@dataclass(frozen=True)
class Square:
    """An element of the quadtree on one of the squares: [x0, x0 + size] x [y0, y0 + size] on
    the floor ("lower") or on the lamp ("upper"). Sizes are powers of 1/2, so every coordinate
    is exact in binary and equal elements compare (and hash) equal."""
    surface: str
    x0: float
    y0: float
    size: float

    @property
    def area(self):
        return self.size * self.size

    @property
    def centre(self):
        return self.x0 + self.size / 2, self.y0 + self.size / 2

    @property
    def level(self):
        """Splits below the whole square (0 for the square itself)."""
        return round(-math.log2(self.size))

    def children(self):
        """The four quarters, which tile this element."""
        h = self.size / 2
        return [Square(self.surface, self.x0 + i * h, self.y0 + j * h, h)
                for j in (0, 1) for i in (0, 1)]

    def parent(self):
        """The element this one is a quarter of (None for the whole square)."""
        if self.size >= 1:
            return None
        s = 2 * self.size
        return Square(self.surface, math.floor(self.x0 / s) * s, math.floor(self.y0 / s) * s, s)

    def contains(self, other):
        """Whether `other` (an element of the same square) lies inside this one."""
        return (other.surface == self.surface and self.x0 <= other.x0 and self.y0 <= other.y0
                and other.x0 + other.size <= self.x0 + self.size
                and other.y0 + other.size <= self.y0 + self.size)


FLOOR = Square("lower", 0.0, 0.0, 1.0)
LAMP = Square("upper", 0.0, 0.0, 1.0)


def point_factor(x, y, s):
    """F from the floor point (x, y), facing up, to the lamp element s, HEIGHT above: exact
    (Lambert's contour integral has this closed form for parallel rectangles). Howell B-3 is
    odd in both sides, so the four corners of s summed with signs give any rectangle."""
    x1, y1 = s.x0 + s.size, s.y0 + s.size
    return (howell_b3(x1 - x, y1 - y, HEIGHT) - howell_b3(s.x0 - x, y1 - y, HEIGHT)
            - howell_b3(x1 - x, s.y0 - y, HEIGHT) + howell_b3(s.x0 - x, s.y0 - y, HEIGHT))


def sample_points(r):
    """The 3 x 3 points where the oracle looks at F over the receiver r: its corners, the
    middles of its edges and its centre."""
    return [(r.x0 + i * r.size / 2, r.y0 + j * r.size / 2) for j in range(3) for i in range(3)]


def exact_radiosity(x, y):
    """The floor's radiosity at (x, y) in W/m², ρ E F(x → lamp); numpy arrays work too."""
    f = np.vectorize(lambda px, py: point_factor(px, py, LAMP), otypes=[float])(x, y)
    return RHO * EMISSION * f


def quadtree_leaves(elements, root):
    """The leaves of the quadtree on `root` that the given elements make. Each element and its
    ancestors are nodes, a node with a node below it is split into all four quarters, and the
    leaves are the nodes left whole: they tile the square. Sorted by (y0, x0)."""
    split = set()
    for e in elements:
        node = e.parent()
        while node is not None and node not in split:
            split.add(node)
            node = node.parent()
    leaves, todo = [], [root]
    while todo:
        node = todo.pop()
        if node in split:
            todo.extend(node.children())
        else:
            leaves.append(node)
    return sorted(leaves, key=lambda e: (e.y0, e.x0))


def floor_leaves(links):
    """The floor's leaves for a list of links (r, s): the quadtree_leaves of the receivers."""
    return quadtree_leaves([r for r, _ in links], FLOOR)


def _integrate(f, square, cells, n):
    """∫ f(x, y) dA over a floor square, f vectorised: cells x cells equal cells, an n x n
    Gauss-Legendre rule on each. scipy's fixed_quad makes the rule on one cell [0, h]², in u
    inside t; the other cells are its translates, summed inside the integrand (one call of f
    per square)."""
    h = square.size / cells
    shift = h * np.arange(cells)
    x0 = square.x0 + shift[:, None, None, None]   # cell i, cell j, point in t, point in u
    y0 = square.y0 + shift[None, :, None, None]

    def over_u(t):  # fixed_quad sums over the last axis: u, for every t at once
        return fixed_quad(lambda u: f(x0 + t[:, None], y0 + u[None, :]).sum(axis=(0, 1)),
                          0.0, h, n=n)[0]
    return float(fixed_quad(over_u, 0.0, h, n=n)[0])


def leaf_mean(square):
    """The exact mean of the floor's radiosity over a floor square (ρ E F from the square to
    the lamp): 8 x 8 Gauss-Legendre points, good to 1e-10 relative for any square here (the
    lamp is a whole side away)."""
    return _integrate(exact_radiosity, square, 1, 8) / square.area


def l1_error(leaves, cells=4, n=3):
    """∫ |B_h(x) − B(x)| dA over the floor, in W, for the piecewise-constant radiosity
    B_h = B on each (Square, B) of `leaves` (which must tile the floor), against the exact
    B(x). |·| has a kink where B_h crosses B, so a composite rule: cells x cells Gauss points
    n x n per leaf (relative accuracy about 1e-3 at the defaults)."""
    total = 0.0
    for square, b in leaves:
        total += _integrate(lambda x, y: np.abs(b - exact_radiosity(x, y)), square, cells, n)
    return total
