"""The radkit Python module against closed forms (docs/oracles.md) and against itself.

Run from the build: PYTHONPATH=build/python python3 -m pytest python/tests (ctest does this).
"""
import json
import math
import os
import subprocess
import warnings

import numpy as np
import pytest
import scipy.sparse

import radkit

DATA = os.environ.get("RADKIT_DATA_DIR",
                      os.path.join(os.path.dirname(__file__), "..", "..", "data"))

# Howell C-11, unit squares one apart (X = Y = 1), and C-14, unit squares sharing an edge
# (W = H = 1): docs/oracles.md.
C11 = 0.19982489569838746
C14 = 0.20004377607540316


def c11(x, y):
    """Howell C-11: identical, directly opposed parallel rectangles (X = a/c, Y = b/c)."""
    return 2 / (math.pi * x * y) * (
        math.log(math.sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)))
        + x * math.sqrt(1 + y * y) * math.atan(x / math.sqrt(1 + y * y))
        + y * math.sqrt(1 + x * x) * math.atan(y / math.sqrt(1 + x * x))
        - x * math.atan(x) - y * math.atan(y))


def surface_factor(mesh, F, a, b):
    """F from surface a to surface b: sum over their patches of A_i F_ij, over A_a."""
    area, surface = mesh.area, mesh.surface
    ia, ib = surface == a, surface == b
    return float(area[ia] @ F[np.ix_(ia, ib)].sum(axis=1) / area[ia].sum())


@pytest.fixture(scope="module")
def squares():
    scene = radkit.load_scene(os.path.join(DATA, "parallel-squares.json"))
    mesh = radkit.mesh(scene, patches=50)
    return scene, mesh, radkit.form_factors(mesh)


@pytest.fixture(scope="module")
def furnace():
    mesh = radkit.mesh(radkit.load_scene(os.path.join(DATA, "furnace.json")), patches=150)
    return mesh, radkit.System(radkit.form_factors(mesh))


def test_closed_form_in_the_test_matches_the_catalogue_value():
    assert c11(1, 1) == pytest.approx(C11, rel=1e-14)
    assert c11(2, 3) == pytest.approx(0.4755764365, abs=1e-10)


def test_parallel_squares_surface_factor_is_c11(squares):
    scene, mesh, ff = squares
    assert scene.surface_names == ["lower", "upper"]
    F = ff.dense()
    assert F.shape == (len(mesh), len(mesh))
    # The point-polygon default's documented accuracy: 1e-6 per pair (docs/formfactors.md).
    assert surface_factor(mesh, F, 0, 1) == pytest.approx(C11, abs=1e-6)
    assert surface_factor(mesh, F, 1, 0) == pytest.approx(C11, abs=1e-6)


def test_perpendicular_squares_surface_factor_is_c14():
    mesh = radkit.mesh(radkit.load_scene(os.path.join(DATA, "perpendicular-squares.json")),
                       patches=72)
    F = radkit.form_factors(mesh).dense()
    # Pairs along the shared edge keep the adaptive contour at 1e-6 absolute each, so the
    # surface factor carries a few of those (measured 1.4e-6 here; the C++ suite's cube
    # bounds its adjacent faces at 1.5e-6).
    assert surface_factor(mesh, F, 0, 1) == pytest.approx(C14, abs=2e-6)


def test_dense_and_sparse_agree_and_reciprocity_holds(squares):
    _, mesh, ff = squares
    F, S = ff.dense(), ff.sparse()
    assert scipy.sparse.isspmatrix_csr(S)
    assert np.array_equal(S.toarray(), F)
    A = mesh.area
    # Reciprocity A_i F_ij = A_j F_ji, set by construction (docs/formfactors.md).
    np.testing.assert_allclose(A[:, None] * F, (A[:, None] * F).T, rtol=1e-12, atol=0)
    d = ff.diagnostics
    assert d["patches"] == len(mesh) and d["storage"] == ff.storage == "dense-double"


def test_mesh_arrays_describe_the_patches(squares):
    scene, mesh, _ = squares
    n = len(mesh)
    assert mesh.area.sum() == pytest.approx(2.0, rel=1e-12)  # two unit squares
    assert mesh.centroid.shape == (n, 3) and mesh.normal.shape == (n, 3)
    np.testing.assert_allclose(np.linalg.norm(mesh.normal, axis=1), 1, rtol=1e-12)
    lower = mesh.surface == 0
    assert np.all(mesh.normal[lower] @ [0, 0, 1] > 0.999)  # the lower square faces up
    np.testing.assert_array_equal(mesh.emission[lower], 0)
    np.testing.assert_array_equal(mesh.emission[~lower], 1)
    np.testing.assert_array_equal(mesh.reflectance[lower], 0.5)
    pv = mesh.patch_vertices
    assert pv.shape == (n, 4) and pv.max() < len(mesh.vertices)


