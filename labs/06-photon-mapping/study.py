"""Lab 6's study, written for you: once photons.py passes `labs/check 6`, run

    python3 labs/06-photon-mapping/study.py [--dir DIR] [--out DIR] [--runs R]

to print the tables of README.md and draw photon-mapping.png; hand in its output.
"""
import argparse
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True  # importing the student's file leaves no __pycache__ there
LAB = Path(__file__).resolve().parent
sys.path.insert(0, str(LAB.parent))
sys.path.insert(0, str(LAB))
from pyradkit import import_radkit, load_student, run_study, save_figure  # noqa: E402
from check_lab import lamp_irradiance, lamp_laplacian  # noqa: E402

GAUSS = np.polynomial.legendre.leggauss(6)


def patch_means(mesh):
    """The closed form averaged over each floor patch (6 x 6 Gauss-Legendre on its bilinear
    map; patches of the floor are parallelograms)."""
    x, w = GAUSS
    out = np.zeros(len(mesh))
    V, idx = mesh.vertices, mesh.patch_vertices
    for i in range(len(mesh)):
        c = V[idx[i][idx[i] >= 0]]
        if len(c) != 4:
            raise SystemExit("study.py expects quadrilateral floor patches")
        total = 0.0
        for a, wa in zip(x, w):
            for b, wb in zip(x, w):
                s, t = (a + 1) / 2, (b + 1) / 2
                p = ((1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2]
                     + (1 - s) * t * c[3])
                total += wa * wb * lamp_irradiance(p[0], p[1])
        out[i] = total / 4
    return out


