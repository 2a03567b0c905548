"""The module's conventions (docs/python.md): paths, solver parameters, units, read-only array
properties, the checks on arrays given to System, and the version.

Run from the build: PYTHONPATH=build/python python3 -m pytest python/tests (ctest does this).
"""
import json
import os
import pathlib
import re

import numpy as np
import pytest

import radkit

DATA = pathlib.Path(os.environ.get("RADKIT_DATA_DIR",
                                   pathlib.Path(__file__).parent / ".." / ".." / "data"))
REPO = pathlib.Path(__file__).resolve().parents[2]

# Two patches that see only each other: B1 = 4/3, B2 = 2/3 (test_radkit.py derives it).
F2 = np.array([[0.0, 1.0], [1.0, 0.0]])


def two_patches():
    return radkit.System(F2, np.ones(2), np.full(2, 0.5), np.array([1.0, 0.0]))


def squares_in(units, tmp_path):
    """data/parallel-squares.json (two unit squares one apart) with its coordinates read in
    `units`."""
    scene = json.loads((DATA / "parallel-squares.json").read_text())
    scene["units"] = units
    path = tmp_path / f"squares-{units}.json"
    path.write_text(json.dumps(scene))
    return radkit.load_scene(str(path))


class FsPath:
    """An os.PathLike that is neither str nor pathlib."""

    def __init__(self, path):
        self.path = str(path)

    def __fspath__(self):
        return self.path


# ---- paths ----

def test_load_scene_takes_str_and_any_path_like(tmp_path):
    path = DATA / "furnace.json"
    for given in (str(path), path, FsPath(path), os.fsencode(path)):
        assert radkit.load_scene(given).name == "furnace", given
    with pytest.raises(radkit.InputError, match="no-such-scene.json"):
        radkit.load_scene(tmp_path / "no-such-scene.json")
    with pytest.raises(TypeError, match="os.PathLike"):
        radkit.load_scene(42)


# ---- solver parameters ----

def test_solver_params_as_a_dict_match_the_text_form():
    system = two_patches()
    text = radkit.solve(system, "sor", params="omega=1.1,power_iterations=5", tolerance=1e-14)
    assert "omega = 1.1" in text["description"]
    for params in ({"omega": 1.1, "power_iterations": 5},
                   {"omega": np.float64(1.1), "power_iterations": np.int32(5)},
                   {"omega": "1.1", "power_iterations": "5"}):
        r = radkit.solve(system, "sor", params=params, tolerance=1e-14)
        assert r["description"] == text["description"], params
        assert r["iterations"] == text["iterations"], params
        np.testing.assert_array_equal(r["radiosity"], text["radiosity"])
    # A bool is 1 or 0: omega = True is Gauss-Seidel's omega.
    assert "omega = 1," in radkit.solve(system, "sor", params={"omega": True})["description"]
    assert radkit.solve(system, "sor", params={})["description"] == \
        radkit.solve(system, "sor")["description"]


def test_solver_params_dict_refusals_name_the_key_and_the_value():
    system = two_patches()
    cases = [({"omegax": 1.2}, ValueError,
              'solver "sor": gives "omegax", which sor does not use. Fix: sor reads omega'),
             ({"omega": "abc"}, ValueError, 'solver "sor": "omega" must be one finite number'),
             ({"omega": "1.2,power_iterations=3"}, ValueError,
              "solver parameter 'omega=1.2,power_iterations=3': expected key=number"),
             ({"omega": 1j}, ValueError, "solver parameter 'omega=1j': expected a number"),
             ({"omega": None}, ValueError, "solver parameter 'omega=None': expected a number"),
             ({1: 1.2}, ValueError, "params: key 1 is not a string"),
             ({"omega=1.2": 1}, ValueError, "params: key 'omega=1.2' is not a parameter name"),
             (["omega", 1.2], TypeError, "params: expected text")]
    for params, error, message in cases:
        with pytest.raises(error, match=re.escape(message)):
            radkit.solve(system, "sor", params=params)
    with pytest.raises(ValueError, match='solver "sor": "omega" must be one finite number'):
        radkit.solve(system, "sor", params="omega=abc")  # the text form: the registry's words
    with pytest.raises(ValueError, match="params are for built-in solvers"):
        radkit.solve(system, lambda s: s.emission, params={"omega": 1.2})


# ---- units: every area in m² ----

def test_areas_are_square_metres_whatever_the_scene_units(tmp_path):
    cm = squares_in("cm", tmp_path)
    assert cm.units == "cm"
    # max_area is m² too: 0.25 cm² splits each 1 cm² square into four.
    mesh = radkit.mesh(cm, max_area=0.25e-4)
    assert len(mesh) == 8
    np.testing.assert_allclose(mesh.area, 0.25e-4, rtol=1e-12)
    system = radkit.System(radkit.form_factors(mesh))
    np.testing.assert_array_equal(system.area, mesh.area)
    metres = radkit.mesh(squares_in("m", tmp_path), max_area=0.25)
    np.testing.assert_allclose(metres.area * 1e-4, mesh.area, rtol=1e-12)
    # Photon areas and powers in m² and W: the emitter (E = 1 W/m² on 1 cm²) emits 1e-4 W.
    tally = radkit.photons(mesh, photons=2000, seed=1)
    assert [s["area"] for s in tally["surfaces"]] == pytest.approx([1e-4, 1e-4], rel=1e-12)
    pm = radkit.photon_map(mesh, photons=2000, seed=1)
    np.testing.assert_allclose(pm.emitted_power, 1e-4, rtol=1e-6)
    summed = np.zeros((len(mesh), 3))
    np.add.at(summed, pm.patch, pm.power)
    np.testing.assert_allclose(summed / mesh.area[:, None], tally["irradiance"], rtol=1e-12)


