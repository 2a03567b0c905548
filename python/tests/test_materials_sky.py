"""Materials, the sky and the outdoor jobs from Python (docs/python.md): BSDFs of the registry
against their closed forms, the sky's radiance against the sky job, and the sky, clouds and
terrain jobs against the command line's files.

Run from the build: PYTHONPATH=build/python python3 -m pytest python/tests (ctest does this).
"""
import math
import os
import subprocess

import numpy as np
import pytest

import radkit

NEEDS_BINARY = pytest.mark.skipif(not os.environ.get("RADKIT_BINARY"),
                                  reason="needs the radkit binary")


def upper_hemisphere(n, rng):
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 1e-3
    return v / np.linalg.norm(v, axis=1)[:, None]


def test_lambert_is_its_reflectance_over_pi():
    rng = np.random.default_rng(1)
    b = radkit.Bsdf("lambert", {"reflectance": [0.8, 0.5, 0.2]})
    f = b.eval(upper_hemisphere(100, rng), upper_hemisphere(100, rng))
    np.testing.assert_allclose(f, np.tile([0.8 / math.pi, 0.5 / math.pi, 0.2 / math.pi],
                                          (100, 1)), rtol=1e-14)
    np.testing.assert_allclose(b.diffuse_albedo, [0.8, 0.5, 0.2], rtol=1e-14)
    # One-sided: nothing toward the back.
    assert not b.eval([0, 0, 1], [0, 0, -1]).any()


def test_phong_albedo_at_normal_incidence_is_ks_by_quadrature_and_by_sampling():
    # Energy-normalised Phong, ks (n + 2)/(2 pi) cos^n alpha: looking straight down the mirror
    # direction is the normal, and the integral of f cos over the hemisphere is exactly ks.
    ks, n = 0.9, 20
    b = radkit.Bsdf("phong", f"kd=0 0 0, ks={ks}, shininess={n}")
    as_dict = radkit.Bsdf("phong", {"kd": [0, 0, 0], "ks": ks, "shininess": n})
    wo = np.array([0.0, 0.0, 1.0])
    # Midpoint rule in (cos theta, phi): f cos dw = f mu dmu dphi.
    m = 4000
    mu = (np.arange(m) + 0.5) / m
    wi = np.stack([np.sqrt(1 - mu**2), np.zeros(m), mu], axis=1)
    f = b.eval(wo, wi)[:, 0]
    np.testing.assert_array_equal(f, as_dict.eval(wo, wi)[:, 0])
    albedo = 2 * math.pi * np.sum(f * mu) / m
    assert albedo == pytest.approx(ks, rel=1e-5)
    # Sampling: the weights f cos / pdf average to the albedo (within four standard errors),
    # and pdf() gives each sample's density.
    rng = np.random.default_rng(7)
    s = b.sample(wo, rng.random((200000, 3)))
    w = s["weight"][:, 0]
    assert abs(w.mean() - ks) <= 4 * w.std(ddof=1) / math.sqrt(len(w))
    kept = s["pdf"] > 0
    np.testing.assert_allclose(b.pdf(wo, s["wi"][kept])[:200], s["pdf"][kept][:200], rtol=1e-9)


def test_bsdf_refusals_name_the_key():
    with pytest.raises(ValueError, match="shininesss"):
        radkit.Bsdf("phong", {"shininesss": 20})
    with pytest.raises(ValueError, match="lambertian"):
        radkit.Bsdf("lambertian")
    with pytest.raises(ValueError, match="wo and wi"):
        radkit.Bsdf("lambert").eval(np.ones((2, 3)), np.ones((3, 3)))


def test_sky_radiance_is_what_the_sky_job_reports(tmp_path):
    r = radkit.sky(tmp_path / "sky", sun_elevation=20, sun_azimuth=90, size=16,
                   projection="fisheye")
    assert sorted(p.name for p in (tmp_path / "sky").iterdir()) == \
        [".radkit-output", "report.json", "sky-fisheye.pfm", "sky-fisheye.png"]
    zenith = radkit.sky_radiance([[0, 0, 1]], sun_elevation=20, sun_azimuth=90)
    np.testing.assert_array_equal(zenith[0], r["report"]["radiance"]["zenith"])
    # Rayleigh scattering grows as 1/lambda^4: the clear zenith is bluest.
    assert zenith[0, 2] > zenith[0, 1] > zenith[0, 0] > 0


