"""Lab 6: photon mapping against radiosity. README.md gives the physics; write the five
functions below and run `labs/check 6` until it passes.

Photons come from radkit.photon_map(mesh, photons=N, seed=s): positions (m, 3), power (m, 3)
in W, patch (m,) and path (m,), the emitted photon that left each one; areas (mesh.area) are
m².
"""
import numpy as np
from scipy.spatial import cKDTree  # noqa: F401  (Task 1 wants it)


def irradiance_estimate(positions, power, points, k):
    """Task 1: the k-nearest-photon estimate of irradiance at each of the q points.

    r is the distance from the point to its k-th nearest photon; every photon p among the k
    nearest counts with the Epanechnikov weight K(d_p) = 2 / (pi r^2) * (1 - d_p^2 / r^2), so
    E = sum_p K(d_p) power_p (the k-th photon has weight 0).
    positions (m, 3), power (m, 3), points (q, 3). Returns (E (q, 3), r (q,)).
    """
    # TODO: a cKDTree over positions; its query(points, k) gives distances and indices.
    raise NotImplementedError("Task 1: irradiance_estimate, the k-nearest-photon estimate")


def patch_tally(patch, path, power, area, paths):
    """Task 2: the photon tally of each patch's mean irradiance and its standard error.

    H_i = (sum of the power of the photons on patch i) / A_i. The draws are the `paths` emitted
    photons, not the stored ones: X_ji is the power path j left on patch i (0 for most paths),
    and Var(sum_j X_ji) = N/(N-1) * (sum_j X_ji^2 - (sum_j X_ji)^2 / N) with N = paths.
    patch, path (m,) ints; power (m, 3); area (n,). Returns (H (n, 3), standard error (n, 3)).
    """
    # TODO: sum the power per (path, patch) first, then per patch.
    raise NotImplementedError("Task 2: patch_tally, per-patch irradiance and its standard error")


def knn_bias(laplacian, r2):
    """Task 3a: the leading term of E[estimate] - E(x) for the Epanechnikov kernel of radius r,
    when E is smooth near x with Laplacian `laplacian` (README.md, "Bias"). r2 = r^2.
    Works elementwise on numpy arrays."""
    # TODO: expand E to second order about x and integrate against the kernel.
    raise NotImplementedError("Task 3a: knn_bias, the kernel's bias from the Laplacian")


def knn_relative_variance(k):
    """Task 3b: Var[estimate] / E^2 for k nearest photons of a uniform Poisson density (README.md,
    "Variance"), exact for every k > 2. Works elementwise on numpy arrays."""
    # TODO: the estimate over E is S / G; use the independence of S and G.
    raise NotImplementedError("Task 3b: knn_relative_variance, the estimate's relative variance")


def optimal_k(photons, laplacian, irradiance, total_power):
    """Task 4: the k that minimises the relative mean squared error
    (knn_bias / E)^2 + knn_relative_variance(k) at a point with irradiance E and Laplacian
    `laplacian`, when `photons` photons carry `total_power` W (each total_power / photons) and
    r^2 is the expected value that gathers k of them (README.md, "The best k")."""
    # TODO: r^2 in terms of k; then minimise (numerically, or in closed form for large k).
    raise NotImplementedError("Task 4: optimal_k, where bias and variance balance")