# ---- read-only array properties ----

def test_array_properties_are_read_only(tmp_path):
    mesh = radkit.mesh(radkit.load_scene(str(DATA / "parallel-squares.json")), patches=8)
    system = radkit.System(radkit.form_factors(mesh))
    pm = radkit.photon_map(mesh, photons=1000, seed=1)
    properties = {"mesh": (mesh, ["area", "centroid", "normal", "surface", "vertices",
                                  "patch_vertices", "reflectance", "emission"]),
                  "system": (system, ["F", "area", "reflectance", "emission"]),
                  "photon_map": (pm, ["positions", "power", "patch", "path", "emitted_power"])}
    for owner, (obj, names) in properties.items():
        for name in names:
            a = getattr(obj, name)
            assert not a.flags.writeable, f"{owner}.{name}"
            with pytest.raises(ValueError, match="read-only"):
                a[...] = 0
    # The documented way to change values: copy, change, build a System from the arrays.
    rho = np.array(mesh.reflectance)
    rho[:] = 0.25
    changed = radkit.System(system.F, mesh.area, rho, mesh.emission)
    np.testing.assert_array_equal(changed.reflectance, 0.25)
    np.testing.assert_array_equal(mesh.reflectance[mesh.surface == 0], 0.5)


def test_arrays_functions_return_are_the_callers():
    system = two_patches()
    mesh = radkit.mesh(radkit.load_scene(str(DATA / "parallel-squares.json")))
    ff = radkit.form_factors(mesh)
    r = radkit.solve(system, "jacobi")
    returned = {"solve radiosity": r["radiosity"], "history": r["history"]["residual"],
                "dense": ff.dense(), "sparse data": ff.sparse().data,
                "F_sparse data": system.F_sparse.data, "multiply": system.multiply(np.ones(2)),
                "render": radkit.render(mesh, np.ones((2, 3)), width=4, height=4),
                "photons": radkit.photons(mesh, photons=100)["radiosity"]}
    for name, a in returned.items():
        assert a.flags.writeable, name


# ---- System(F, area, reflectance, emission) ----

def test_dense_form_factors_are_checked_in_any_layout():
    # Whatever numpy hands over (lists, Fortran order, strided views, float32) is checked as
    # the values the user sees.
    rows = [[0.0, 1.0], [1.0, 1.0]]  # row 1 sums to 2
    for F in (rows, np.asfortranarray(rows), np.array([[0, 9, 1, 9], [1, 9, 1, 9]])[:, ::2],
              np.array(rows, dtype=np.float32)):
        with pytest.raises(ValueError, match="F row 1 sums to 2, above 1 \\+ 0.05"):
            radkit.System(F, np.ones(2), np.full(2, 0.5), np.ones(2))
    for bad, text in ((np.nan, "F[0, 1] = nan is not finite"),
                      (-0.5, "F[0, 1] = -0.5 is negative")):
        F = np.array([[0.0, bad], [1.0, 0.0]], dtype=np.float32)
        with pytest.raises(ValueError, match=re.escape(text)):
            radkit.System(F, np.ones(2), np.full(2, 0.5), np.ones(2))


def test_masked_entries_are_refused_not_read_as_stored():
    # numpy.ma keeps the values behind a mask; reading them as given would solve with a
    # row summing to 2 the user had masked out.
    F = np.ma.masked_array([[0.0, 2.0], [1.0, 0.0]], mask=[[0, 1], [0, 0]])
    with pytest.raises(ValueError, match=re.escape("F[0, 1] is masked. Fix: F.filled(value)")):
        radkit.System(F, np.ones(2), np.full(2, 0.5), np.ones(2))
    area = np.ma.masked_array([1.0, -1.0], mask=[0, 1])
    with pytest.raises(ValueError, match=re.escape("area[1] is masked")):
        radkit.System(F2, area, np.full(2, 0.5), np.ones(2))
    unmasked = np.ma.masked_array(F2, mask=False)
    np.testing.assert_array_equal(radkit.System(unmasked, np.ones(2), 0.5 * np.ones(2),
                                                np.ones(2)).F, F2)


# ---- version ----

def test_version_is_the_projects():
    project = re.search(r"project\(radkit VERSION ([0-9.]+)",
                        (REPO / "CMakeLists.txt").read_text())
    assert project, "CMakeLists.txt: project(radkit VERSION ...) not found"
    assert radkit.__version__ == project.group(1)