def test_two_patch_system_from_the_closed_form():
    # Lower square rho = 0.5 lit by the upper (E = 1, rho = 0): B_lower = rho F E exactly, as
    # the upper reflects nothing; F from whole squares is C-11.
    mesh = radkit.mesh(radkit.load_scene(os.path.join(DATA, "parallel-squares.json")))
    assert len(mesh) == 2
    system = radkit.System(radkit.form_factors(mesh))
    for solver in radkit.solver_names():
        r = radkit.solve(system, solver, tolerance=1e-12)
        assert r["converged"], (solver, r["reason"])
        # F of the whole squares is within the tensor rule's 1e-6 relative (measured 1e-7).
        assert r["radiosity"][0] == pytest.approx([0.5 * C11] * 3, rel=1e-6), solver
        assert r["radiosity"][1] == pytest.approx([1, 1, 1], abs=1e-12), solver


def test_furnace_every_solver_gives_e_over_one_minus_rho(furnace):
    mesh, system = furnace
    # B = E/(1 - rho) = 2 when every row of F sums to 1. A row sum 1 - d moves B by at most
    # rho ||B|| d/(1 - rho) = 2d (infinity norm), d from the run's own diagnostics.
    d = radkit.form_factors(mesh).diagnostics["row_sum"]["max_abs_deviation_from_one"]
    assert d < 1e-4
    for solver in radkit.solver_names():
        r = radkit.solve(system, solver, tolerance=1e-9)
        assert r["converged"], (solver, r["reason"])
        np.testing.assert_allclose(r["radiosity"], 2.0, atol=2 * d + 4e-9, rtol=0,
                                   err_msg=solver)
        assert r["checked_residual"] <= 1e-9 * 1.01


def test_jacobi_residual_falls_by_rho_per_sweep(furnace):
    # From B = E, Jacobi's residual after k sweeps is (rho F)^k rho F E = rho^(k+1) E when every
    # row of F sums to 1: the residual ratio is rho = 0.5 (Cohen & Wallace 1993, 5.3.1).
    _, system = furnace
    r = radkit.solve(system, "jacobi", tolerance=1e-8)
    res = r["history"]["residual"]
    ratios = res[1:] / res[:-1]
    np.testing.assert_allclose(ratios, 0.5, atol=1e-4)
    assert r["iterations"] == math.ceil(math.log(1e-8 / 0.5) / math.log(0.5))


class Jacobi:
    """A solver written in Python against the module's solver protocol."""
    name = "python-jacobi"

    def start(self, system):
        self.F, self.rho, self.E = system.F, system.reflectance, system.emission
        self.B = self.E.copy()

    def step(self):
        self.B = self.E + self.rho * (self.F @ self.B)

    def radiosity(self):
        return self.B


def test_python_solver_object_matches_the_built_in_one(furnace):
    _, system = furnace
    ours = radkit.solve(system, Jacobi(), tolerance=1e-8)
    built_in = radkit.solve(system, "jacobi", tolerance=1e-8)
    assert ours["solver"] == "python-jacobi" and ours["converged"]
    assert ours["iterations"] == built_in["iterations"]
    np.testing.assert_allclose(ours["radiosity"], built_in["radiosity"], rtol=1e-12)
    np.testing.assert_allclose(ours["history"]["residual"], built_in["history"]["residual"],
                               rtol=1e-6)


def test_python_function_solver_is_measured_by_the_module(furnace):
    _, system = furnace
    F, rho, E = system.F, system.reflectance, system.emission

    def direct(s):
        return np.stack([np.linalg.solve(np.eye(len(s)) - rho[:, c, None] * F, E[:, c])
                         for c in range(3)], axis=1)

    r = radkit.solve(system, direct, tolerance=1e-12)
    assert r["converged"] and r["checked_residual"] < 1e-12

    def wrong(s):
        return s.emission  # B = E ignores every bounce: residual rho F E / E = 0.5

    r = radkit.solve(system, wrong, tolerance=1e-6)
    assert not r["converged"] and r["exit"] == "not_converged"
    assert r["checked_residual"] == pytest.approx(0.5, abs=1e-5)


def test_system_from_arrays_dense_and_sparse():
    # Two patches that see only each other (F = [[0, 1], [1, 0]]), rho = 0.5, E = (1, 0):
    # B1 = 1 + 0.5 B2, B2 = 0.5 B1, so B1 = 4/3 and B2 = 2/3.
    F = np.array([[0.0, 1.0], [1.0, 0.0]])
    for matrix in (F, scipy.sparse.csr_matrix(F)):
        system = radkit.System(matrix, np.ones(2), np.full(2, 0.5), np.array([1.0, 0.0]))
        np.testing.assert_array_equal(system.F, F)  # back out of dense and CSR storage alike
        assert (system.F_sparse != scipy.sparse.csr_matrix(F)).nnz == 0
        r = radkit.solve(system, "sor", params="omega=1.1", tolerance=1e-14)
        np.testing.assert_allclose(r["radiosity"][:, 0], [4 / 3, 2 / 3], rtol=1e-13)
        assert system.residual(r["radiosity"]) <= 1e-14
        np.testing.assert_allclose(system.multiply(np.eye(2)[:, [0, 1, 1]]),
                                   F @ np.eye(2)[:, [0, 1, 1]])


