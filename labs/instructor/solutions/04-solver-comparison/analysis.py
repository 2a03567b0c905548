"""Lab 4 reference solution: how fast the iterative solvers converge, and why."""
import numpy as np


def convergence_factor(history, tail=0.5):
    """Residual reduction per sweep: exp of the least-squares slope of log(residual) against
    sweeps over the last `tail` fraction of the history (the asymptotic rate, not the start)."""
    sweeps = np.asarray(history["sweeps"], dtype=float)
    residual = np.asarray(history["residual"], dtype=float)
    keep = (sweeps >= sweeps[-1] * (1 - tail)) & (residual > 0)
    slope = np.polyfit(sweeps[keep], np.log(residual[keep]), 1)[0]
    return float(np.exp(slope))


def spectral_radius(F, rho):
    """Spectral radius of Jacobi's iteration matrix diag(rho_c) F, largest over the channels."""
    return max(float(np.abs(np.linalg.eigvals(rho[:, c, None] * F)).max())
               for c in range(rho.shape[1]))


def young_omega(rho_jacobi):
    """Young's optimal SOR parameter for a consistently ordered matrix."""
    return 2.0 / (1.0 + np.sqrt(1.0 - rho_jacobi ** 2))


def best_omega(solve_sweeps, omegas):
    """The omega of `omegas` with the fewest sweeps; solve_sweeps(omega) returns the sweeps."""
    sweeps = [solve_sweeps(w) for w in omegas]
    return float(omegas[int(np.argmin(sweeps))])
