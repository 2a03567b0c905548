"""Lab 4: how fast the iterative solvers converge, and why. Fill in the four functions.

The check imports them; README.md says what each must return.
"""
import numpy as np


def convergence_factor(history, tail=0.5):
    """Residual reduction per sweep over the last `tail` fraction of a solve's history.

    history: the "history" dict of radkit.solve (numpy arrays "residual", "sweeps", ...).
    """
    raise NotImplementedError("Task 1: convergence_factor (analysis.py)")


def spectral_radius(F, rho):
    """Spectral radius of Jacobi's iteration matrix diag(rho_c) F, largest over the channels.

    F: (n, n); rho: (n, 3).
    """
    raise NotImplementedError("Task 2: spectral_radius (analysis.py)")


def young_omega(rho_jacobi):
    """Young's optimal SOR parameter omega for a consistently ordered matrix whose Jacobi
    iteration has spectral radius rho_jacobi."""
    raise NotImplementedError("Task 3: young_omega (analysis.py)")


def best_omega(solve_sweeps, omegas):
    """The omega in `omegas` for which solve_sweeps(omega) (the sweeps SOR needs) is smallest."""
    raise NotImplementedError("Task 4: best_omega (analysis.py)")