def test_bad_input_raises_with_the_fix(tmp_path):
    with pytest.raises(radkit.InputError, match="no-such-scene.json"):
        radkit.load_scene(str(tmp_path / "no-such-scene.json"))
    bad = tmp_path / "bad.json"
    bad.write_text('{"surfaces": [')
    with pytest.raises(ValueError, match="bad.json"):
        radkit.load_scene(str(bad))
    F = np.zeros((2, 2))
    with pytest.raises(ValueError, match="reflectance"):
        radkit.System(F, np.ones(2), np.array([0.5, 1.0]), np.zeros(2))
    with pytest.raises(ValueError, match="shape"):
        radkit.System(F, np.ones(3), np.zeros(2), np.zeros(2))
    system = radkit.System(F, np.ones(2), np.zeros(2), np.ones(2))
    with pytest.raises(ValueError, match="no-such-solver"):
        radkit.solve(system, "no-such-solver")
    with pytest.raises(ValueError, match="precision"):
        radkit.form_factors(radkit.mesh(radkit.load_scene(os.path.join(DATA, "furnace.json"))),
                            precision="half")


def test_render_shows_b_over_pi(furnace):
    # A uniform B seen from inside the closed cube: every pixel is B/pi exactly.
    mesh, _ = furnace
    B = np.tile([2.0, 1.0, 0.5], (len(mesh), 1))
    img = radkit.render(mesh, B, width=24, height=16, camera="0.5,0.5,0.5,0.5,0.5,0")
    assert img.shape == (16, 24, 3)
    np.testing.assert_allclose(img, np.broadcast_to(np.array([2.0, 1.0, 0.5]) / math.pi,
                                                    img.shape), rtol=1e-12)


def test_path_tracer_furnace_within_standard_errors(furnace):
    # White furnace: L = E/(pi (1 - rho)) = 2/pi everywhere (docs/oracles.md). The image mean
    # is tested against a standard error estimated from the per-pixel variances.
    mesh, _ = furnace
    img, var = radkit.path_trace(mesh, spp=16, width=16, height=16, seed=3,
                                 camera="0.5,0.5,0.5,0.5,0.5,0")
    assert img.shape == var.shape == (16, 16, 3)
    n = img.shape[0] * img.shape[1]
    mean = img[..., 0].mean()
    se = math.sqrt(var[..., 0].sum()) / n
    assert se > 0
    assert abs(mean - 2 / math.pi) < 4 * se + 1e-12
    # Deterministic for a seed.
    again, _ = radkit.path_trace(mesh, spp=16, width=16, height=16, seed=3,
                                 camera="0.5,0.5,0.5,0.5,0.5,0")
    assert np.array_equal(img, again)


def test_photon_map_holds_the_photons_photons_tallies(furnace):
    mesh, _ = furnace
    pm = radkit.photon_map(mesh, photons=20000, seed=2)
    tally = radkit.photons(mesh, photons=20000, seed=2)
    assert pm.emitted == 20000 and len(pm) == len(pm.positions) == len(pm.patch) == len(pm.path)
    assert pm.path.max() < 20000
    summed = np.zeros((len(mesh), 3))
    np.add.at(summed, pm.patch, pm.power)
    np.testing.assert_allclose(summed / mesh.area[:, None], tally["irradiance"], rtol=1e-12)


def test_photon_map_estimate_is_unbiased_where_the_density_is_uniform(furnace):
    # In the furnace H = (B - E)/rho = 2 everywhere. With the k-th photon at weight 0, the
    # Epanechnikov estimate of a uniform Poisson density is unbiased and has relative variance
    # 4/(3(k - 2)) (labs/06-photon-mapping/README.md); the six face centres are independent.
    mesh, _ = furnace
    pm = radkit.photon_map(mesh, photons=200000, seed=3)
    centres = np.array([[0.5, 0.5, 0], [0.5, 0.5, 1], [0.5, 0, 0.5], [0.5, 1, 0.5],
                        [0, 0.5, 0.5], [1, 0.5, 0.5]])
    normals = 0.5 - centres
    k = 50
    e = pm.irradiance(centres, normals, k=k)
    assert np.all(e["photons"] == k) and np.all(e["radius"] < 0.5)
    se = 2.0 * np.sqrt(4 / (3 * (k - 2)) / len(centres))
    assert abs(e["irradiance"][:, 0].mean() - 2.0) < 4 * se
    same = pm.irradiance(centres[0], normals[0], k=k)  # one point as (3,)
    np.testing.assert_array_equal(same["irradiance"][0], e["irradiance"][0])