@NEEDS_BINARY
def test_clouds_and_terrain_write_the_files_the_command_line_writes(tmp_path):
    cli = os.environ["RADKIT_BINARY"]
    subprocess.run([cli, "clouds", "--width", "8", "--height", "6", "--samples", "2",
                    "--sun-elevation", "25", "--out", str(tmp_path / "c-cli")],
                   check=True, capture_output=True)
    radkit.clouds(tmp_path / "c-py", width=8, height=6, samples=2, sun_elevation=25)
    subprocess.run([cli, "terrain", "--resolution", "17", "--seed", "3", "--out",
                    str(tmp_path / "t-cli")], check=True, capture_output=True)
    radkit.terrain(tmp_path / "t-py", resolution=17, seed=3)
    for a, b in [("c-cli", "c-py"), ("t-cli", "t-py")]:
        files = sorted(p.name for p in (tmp_path / a).iterdir())
        assert files == sorted(p.name for p in (tmp_path / b).iterdir())
        for name in files:
            # report.json holds times; terrain.json names the scene after its folder.
            if name not in ("report.json", ".radkit-output", "terrain.json"):
                assert (tmp_path / a / name).read_bytes() == (tmp_path / b / name).read_bytes(), \
                    name


def test_phase_functions_integrate_to_one_and_have_their_mean_cosine():
    # Henyey-Greenstein: normalised over the sphere, mean cosine g (Henyey and Greenstein
    # 1941), and sampled as its density; Rayleigh: 3(1 + mu^2)/(16 pi), mean cosine 0.
    assert "henyey-greenstein" in radkit.phase_function_names()
    m = 400000
    mu = -1 + (np.arange(m) + 0.5) * 2 / m  # midpoint rule in mu: dw = 2 pi dmu
    for name, params, g in [("henyey-greenstein", {"g": 0.7}, 0.7),
                            ("henyey-greenstein", "g=-0.3", -0.3), ("rayleigh", None, 0.0)]:
        p = radkit.PhaseFunction(name, params)
        f = p.eval(mu)
        assert 2 * math.pi * f.sum() * 2 / m == pytest.approx(1, abs=1e-6), name
        assert 2 * math.pi * (f * mu).sum() * 2 / m == pytest.approx(g, abs=1e-6), name
        assert p.mean_cosine == pytest.approx(g, abs=1e-15)
        s, pdf = p.sample(np.random.default_rng(3).random(100000))
        np.testing.assert_allclose(pdf, p.eval(s), rtol=1e-9)
        assert abs(s.mean() - g) <= 4 * s.std(ddof=1) / math.sqrt(len(s))
    np.testing.assert_allclose(radkit.PhaseFunction("rayleigh").eval(np.array([0.0, 1.0])),
                               [3 / (16 * math.pi), 6 / (16 * math.pi)], rtol=1e-14)
    with pytest.raises(ValueError, match="g"):
        radkit.PhaseFunction("henyey-greenstein", {"g": 1.5})
    with pytest.raises(ValueError, match="not a cosine"):
        radkit.PhaseFunction("isotropic").eval(np.array([1.5]))


def test_every_sky_model_is_a_scene_sky_whose_irradiance_integrates_its_radiance():
    # E_h = ∫ L cos θ dω by the midpoint rule on a grid unlike any model's own.
    n = 200
    e = (np.arange(n) + 0.5) / n * (math.pi / 2)
    a = (np.arange(2 * n) + 0.5) / (2 * n) * 2 * math.pi
    E, A = np.meshgrid(e, a, indexing="ij")
    dirs = np.stack([np.cos(E) * np.sin(A), np.cos(E) * np.cos(A), np.sin(E)], -1).reshape(-1, 3)
    weight = (np.sin(E) * np.cos(E)).reshape(-1, 1) * (math.pi / 2 / n) * (2 * math.pi / (2 * n))
    examples = {"uniform": {"luminance": 3183}, "cie-overcast": {"zenith_luminance": 4093}}
    assert set(examples) | {"physical"} <= set(radkit.sky_models())
    for name in radkit.sky_models():
        sky = radkit.SkyModel(name, examples.get(name), sun_elevation=30, sun_azimuth=120)
        integral = (sky.radiance(dirs) * weight).sum(axis=0)
        np.testing.assert_allclose(sky.horizontal_irradiance[0], integral, rtol=2e-3, err_msg=name)
        assert np.all(sky.radiance(-dirs) == 0)  # below the horizon: the scene's ground
    # Uniform: E_h = πL, so 3183 cd/m² is 10 000 lux within the rounding to whole cd/m².
    uniform = radkit.SkyModel("uniform", {"luminance": 3183})
    assert 683 * uniform.horizontal_irradiance[0, 1] == pytest.approx(1e4, abs=2)
    assert radkit.SkyModel("physical", sun_elevation=30).sun_irradiance[0, 0] > 0
    assert np.all(radkit.SkyModel("uniform", {"radiance": 1}).sun_irradiance == 0)


