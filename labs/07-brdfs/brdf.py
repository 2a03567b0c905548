"""Lab 7: a microfacet BRDF (GGX Cook-Torrance) and normalised Phong, in one file. Fill in the
six tasks (README.md has the formulas); labs/check 7 tells you what is still wrong.

Local frame: z is the surface normal; directions are unit vectors as (..., 3) numpy arrays that
point away from the surface; functions work on whole arrays at once.
"""
import numpy as np


def ggx_D(cos_h, alpha):
    """GGX (Trowbridge-Reitz) normal distribution D(h), per steradian of microfacet normal."""
    # TODO Task 1: D(h) of README.md, from cos(theta_h) and alpha.
    raise NotImplementedError("Task 1: ggx_D (brdf.py)")


def smith_lambda(cos_v, alpha):
    """Smith's Lambda for GGX."""
    # TODO Task 2: Lambda(v) of README.md; tan^2 theta = (1 - cos^2) / cos^2.
    raise NotImplementedError("Task 2: smith_lambda (brdf.py)")


def smith_G1(cos_v, alpha):
    """Smith's masking function G1 = 1 / (1 + Lambda)."""
    # TODO Task 3: from smith_lambda.
    raise NotImplementedError("Task 3: smith_G1 (brdf.py)")


def phong(wo, wi, exponent, ks):
    """The energy-normalised Phong lobe about the mirror direction of wo; zero below."""
    # TODO Task 4: ks (n + 2) / (2 pi) cos^n(alpha), alpha between wi and the mirror of wo.
    raise NotImplementedError("Task 4: phong (brdf.py)")


def cook_torrance(wo, wi, alpha):
    """D G2 / (4 cos_o cos_i), Fresnel 1, height-correlated G2; zero below the surface."""
    # TODO Task 5: h = (wo + wi) / |wo + wi|; G2 = 1 / (1 + Lambda(o) + Lambda(i)).
    raise NotImplementedError("Task 5: cook_torrance (brdf.py)")


def albedo(brdf, wo, samples, seed):
    """E(wo) = integral of brdf(wo, wi) cos(theta_i) dwi by Monte Carlo with `samples` samples
    from numpy.random.default_rng(seed): returns (estimate, standard error)."""
    # TODO Task 6: draw wi with a density p (cosine-weighted is simplest), average
    # brdf(wo, wi) cos(theta_i) / p(wi); the standard error is the samples' std / sqrt(samples).
    raise NotImplementedError("Task 6: albedo (brdf.py)")