def test_photon_map_rejects_bad_queries(furnace):
    mesh, _ = furnace
    pm = radkit.photon_map(mesh, photons=1000, seed=1)
    with pytest.raises(ValueError, match="k must be >= 2"):
        pm.irradiance([0.5, 0.5, 0], [0, 0, 1], k=1)
    with pytest.raises(ValueError, match="filter 'box' is not known"):
        pm.irradiance([0.5, 0.5, 0], [0, 0, 1], filter="box")
    with pytest.raises(ValueError, match="expected shape"):
        pm.irradiance(np.zeros((2, 2)), [0, 0, 1])
    with pytest.raises(ValueError, match="one per point"):
        pm.irradiance(np.zeros((3, 3)), np.ones((2, 3)))
    with pytest.raises(ValueError, match="zero length"):
        pm.irradiance([0.5, 0.5, 0], [0, 0, 0])
    with pytest.raises(ValueError, match="finite"):
        pm.irradiance([np.nan, 0.5, 0], [0, 0, 1])


def test_photon_image_of_the_furnace_is_its_radiance(furnace):
    # From the middle of the closed cube every face has L = B/pi = 2/pi. The map view is
    # E/pi + (rho/pi) H with H the k-nearest estimate, of relative variance 4/(3(k - 2)) under
    # the uniform photon density; the bound takes the pixels as fully correlated (one draw).
    mesh, _ = furnace
    camera = "0.5,0.5,0.5,0.5,0.5,0,0,1,0,60"
    k = 100
    args = dict(photons=200000, k=k, width=32, height=32, seed=4, camera=camera)
    image = radkit.photon_image(mesh, view="map", **args)
    assert image.shape == (32, 32, 3)
    sd = 0.5 / math.pi * 2.0 * math.sqrt(4 / (3 * (k - 2)))
    assert abs(image[8:24, 8:24].mean() - 2 / math.pi) < 4 * sd
    np.testing.assert_array_equal(image, radkit.photon_image(mesh, view="map", **args))
    assert not np.array_equal(image, radkit.photon_image(mesh, view="map", **{**args, "seed": 5}))
    # No mirror or glass: the caustic map is empty and shows only emission, E/pi = 1/pi.
    np.testing.assert_allclose(radkit.photon_image(mesh, view="caustic", **args), 1 / math.pi,
                               rtol=1e-12)
    with pytest.raises(ValueError, match="view 'film' is not known"):
        radkit.photon_image(mesh, view="film", **args)


def test_photons_furnace_within_standard_errors(furnace):
    mesh, _ = furnace
    p = radkit.photons(mesh, photons=20000, seed=2)
    assert p["radiosity"].shape == (len(mesh), 3)
    for s in p["surfaces"]:
        # Per-surface B = E + rho H is unbiased; each is 2 within a few standard errors.
        assert s["radiosity_error"][0] > 0
        assert abs(s["radiosity"][0] - 2.0) < 4 * s["radiosity_error"][0], s


# ---- System(F, area, reflectance, emission): every array checked before use ----
# Out-of-range CSR indices used to reach the matrix kernels unchecked (SIGSEGV, heap
# corruption, a column of -5 "converging"); negative or NaN F, rows summing far above 1 and
# bad per-patch values were solved as given. Each refusal names the argument and the element.

GOOD_F = np.array([[0.0, 0.5, 0.5], [0.5, 0.0, 0.5], [0.5, 0.5, 0.0]])
ONES, GREY, LIT = np.ones(3), np.full(3, 0.5), np.array([1.0, 0.0, 0.0])


def raw_csr(indptr, indices, data, n=3, index_dtype=np.int32, fmt="csr"):
    """A scipy matrix whose arrays are set after construction, as scipy does not check them
    then (its constructor would refuse some of these inputs)."""
    m = scipy.sparse.csr_matrix((n, n)) if fmt == "csr" else scipy.sparse.csc_matrix((n, n))
    m.indptr = np.asarray(indptr, dtype=index_dtype)
    m.indices = np.asarray(indices, dtype=index_dtype)
    m.data = np.asarray(data, dtype=float)
    return m


def refused(F, fragment, area=ONES, reflectance=GREY, emission=LIT):
    with pytest.raises(ValueError) as e:
        radkit.System(F, area, reflectance, emission)
    assert fragment in str(e.value) and "Fix:" in str(e.value), str(e.value)


def test_csr_column_index_out_of_range_is_refused():
    for column in (3, 100000000, 2**31 - 1):
        refused(raw_csr([0, 1, 2, 3], [1, column, 0], [0.5, 0.5, 0.5]),
                f"F.indices[1] = {column} (an entry of row 1) is outside [0, 3)")
    refused(raw_csr([0, 1, 2, 3], [1, 2**40, 0], [0.5, 0.5, 0.5], index_dtype=np.int64),
            f"F.indices[1] = {2**40}")
    refused(raw_csr([0, 1, 2, 3], [1, 2**64 - 1, 0], [0.5] * 3, index_dtype=np.uint64),
            f"F.indices[1] = {2**64 - 1} is beyond int64")


