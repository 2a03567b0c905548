"""Lab 5 reference solution: reading the form-factor matrix."""
import numpy as np


def surface_factors(F, area, surface):
    """F_ST = sum_{i in S} A_i sum_{j in T} F_ij / A_S for every pair of surfaces, (S, S)."""
    count = int(surface.max()) + 1
    member = np.zeros((len(area), count))
    member[np.arange(len(area)), surface] = 1.0  # patch-to-surface incidence
    power = (area[:, None] * F) @ member         # A_i F_iT: row i's flux fraction to surface T
    return (member.T @ power) / (member.T @ area)[:, None]


def row_deficit(F):
    """1 - sum_j F_ij per patch: the fraction of a patch's light that leaves the scene."""
    return 1.0 - F.sum(axis=1)


def reciprocity_error(F, area):
    """(largest, mean) relative reciprocity error over the pairs with A_i F_ij or A_j F_ji > 0:
    |A_i F_ij - A_j F_ji| / max(A_i F_ij, A_j F_ji), and sum |diff| / sum (A_i F_ij + A_j F_ji)."""
    flux = area[:, None] * F
    upper = np.triu_indices(len(area), k=1)
    a, b = flux[upper], flux.T[upper]
    both = np.maximum(np.abs(a), np.abs(b))
    diff = np.abs(a - b)
    used = both > 0
    return float((diff[used] / both[used]).max(initial=0.0)), float(diff.sum() / (np.abs(a) + np.abs(b)).sum())