def main():
    parser = argparse.ArgumentParser(description="Lab 6: photon mapping against radiosity")
    parser.add_argument("--dir", default=str(LAB), help="folder with your photons.py")
    parser.add_argument("--out", default=".", help="folder for photon-mapping.png")
    parser.add_argument("--runs", type=int, default=64, help="independent runs per photon count")
    args = parser.parse_args()
    rk = import_radkit(6)
    lab = load_student(args.dir, "photons.py")
    scene = rk.load_scene(str(LAB / "lamp.json"))
    E0, lap = lamp_irradiance(0, 0), lamp_laplacian()
    centre = np.zeros((1, 3))

    # A. Bias, variance and error of the estimate at the floor's centre against k and N.
    print(f"A. lamp.json, the floor's centre: E = {E0:.6f} W/m^2 (Howell B-3), Laplacian "
          f"{lap:.4f} W/m^4; {args.runs} runs per photon count; relative figures")
    print(f"{'N':>7s} {'k':>5s} {'r (m)':>7s} {'bias':>8s} {'+-':>7s} {'theory':>8s} "
          f"{'std':>7s} {'theory':>7s} {'rmse':>7s} {'theory':>7s}")
    coarse = rk.mesh(scene, patches=16)
    curves, best = {}, []
    for N in (10000, 40000, 160000):
        ks = [k for k in (5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000)
              if k <= N // 5]
        est = np.zeros((args.runs, len(ks)))
        r2 = np.zeros_like(est)
        for s in range(args.runs):
            pm = rk.photon_map(coarse, photons=N, seed=1 + s)
            near = np.hypot(pm.positions[:, 0], pm.positions[:, 1]) < 0.9  # r stays below 0.6
            P, W = pm.positions[near], pm.power[near]
            for j, k in enumerate(ks):
                E, r = lab.irradiance_estimate(P, W, centre, k)
                est[s, j], r2[s, j] = np.asarray(E)[0, 0] / E0, float(np.asarray(r)[0]) ** 2
        bias = est.mean(axis=0) - 1
        bias_se = est.std(axis=0, ddof=1) / math.sqrt(args.runs)
        std = est.std(axis=0, ddof=1)
        rmse = np.sqrt(np.mean((est - 1) ** 2, axis=0))
        theory_bias = np.array([lab.knn_bias(lap, k / (N * math.pi * E0)) / E0 for k in ks])
        theory_std = np.sqrt([lab.knn_relative_variance(k) for k in ks])
        theory_rmse = np.hypot(theory_bias, theory_std)
        for j, k in enumerate(ks):
            print(f"{N:7d} {k:5d} {math.sqrt(r2[:, j].mean()):7.4f} {bias[j]:+8.4f} "
                  f"{bias_se[j]:7.4f} {theory_bias[j]:+8.4f} {std[j]:7.4f} {theory_std[j]:7.4f} "
                  f"{rmse[j]:7.4f} {theory_rmse[j]:7.4f}")
        k_opt = lab.optimal_k(N, lap, E0, 1.0)
        measured = ks[int(np.argmin(rmse))]
        best.append((N, k_opt, measured))
        curves[N] = (np.array(ks), rmse, theory_rmse, k_opt)
    print(f"\n{'N':>7s} {'optimal_k':>10s} {'best k measured':>16s}")
    for N, k_opt, measured in best:
        print(f"{N:7d} {k_opt:10.0f} {measured:16d}")
    Ns = np.array([b[0] for b in best], dtype=float)
    slope = np.polyfit(np.log(Ns), np.log([b[1] for b in best]), 1)[0]
    print(f"log-log slope of optimal_k against N: {slope:.3f} (2/3 from the theory)")

    # B. The same floor by radiosity, by the photon tally and by the estimate at k = optimal_k.
    mesh = rk.mesh(scene, patches=400)
    floor = mesh.surface == scene.surface_names.index("floor")
    system = rk.System(rk.form_factors(mesh))
    B = rk.solve(system, "gauss-seidel", tolerance=1e-10)["radiosity"]
    rho = mesh.reflectance[:, 0]
    H_radiosity = np.where(floor, (B[:, 0] - mesh.emission[:, 0]) / np.where(floor, rho, 1), 0)
    exact = np.zeros(len(mesh))
    exact[floor] = patch_means(_Sub(mesh, floor))
    N = 160000
    pm = rk.photon_map(mesh, photons=N, seed=1)
    H, se = lab.patch_tally(pm.patch, pm.path, pm.power, mesh.area, N)
    H, se = np.asarray(H)[:, 0], np.asarray(se)[:, 0]
    z = (H[floor] - exact[floor]) / se[floor]
    k = int(round(lab.optimal_k(N, lap, E0, 1.0)))
    knn, radius = lab.irradiance_estimate(pm.positions, pm.power, mesh.centroid[floor], k)
    knn = np.asarray(knn)[:, 0]
    point = np.array([lamp_irradiance(x, y) for x, y, _ in mesh.centroid[floor]])
    edge = 2 - np.abs(mesh.centroid[floor][:, :2]).max(axis=1) < np.asarray(radius)
    print(f"\nB. lamp.json, {floor.sum()} floor patches of {mesh.area[floor][0]:.4f} m^2")
    print(f"radiosity (form factors + Gauss-Seidel to 1e-10): largest relative error of the "
          f"patch means {np.max(np.abs(H_radiosity[floor] / exact[floor] - 1)):.2e}")
    print(f"photon tally, N = {N}: |z| > 2 on {np.mean(np.abs(z) > 2):.1%} of patches (4.6 % for "
          f"a normal z), largest |z| {np.abs(z).max():.2f}, median relative SE "
          f"{np.median(se[floor] / exact[floor]):.3f}")
    rel = knn / point - 1
    print(f"k-nearest estimate at k = {k} (optimal_k at the centre) against E at the centroids: "
          f"RMS {np.sqrt(np.mean(rel[~edge] ** 2)):.3f} on {np.sum(~edge)} patches farther than "
          f"r from the floor's edge, {np.sqrt(np.mean(rel[edge] ** 2)):.3f} (mean "
          f"{rel[edge].mean():+.3f}) on the {edge.sum()} within r")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is missing: no figure (Debian: python3-matplotlib)")
        return
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for N, (ks, rmse, theory, k_opt) in curves.items():
        line, = a.loglog(ks, rmse, "o", label=f"N = {N} measured")
        a.loglog(ks, theory, "-", color=line.get_color(), label="theory")
        a.axvline(k_opt, color=line.get_color(), ls=":", lw=1)
    a.set_xlabel("k (nearest photons)")
    a.set_ylabel("relative RMS error at the centre")
    a.set_title("bias against variance (dotted: optimal_k)")
    a.legend(fontsize=7)
    row = floor & (np.abs(mesh.centroid[:, 1] - mesh.centroid[floor][np.argmin(
        np.abs(mesh.centroid[floor][:, 1])), 1]) < 1e-9)
    xs = np.linspace(-2, 2, 401)
    yrow = mesh.centroid[row][0, 1]
    b.plot(xs, [lamp_irradiance(x, yrow) for x in xs], "k-", lw=1, label="closed form")
    order = np.argsort(mesh.centroid[row][:, 0])
    cx = mesh.centroid[row][order, 0]
    b.step(cx, H_radiosity[row][order], where="mid", label="radiosity (patch means)")
    b.errorbar(cx, H[row][order], yerr=2 * se[row][order], fmt=".", ms=4,
               label=f"photon tally +- 2 SE, N = {N}")
    on_row = row[floor]
    b.plot(mesh.centroid[floor][on_row][:, 0], knn[on_row], "x", ms=5,
           label=f"k-nearest, k = {k}")
    b.set_xlabel(f"x (m), along y = {yrow:.2f}")
    b.set_ylabel("irradiance (W/m^2)")
    b.set_title("the floor: radiosity, tally and density estimate")
    b.legend(fontsize=7)
    save_figure(fig, args.out, "photon-mapping.png", dpi=110)


class _Sub:
    """The floor patches of a mesh, as patch_means wants them."""
    def __init__(self, mesh, on):
        self.vertices, self.patch_vertices = mesh.vertices, mesh.patch_vertices[on]

    def __len__(self):
        return len(self.patch_vertices)


if __name__ == "__main__":
    run_study(main, 6)