def test_csr_column_minus_five_is_refused_not_converged():
    for dtype in (np.int32, np.int64):
        refused(raw_csr([0, 1, 2, 3], [1, -5, 0], [0.5, 0.5, 0.5], index_dtype=dtype),
                "F.indices[1] = -5 (an entry of row 1) is outside [0, 3)")


def test_csr_indptr_out_of_range_is_refused():
    refused(raw_csr([0, 1, 2, 100000000], [1, 2, 0], [0.5] * 3),
            "F.indptr[3] = 100000000 entries, but F.indices has 3 and F.data 3")
    refused(raw_csr([0, 1, 2, -7], [1, 2, 0], [0.5] * 3), "F.indptr[3] = -7 is below F.indptr[2]")
    refused(raw_csr([0, 2, 1, 3], [1, 2, 0], [0.5] * 3),
            "F.indptr[2] = 1 is below F.indptr[1] = 2: row 1 would end before it starts")
    refused(raw_csr([1, 1, 2, 3], [1, 2, 0], [0.5] * 3), "F.indptr[0] = 1. Fix: pointers start at 0")
    refused(raw_csr([0, 1, 3], [1, 2, 0], [0.5] * 3), "F.indptr has 3 entries for 3 rows")
    refused(raw_csr([0, 1, 2, 3, 3], [1, 2, 0], [0.5] * 3), "F.indptr has 5 entries for 3 rows")
    refused(raw_csr([0, 1, 2, 3], [1, 2, 0], [0.5] * 2), "F.indices has 3 and F.data 2")
    refused(raw_csr([0, 1, 2, 2], [1, 2, 0], [0.5] * 3), "F.indptr[3] = 2 entries")
    m = raw_csr([0, 1, 2, 3], [1, 2, 0], [0.5] * 3)
    m.indices = m.indices.astype(float)
    refused(m, "F.indices: dtype float64 is not an integer type")


def test_csc_and_coo_indices_are_checked_too():
    refused(raw_csr([0, 1, 2, 3], [1, 7, 0], [0.5] * 3, fmt="csc"),
            "F.indices[1] = 7 (an entry of column 1) is outside [0, 3). Fix: row indices")
    coo = scipy.sparse.coo_matrix(GOOD_F)
    coo.row = coo.row.copy()
    coo.row[2] = 9
    refused(coo, "F.row[2] = 9 is outside [0, 3)")
    coo = scipy.sparse.coo_matrix(GOOD_F)
    coo.col = coo.col.copy()
    coo.col[0] = -1
    refused(coo, "F.col[0] = -1 is outside [0, 3)")


def test_sparse_duplicates_are_summed_and_columns_sorted():
    # Row 0 lists column 2 before 1 and column 1 twice: F[0, 1] = 0.25 + 0.25.
    F = raw_csr([0, 3, 5, 7], [2, 1, 1, 0, 2, 1, 0], [0.5, 0.25, 0.25, 0.5, 0.5, 0.5, 0.5])
    system = radkit.System(F, ONES, GREY, LIT)
    np.testing.assert_array_equal(system.F, GOOD_F)
    for fmt in (scipy.sparse.csc_matrix, scipy.sparse.coo_matrix, scipy.sparse.lil_matrix,
                scipy.sparse.dok_matrix, scipy.sparse.bsr_matrix, scipy.sparse.dia_matrix):
        np.testing.assert_array_equal(radkit.System(fmt(GOOD_F), ONES, GREY, LIT).F, GOOD_F)
    coo = scipy.sparse.coo_matrix(([0.25, 0.25], ([0, 0], [1, 1])), shape=(3, 3))
    assert radkit.System(coo, ONES, GREY, LIT).F[0, 1] == 0.5


def test_negative_and_non_finite_form_factors_are_refused():
    for bad, text in ((-0.9, "= -0.9 is negative"), (np.nan, "= nan is not finite"),
                      (np.inf, "= inf is not finite")):
        F = GOOD_F.copy()
        F[2, 1] = bad
        refused(F, "F[2, 1] " + text)
        refused(scipy.sparse.csr_matrix(F), "F.data[5] (F[2, 1]) " + text)
    refused(np.array([[0, 0.5j], [0.5, 0]]), "F: dtype complex128 is not real")
    refused(np.zeros((2, 3)), "F: expected a square (n, n) matrix, got shape (2, 3)")
    refused(np.zeros((0, 0)), "F: shape (0, 0) has no patches")
    refused(np.zeros(3), "F: expected a square (n, n) array, got shape (3,)")


