"""Lab 5: reading the form-factor matrix. Fill in the three functions; README.md says what each
must return and why. F is (n, n), area (n,) and surface (n,) the surface index of each patch."""
import numpy as np


def surface_factors(F, area, surface):
    """The (S, S) matrix of surface-to-surface form factors F_ST."""
    raise NotImplementedError("Task 1: surface_factors (matrix.py)")


def row_deficit(F):
    """Per patch, the fraction of its light that reaches no patch of the scene."""
    raise NotImplementedError("Task 2: row_deficit (matrix.py)")


def reciprocity_error(F, area):
    """(largest, mean) relative reciprocity error, as defined in README.md."""
    raise NotImplementedError("Task 3: reciprocity_error (matrix.py)")
