"""Lab 7 reference solution: GGX Cook-Torrance and normalised Phong in local frames (z = normal).
Directions are unit vectors as (..., 3) arrays pointing away from the surface."""
import numpy as np


def ggx_D(cos_h, alpha):
    """GGX (Trowbridge-Reitz) normal distribution D(h), per steradian of microfacet normal."""
    c2 = cos_h * cos_h
    return alpha ** 2 / (np.pi * (c2 * (alpha ** 2 - 1) + 1) ** 2)


def smith_lambda(cos_v, alpha):
    """Smith's Lambda for GGX: (sqrt(1 + alpha^2 tan^2) - 1) / 2."""
    c2 = cos_v * cos_v
    return (np.sqrt(1 + alpha ** 2 * (1 - c2) / c2) - 1) / 2


def smith_G1(cos_v, alpha):
    return 1 / (1 + smith_lambda(cos_v, alpha))


def cook_torrance(wo, wi, alpha):
    """D G2 / (4 cos_o cos_i) with Fresnel 1 and height-correlated G2 = 1 / (1 + L(o) + L(i))."""
    co, ci = wo[..., 2], wi[..., 2]
    h = wo + wi
    h = h / np.linalg.norm(h, axis=-1, keepdims=True)
    g2 = 1 / (1 + smith_lambda(co, alpha) + smith_lambda(ci, alpha))
    return np.where((co > 0) & (ci > 0), ggx_D(h[..., 2], alpha) * g2 / (4 * co * ci), 0.0)


def phong(wo, wi, exponent, ks):
    """Energy-normalised Phong lobe ks (n + 2) / (2 pi) cos^n(angle to the mirror direction)."""
    mirror = wo * np.array([-1.0, -1.0, 1.0])
    c = np.clip(np.sum(mirror * wi, axis=-1), 0, None)
    return np.where(wi[..., 2] > 0, ks * (exponent + 2) / (2 * np.pi) * c ** exponent, 0.0)


def albedo(brdf, wo, samples, seed):
    """E(wo) = integral of f(wo, wi) cos(theta_i) over the hemisphere, by Monte Carlo with
    cosine-weighted wi (pdf cos/pi): the mean of pi f. Returns (estimate, standard error)."""
    rng = np.random.default_rng(seed)
    u1, u2 = rng.random(samples), rng.random(samples)
    r, phi = np.sqrt(u1), 2 * np.pi * u2
    wi = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(1 - u1)], axis=-1)
    x = np.pi * brdf(np.broadcast_to(wo, wi.shape), wi)
    return float(x.mean()), float(x.std(ddof=1) / np.sqrt(samples))