def test_rows_summing_above_one_are_refused():
    F = GOOD_F.copy()
    F[1] = [0.75, 0.0, 0.75]  # row 1 sums to 1.5
    refused(F, "F row 1 sums to 1.5, above 1 + 0.05")
    refused(scipy.sparse.csr_matrix(F), "F row 1 sums to 1.5")
    # Within the tolerance (radkit's own point-polygon F exceeds 1 by up to about 2 %).
    F[1] = [0.52, 0.0, 0.52]
    assert len(radkit.System(F, ONES, GREY, LIT)) == 3
    # A patch may see itself (an enclosure given as one patch): F_ii counts like any entry.
    radkit.System(np.array([[0.0, 1.0], [0.25, 0.75]]), np.array([1.0, 4.0]), np.full(2, 0.5),
                  np.array([1.0, 0.0]))


def test_bad_area_reflectance_and_emission_are_refused():
    for value, text in ((0.0, "= 0 must be finite and > 0"), (-1.0, "= -1 must be"),
                        (np.nan, "= nan must be"), (np.inf, "= inf must be")):
        refused(GOOD_F, "area[1] " + text, area=np.array([1.0, value, 1.0]))
    for value, text in ((1.0, "= 1 is outside [0, 1)"), (-0.1, "= -0.1 is outside"),
                        (np.nan, "= nan is outside"), (np.inf, "= inf is outside")):
        refused(GOOD_F, "reflectance[2] " + text, reflectance=np.array([0.5, 0.5, value]))
        rgb = np.full((3, 3), 0.5)
        rgb[2, 1] = value
        refused(GOOD_F, "reflectance[2, 1] " + text, reflectance=rgb)
    for value, text in ((-1.0, "= -1 must be finite and >= 0"), (np.inf, "= inf must be"),
                        (np.nan, "= nan must be")):
        refused(GOOD_F, "emission[0] " + text, emission=np.array([value, 0.0, 0.0]))
    # Magnitudes whose products overflow in the solvers (E at the largest double made B inf in
    # the first sweep; a subnormal reflectance made cg's A / rho inf).
    refused(GOOD_F, "emission[0] = 1.797693135e+308 is above 1e+50",
            emission=np.array([np.finfo(float).max, 0.0, 0.0]))
    refused(GOOD_F, "area[2] = 1e+60 is not in [1e-50, 1e+50]", area=np.array([1, 1, 1e60]))
    refused(GOOD_F, "reflectance[0] = 4.940656458e-324 is below 1e-50 but not 0",
            reflectance=np.array([5e-324, 0.5, 0.5]))
    refused(GOOD_F, "area: expected shape (3,), got (2,)", area=np.ones(2))
    refused(GOOD_F, "area: expected shape (3,), got (3, 1)", area=np.ones((3, 1)))
    refused(GOOD_F, "reflectance: expected shape (3, 3) or (3,), got (3, 2)",
            reflectance=np.zeros((3, 2)))
    refused(GOOD_F, "emission: expected shape (3, 3) or (3,), got (4,)", emission=np.zeros(4))
    refused(GOOD_F, "emission: dtype complex128 is not real", emission=np.zeros(3, complex))


def test_systems_of_radkits_own_form_factors_pass_the_checks():
    # The Cornell box's blocks make point-polygon rows sum above 1 by visibility noise (0.9 %
    # at 100 patches): its F passes as arrays, dense and sparse, and System(ff) is unchanged.
    mesh = radkit.mesh(radkit.load_scene(os.path.join(DATA, "cornell-box.json")), patches=100)
    ff = radkit.form_factors(mesh)
    assert ff.diagnostics["row_sum"]["max"] > 1
    reference = radkit.solve(radkit.System(ff), "jacobi", tolerance=1e-10)["radiosity"]
    for F in (ff.dense(), ff.sparse()):
        system = radkit.System(F, mesh.area, mesh.reflectance, mesh.emission)
        r = radkit.solve(system, "jacobi", tolerance=1e-10)
        assert r["converged"]
        np.testing.assert_allclose(r["radiosity"], reference, rtol=1e-12)


class Idle:
    """A Python solver whose step() never changes B."""

    def start(self, system):
        self.B = system.emission.copy()

    def step(self):
        pass

    def radiosity(self):
        return self.B


def test_python_solver_that_never_changes_b_stops_as_stagnated(furnace):
    # It used to step to max_iterations (1e8 by default) and report only that.
    _, system = furnace
    r = radkit.solve(system, Idle(), tolerance=1e-8, max_iterations=100000)
    assert r["exit"] == "stagnated" and not r["converged"], r["reason"]
    assert r["iterations"] == 2
    assert "B, the residual 0.5 and the unshot power have not changed since iteration 1" in r["reason"]
    assert "step() must update the B its radiosity() returns" in r["reason"]