def test_sky_model_refusals_name_the_model_and_key():
    with pytest.raises(ValueError, match="uniform, cie-overcast, physical"):
        radkit.SkyModel("foggy")
    with pytest.raises(ValueError, match="exactly one"):
        radkit.SkyModel("uniform")
    with pytest.raises(ValueError, match='"altitude"'):
        radkit.SkyModel("physical", {"altitude": 1e6})
    with pytest.raises(ValueError, match='"colour"'):
        radkit.SkyModel("uniform", {"radiance": 1, "colour": 2})
    assert radkit.preset_names()[:3] == ["draft", "balanced", "reference"]


def test_medium_transmittance_is_beer_lambert_within_its_standard_error():
    box = radkit.Medium({"type": "homogeneous-box", "min": [0, 0, 0], "max": [10, 10, 10],
                         "extinction": 0.2, "phase": "isotropic"})
    assert box.kind == "homogeneous-box" and box.majorant == 0.2 and box.albedo == 1
    np.testing.assert_array_equal(box.extinction(np.array([[5, 5, 5], [11, 5, 5]])), [0.2, 0])
    assert box.phase.name == "isotropic"
    # Inside for 3 m: from within, and from outside through the wall; T = exp(-0.6).
    origins = np.array([[5.0, 5, 1], [-5.0, 5, 5]])
    mean, se = box.transmittance(origins, np.array([1.0, 0, 0]), np.array([3.0, 8.0]),
                                 samples=4000, seed=3)
    assert np.all(se > 0)
    assert np.all(np.abs(mean - math.exp(-0.6)) < 4 * se), (mean, se)
    # A cloud layer: ratio tracking against exp(-∫ σ_t dt) by the midpoint rule on
    # extinction() along slanted rays through the layer (1500-4000 m).
    layer = radkit.Medium({"type": "cloud-layer", "coverage": 0.7, "extinction": 0.02})
    o = np.array([[0.0, 0, 1000], [300, -200, 1000], [-800, 500, 1000]])
    d = np.array([[0.2, 0.1, 1.0], [0.0, 0.3, 1.0], [-0.4, 0.0, 1.0]])
    d /= np.linalg.norm(d, axis=1)[:, None]
    length = 3500 / d[:, 2]
    mean, se = layer.transmittance(o, d, length, samples=3000, seed=5)
    n = 20000
    for k in range(3):
        t = (np.arange(n) + 0.5) / n * length[k]
        tau = layer.extinction(o[k] + t[:, None] * d[k]).sum() * length[k] / n
        assert abs(mean[k] - math.exp(-tau)) < 4 * se[k] + 1e-3, (k, mean[k], se[k], tau)
    # Same seed, same numbers; a medium the format refuses is a ValueError naming the key.
    np.testing.assert_array_equal(layer.transmittance(o, d, length, samples=3000, seed=5)[0], mean)
    with pytest.raises(ValueError, match="extinction"):
        radkit.Medium({"type": "homogeneous-box", "min": [0, 0, 0], "max": [1, 1, 1],
                       "extinction": -1})


def test_rayleigh_models_by_name_reach_the_sky_job_and_the_scene_sky(tmp_path):
    # Bodhaine et al. 1999, eq. (30) (their fit of Table 3): tau_R at 680, 550, 440 nm.
    bodhaine = [0.040959, 0.097065, 0.24261]
    np.testing.assert_allclose(radkit.rayleigh_optical_depth("bodhaine")[0], bodhaine, rtol=0.01)
    r = radkit.sky(tmp_path / "sky", size=16, projection="fisheye", rayleigh="bodhaine")
    reported = r["report"]["rayleigh"]
    assert reported["model"] == "bodhaine"
    np.testing.assert_allclose(reported["optical_depth"], bodhaine, rtol=0.01)
    # The default (Bruneton and Neyret's coefficients) lies 8-14 % above.
    ratio = radkit.rayleigh_optical_depth()[0] / bodhaine
    assert np.all((ratio > 1.08) & (ratio < 1.14)), ratio
    # Less Rayleigh scattering, a darker blue sky, in the scene's physical sky too.
    thin = radkit.SkyModel("physical", {"rayleigh": "bodhaine"}, sun_elevation=30)
    default = radkit.SkyModel("physical", sun_elevation=30)
    assert thin.horizontal_irradiance[0, 2] < default.horizontal_irradiance[0, 2]
    with pytest.raises(ValueError, match="bruneton, bodhaine"):
        radkit.SkyModel("physical", {"rayleigh": "nishita"})
    with pytest.raises(ValueError, match="co2"):
        radkit.rayleigh_optical_depth("bodhaine:co2=-1")
