# Mie theory a second way, for the numbers tests/media checks (docs/media.md): coefficients from
# scipy's spherical Bessel functions (complex argument, no logarithmic-derivative recurrence),
# angular functions from scipy's associated Legendre functions; a different code path from
# phase/mie.cpp. Run: /usr/bin/python3 scripts/mie-crosscheck.py
import numpy as np
from scipy.special import spherical_jn, spherical_yn
import sys

def coeffs(m, x):
    nmax = max(1, int(x + 4 * x ** (1 / 3) + 2))  # truncated, as the C++
    n = np.arange(1, nmax + 1)
    mx = m * x
    jx, djx = spherical_jn(n, x), spherical_jn(n, x, derivative=True)
    yx, dyx = spherical_yn(n, x), spherical_yn(n, x, derivative=True)
    jm, djm = spherical_jn(n, mx), spherical_jn(n, mx, derivative=True)
    psi, dpsi = x * jx, jx + x * djx
    xi, dxi = x * (jx + 1j * yx), (jx + 1j * yx) + x * (djx + 1j * dyx)
    psim, dpsim = mx * jm, jm + mx * djm
    a = (m * psim * dpsi - psi * dpsim) / (m * psim * dxi - xi * dpsim)
    b = (psim * dpsi - m * psi * dpsim) / (psim * dxi - m * xi * dpsim)
    return n, a, b

def mie(m, x):
    n, a, b = coeffs(m, x)
    qext = 2 / x**2 * np.sum((2 * n + 1) * (a + b).real)
    qsca = 2 / x**2 * np.sum((2 * n + 1) * (abs(a)**2 + abs(b)**2))
    g = 4 / x**2 / qsca * (np.sum(n[:-1] * (n[:-1] + 2) / (n[:-1] + 1) *
        (a[:-1] * a[1:].conj() + b[:-1] * b[1:].conj()).real) +
        np.sum((2 * n + 1) / (n * (n + 1)) * (a * b.conj()).real))
    return qext, qsca, g, n, a, b

def phase(m, x, mu):
    # p from Legendre-derived pi_n, tau_n via scipy's lpmn-free direct recurrence in closed form
    qext, qsca, g, n, a, b = mie(m, x)
    from scipy.special import lpmv
    S1 = np.zeros(len(mu), complex); S2 = np.zeros(len(mu), complex)
    s = np.sqrt(np.maximum(1 - mu**2, 1e-300))
    for k in range(len(n)):
        nn = n[k]
        P1 = lpmv(1, nn, mu)  # associated Legendre with Condon-Shortley phase
        pin = -P1 / s
        # tau_n = d P_n^1 / d theta: from the identity tau = n mu pi_n - (n+1) pi_{n-1}
        pinm1 = -lpmv(1, nn - 1, mu) / s if nn > 1 else np.zeros_like(mu)
        taun = nn * mu * pin - (nn + 1) * pinm1
        f = (2 * nn + 1) / (nn * (nn + 1))
        S1 += f * (a[k] * pin + b[k] * taun); S2 += f * (a[k] * taun + b[k] * pin)
    return (abs(S1)**2 + abs(S2)**2) / (2 * np.pi * x**2 * qsca)

if __name__ == "__main__":
    for m, x in [(1.55, 5.21282), (1.55, 2*np.pi*0.525/0.6328), (1.33, 0.01), (1.333, 2*np.pi*10/0.55),
                 (1.333, 1000.0), (1.5+0.1j, 10.0), (1.333, 1.0)]:
        qe, qs, g, *_ = mie(m, x)
        print(f"m={m} x={x:.6f} Qext={qe:.6f} Qsca={qs:.6f} Qabs={qe-qs:.2e} g={g:.6f}")
    mu = np.array([1.0 - 1e-9, 0.5, 0.0, -0.5, -1 + 1e-9])
    print("phase m=1.55 x=5.21282", phase(1.55, 5.21282, mu))
    print("phase m=1.5+0.1i x=10", phase(1.5+0.1j, 10.0, mu))
    x = 0.01; mm = 1.33
    print("rayleigh Qsca", 8/3*x**4*abs((mm**2-1)/(mm**2+2))**2)