def furnace_of_input_faces(tmp_path, n, rho):
    """data/furnace.json at reflectance rho, each face cut into n x n input faces wound as the
    face is."""
    with open(os.path.join(DATA, "furnace.json")) as f:
        scene = json.load(f)
    scene["materials"]["glow"]["reflectance"] = [rho] * 3
    polygons = []
    for surface in scene["surfaces"]:
        p0, p1, p2, p3 = (np.array(p, dtype=float) for p in surface["polygon"])

        def at(i, j):  # bilinear over the face, i along p0 -> p1, j along p0 -> p3
            u, v = i / n, j / n
            return list((1 - u) * (1 - v) * p0 + u * (1 - v) * p1 + u * v * p2 + (1 - u) * v * p3)
        polygons += [[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]
                     for i in range(n) for j in range(n)]
    # One closed surface: faces share the vertices along the cube's edges.
    scene["surfaces"] = [{"name": "box", "material": "glow", "polygons": polygons}]
    path = tmp_path / "furnace-cut.json"
    path.write_text(json.dumps(scene))
    return radkit.load_scene(path)


def test_hierarchical_furnace_is_e_over_one_minus_rho_on_every_leaf(tmp_path):
    # Closed cube, E = 1, rho = 0.95: B = E/(1 - rho) = 20 (docs/oracles.md). Cut into input
    # faces, every leaf's hemisphere is closed and its row sum filled to 1, so the answer is
    # exact to the solver's tolerance (docs/hierarchical.md's furnace with clusters; the fill
    # ramps in with rho, so at rho = 0.5 leaves carry their links' row-sum noise instead).
    r = radkit.hierarchical(furnace_of_input_faces(tmp_path, 8, 0.95), epsilon=1e-3,
                            tolerance=1e-10)
    assert r["converged"], r["reason"]
    assert len(r["mesh"]) == r["radiosity"].shape[0] >= 6 * 64
    np.testing.assert_allclose(r["radiosity"], 20.0, rtol=1e-8)
    np.testing.assert_allclose(r["mesh"].area.sum(), 6.0, rtol=1e-12)  # m², the six faces
    assert r["links"] > 0 and r["rays"] > 0 and len(r["rounds"]) == 3
    with pytest.raises(ValueError, match="gauss-seidel"):
        radkit.hierarchical(radkit.load_scene(os.path.join(DATA, "furnace.json")), order="sor")


@pytest.mark.skipif(not os.environ.get("RADKIT_BINARY"), reason="needs the radkit binary")
def test_hierarchical_gives_what_the_command_line_writes(tmp_path):
    # One library call behind both front ends: the same leaves and radiosity, digit for digit.
    RADKIT = os.environ["RADKIT_BINARY"]
    path = os.path.join(DATA, "cornell-box.json")
    r = radkit.hierarchical(radkit.load_scene(path), seed=3)
    out = tmp_path / "run"
    subprocess.run([RADKIT, "run", path, "--method", "hierarchical", "--seed", "3",
                    "--no-render", "--out", str(out)], check=True, capture_output=True)
    rows = np.genfromtxt(out / "patches.csv", delimiter=",", names=True, dtype=None,
                         encoding="utf-8")
    assert len(rows) == len(r["mesh"])
    np.testing.assert_allclose(rows["area_m2"], r["mesh"].area, rtol=1e-15)
    for c, name in enumerate(["b_r_W_m2", "b_g_W_m2", "b_b_W_m2"]):
        np.testing.assert_allclose(rows[name], r["radiosity"][:, c], rtol=1e-15, atol=0)


@pytest.mark.skipif(not os.environ.get("RADKIT_BINARY"), reason="needs the radkit binary")
@pytest.mark.parametrize("kind,args", [
    ("run", ["--preset", "draft", "--patches", "150", "--no-render"]),
    ("run", ["--method", "hierarchical", "--seed", "4", "--epsilon", "1e-3", "--no-render"]),
    ("solvers", ["--patches", "120", "--solvers", "jacobi,sor:omega=1.3"]),
    ("formfactors", ["--ff", "monte-carlo", "--seed", "2"])])
def test_run_writes_the_folder_the_command_line_writes(tmp_path, kind, args):
    # The command line and run() are one library call (job/job.h): the same files, byte for
    # byte, and the same report but for the clock and the memory.
    path = os.path.join(DATA, "cornell-box.json")
    cli = tmp_path / "cli"
    subprocess.run([os.environ["RADKIT_BINARY"], kind, path, *args, "--out", str(cli)],
                   check=True, capture_output=True)
    options = {"run": {}, "solvers": {"kind": "solvers"}, "formfactors": {"kind": "formfactors"}}
    keywords = dict(options[kind])
    flags = dict(zip(args[::2], args[1::2]))
    names = {"--preset": "preset", "--method": "method", "--seed": "seed", "--epsilon": "epsilon",
             "--solvers": "solvers", "--ff": "ff"}
    for flag, value in flags.items():
        if flag in names:
            keywords[names[flag]] = int(value) if flag == "--seed" else \
                float(value) if flag == "--epsilon" else value
    if "--patches" in args:
        keywords["patches"] = int(args[args.index("--patches") + 1])
    if "--no-render" in args:
        keywords["render"] = False
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the box's non-planar wall is split into triangles
        r = radkit.run(path, out=tmp_path / "py", **keywords)
    assert r["out"] == str(tmp_path / "py")
    files = sorted(p.name for p in cli.iterdir())
    assert files == sorted(p.name for p in (tmp_path / "py").iterdir())
    for name in files:
        if name.endswith((".csv", ".vtp", ".bin", ".mtx")) and name != "convergence.csv":
            assert (cli / name).read_bytes() == (tmp_path / "py" / name).read_bytes(), name
    report = json.loads((cli / "report.json").read_text())
    assert r["report"]["surfaces" if kind != "formfactors" else "mesh"] == \
        report["surfaces" if kind != "formfactors" else "mesh"]
    assert r["report"]["command"] == kind
    assert len(r["mesh"]) == report["mesh"]["patches"]
    if kind != "formfactors":
        assert r["radiosity"].shape == (len(r["mesh"]), 3)


