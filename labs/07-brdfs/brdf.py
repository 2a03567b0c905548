"""Lab 7: a microfacet BRDF (GGX Cook-Torrance) and normalised Phong, in one file.

Local frame: z is the surface normal; directions are unit vectors as (..., 3) numpy arrays that
point away from the surface; functions work on whole arrays at once. README.md has the formulas.
"""
import numpy as np


def ggx_D(cos_h, alpha):
    """GGX (Trowbridge-Reitz) normal distribution D(h), per steradian of microfacet normal."""
    raise NotImplementedError("Task 1: ggx_D (brdf.py)")


def smith_lambda(cos_v, alpha):
    """Smith's Lambda for GGX."""
    raise NotImplementedError("Task 2: smith_lambda (brdf.py)")


def smith_G1(cos_v, alpha):
    """Smith's masking function G1 = 1 / (1 + Lambda)."""
    raise NotImplementedError("Task 2: smith_G1 (brdf.py)")


def cook_torrance(wo, wi, alpha):
    """D G2 / (4 cos_o cos_i), Fresnel 1, height-correlated G2; zero below the surface."""
    raise NotImplementedError("Task 4: cook_torrance (brdf.py)")


def phong(wo, wi, exponent, ks):
    """The energy-normalised Phong lobe about the mirror direction of wo; zero below."""
    raise NotImplementedError("Task 3: phong (brdf.py)")


def albedo(brdf, wo, samples, seed):
    """E(wo) = integral of brdf(wo, wi) cos(theta_i) dwi by Monte Carlo with `samples` samples
    from numpy.random.default_rng(seed): returns (estimate, standard error)."""
    raise NotImplementedError("Task 4: albedo (brdf.py)")