def test_run_takes_areas_in_square_metres_raises_warnings_and_refuses_bad_settings(tmp_path):
    # A centimetre scene: max_area is m², as everywhere in the module (1 cm² squares, 0.25 cm²).
    scene = json.loads(open(os.path.join(DATA, "parallel-squares.json")).read())
    scene["units"] = "cm"
    path = tmp_path / "squares.json"
    path.write_text(json.dumps(scene))
    r = radkit.run(path, out=tmp_path / "a", max_area=0.25e-4, render=False)
    assert len(r["mesh"]) == 8
    np.testing.assert_allclose(r["mesh"].area, 0.25e-4, rtol=1e-12)
    # A loaded Scene runs as its file does.
    again = radkit.run(radkit.load_scene(path), out=tmp_path / "b", max_area=0.25e-4,
                       render=False)
    np.testing.assert_array_equal(again["radiosity"], r["radiosity"])
    with pytest.warns(UserWarning, match="not planar"):
        radkit.run(os.path.join(DATA, "cornell-box.json"), out=tmp_path / "c", patches=60,
                   render=False)
    for keywords, message in [({"kind": "study"}, "kind 'study'"),
                              ({"preset": "large", "method": "dense"}, "not the dense one"),
                              ({"method": "hierarchical", "adaptive": True}, "adaptive"),
                              ({"solvers": "jacobi,nope"}, "nope")]:
        with pytest.raises(ValueError, match=message):
            radkit.run(path, out=tmp_path / "d", **keywords)
        assert not (tmp_path / "d").exists()
    with pytest.raises(ValueError, match="units and repair are for a scene file"):
        radkit.run(radkit.load_scene(path), out=tmp_path / "d", units="mm")
    # The library names settings; Python spells them as its keywords, not the flags.
    for keywords, spelled in [({"method": "hierarchical", "epsilon": 5}, "epsilon= 5"),
                              ({"method": "hierarchical", "rays_per_link": 0}, "rays_per_link= 0"),
                              ({"units": "parsec"}, "units= parsec")]:
        with pytest.raises((ValueError, radkit.InputError), match=spelled) as error:
            radkit.run(path, out=tmp_path / "d", **keywords)
        assert "--" not in str(error.value), error.value


def read_pfm(path):
    """A PFM image as (height, width, 3), top row first (the file stores the bottom row first)."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1]


@pytest.mark.skipif(not os.environ.get("RADKIT_BINARY"), reason="needs the radkit binary")
@pytest.mark.parametrize("shading", ["radiosity", "path-trace", "final-gather"])
def test_render_scene_gives_the_image_radkit_render_writes(tmp_path, shading):
    # One integrator registry behind both front ends: the same image (the PFM holds float32).
    path = os.path.join(DATA, "cornell-box-glossy.json")
    image = radkit.render_scene(radkit.load_scene(path), shading, width=24, height=16, spp=2,
                                seed=5, patches=150)
    out = tmp_path / "r.pfm"
    subprocess.run([os.environ["RADKIT_BINARY"], "render", path, "--shading", shading,
                    "--size", "24x16", "--spp", "2", "--seed", "5", "--patches", "150",
                    "--out", str(out)], check=True, capture_output=True)
    assert image.shape == (16, 24, 3)
    np.testing.assert_array_equal(read_pfm(out), image.astype(np.float32))
    assert image.max() > 0


def test_registries_are_listed_and_unknown_names_refused():
    assert radkit.render_modes() == ["radiosity", "phong", "cook-torrance", "path-trace",
                                     "photon-map", "final-gather"]
    assert {"lambert", "phong", "cook-torrance", "oren-nayar"} <= set(radkit.bsdf_names())
    assert radkit.form_factor_methods()[0] == "point-polygon"
    scene = radkit.load_scene(os.path.join(DATA, "furnace.json"))
    with pytest.raises(ValueError, match='unknown integrator "raytrace". Fix: use one of'):
        radkit.render_scene(scene, "raytrace")
