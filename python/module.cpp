// The `radkit` Python module: the pipeline's stages as functions over numpy arrays, for
// notebooks and the labs. Objects hold what they were made from (a mesh its scene, form
// factors their mesh, a system its matrix), so Python's reference counting keeps every
// pointer the C++ side stores valid. docs/python.md is the user's guide.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "atmosphere/atmosphere.h"
#include "atmosphere/rayleigh.h"
#include "bsdf/bsdf.h"
#include "geometry/patch_mesh.h"
#include "geometry/ray_scene.h"
#include "geometry/scene.h"
#include "geometry/scene_loader.h"
#include "geometry/subdivision.h"
#include "hierarchy/hierarchical.h"
#include "integrators/integrator.h"
#include "job/clouds_job.h"
#include "job/job.h"
#include "job/sky_job.h"
#include "job/terrain_job.h"
#include "media/medium_json.h"
#include "media/volume_tracer.h"
#include "phase/phase_function.h"
#include "photon/estimate.h"
#include "photon/image.h"
#include "photon/map.h"
#include "photon/tracer.h"
#include "radiosity/form_factor_storage.h"
#include "radiosity/form_factors.h"
#include "radiosity/pair_rule.h"
#include "radiosity/presets.h"
#include "radiosity/radiosity_solution.h"
#include "render/camera.h"
#include "render/path_tracer.h"
#include "render/radiosity_image.h"
#include "render/shading_context.h"
#include "sky/sky_radiance.h"
#include "solvers/registry.h"
#include "solvers/solver.h"
#include "solvers/system_input.h"
#include "util/format.h"
#include "util/setting_names.h"
#include "util/threads.h"

namespace py = pybind11;
using namespace radkit;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// An array property as read-only: each access makes a new copy, so a write into it would
/// change nothing the object holds and must fail instead of being lost.
py::object readOnly(py::object a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

/// Square metres per scene unit², the factor from scene-unit areas to the module's m².
double squareMetres(const Scene& scene) { return scene.metresPerUnit() * scene.metresPerUnit(); }

Array vec3Array(const std::vector<Vec3>& v) {
  Array a({static_cast<py::ssize_t>(v.size()), py::ssize_t(3)});
  auto m = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < m.shape(0); ++i) m(i, 0) = v[i].x, m(i, 1) = v[i].y, m(i, 2) = v[i].z;
  return a;
}

Array channelsArray(const Channels& c) {
  const py::ssize_t n = static_cast<py::ssize_t>(c[0].size());
  Array a({n, py::ssize_t(3)});
  auto m = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) m(i, k) = c[k][i];
  return a;
}

/// (n, 3) or (n,) (grey: the same value in every channel) to three channels; `what` names the
/// argument in the error.
Channels toChannels(const Array& a, py::ssize_t n, const char* what) {
  Channels c = makeChannels(static_cast<int>(n));
  if (a.ndim() == 1 && a.shape(0) == n) {
    auto m = a.unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) c[0][i] = c[1][i] = c[2][i] = m(i);
  } else if (a.ndim() == 2 && a.shape(0) == n && a.shape(1) == 3) {
    auto m = a.unchecked<2>();
    for (py::ssize_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) c[k][i] = m(i, k);
  } else {
    throw py::value_error(std::string(what) + ": expected shape (" + std::to_string(n) +
                          ", 3) or (" + std::to_string(n) + ",), one row per patch");
  }
  return c;
}

Array imageArray(const RadianceImage& img) {
  Array a({py::ssize_t(img.height), py::ssize_t(img.width), py::ssize_t(3)});
  auto m = a.mutable_unchecked<3>();
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Vec3& v = img.radiance[static_cast<std::size_t>(y) * img.width + x];
      m(y, x, 0) = v.x, m(y, x, 1) = v.y, m(y, x, 2) = v.z;
    }
  return a;
}

py::object jsonToPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

// ---- holders: each keeps alive what its C++ object points into ----

struct PyScene {
  std::shared_ptr<const Scene> scene;
};

struct PyMesh {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const PatchMesh> mesh;
  std::vector<std::string> warnings;
  mutable std::shared_ptr<const RayScene> rays;  // built on first use, then shared
  const RayScene& rayScene() const {
    if (!rays) rays = std::make_shared<const RayScene>(*mesh);
    return *rays;
  }
};

struct PyFormFactors {
  PyMesh mesh;
  std::shared_ptr<const FormFactorResult> result;
};

struct PySystem {
  std::shared_ptr<const FormFactorMatrix> matrix;  // shared with PyFormFactors or owned
  std::optional<PyMesh> mesh;                      // when made from a mesh
  RadiositySystem system;
};

// ---- scene, mesh ----

PyScene loadScenePy(const std::filesystem::path& path, const std::string& units, bool repair) {
  LoadOptions options;
  options.units = units;
  options.repair = repair;
  return {std::make_shared<const Scene>(loadScene(path.string(), nullptr, options))};
}

PyMesh meshPy(const PyScene& s, int patches, double maxArea) {
  if (patches < 0 || !(maxArea >= 0) || !std::isfinite(maxArea))
    throw py::value_error("mesh: patches and max_area must be finite and >= 0 (0: no limit)");
  SubdivisionSettings settings;
  settings.targetPatches = patches;
  settings.maxArea = maxArea / squareMetres(*s.scene);  // m² to the subdivision's scene units²
  PyMesh m;
  m.scene = s.scene;
  m.mesh = std::make_shared<const PatchMesh>(subdivide(*s.scene, settings, &m.warnings));
  return m;
}

// ---- form factors ----

PyFormFactors formFactorsPy(const PyMesh& mesh, const std::string& method, int samples,
                            std::uint64_t seed, const std::string& precision, int pairLevels) {
  FormFactorSettings settings;
  const PluginChoice choice = splitPluginChoice(method);  // "name:key=value;..."
  settings.method = choice.name;
  settings.parameters = choice.parameters;
  settings.samples = samples;
  settings.seed = seed;
  if (precision == "float")
    settings.precision = FormFactorPrecision::Float;
  else if (precision != "double")
    throw py::value_error("form_factors: precision '" + precision +
                          "' is not known. Fix: 'double' (default) or 'float'");
  if (pairLevels < 0 || pairLevels > kMaxPairLevel)
    throw py::value_error(
        "form_factors: pair_levels must be in 0..8. Fix: 0 (adaptive contour "
        "for every pair) to 8 (default)");
  settings.quadrature.pairLevels = pairLevels;
  const RayScene& rays = mesh.rayScene();
  std::shared_ptr<FormFactorResult> result;
  {
    py::gil_scoped_release release;
    result = std::make_shared<FormFactorResult>(computeFormFactors(*mesh.mesh, rays, settings));
  }
  return {mesh, result};
}

/// F as a dense (n, n) array (a copy in double, whatever the storage).
Array denseArray(const FormFactorMatrix& f) {
  const py::ssize_t n = matrixSize(f);
  Array a({n, n});
  double* out = a.mutable_data();
  std::fill(out, out + n * n, 0.0);
  forEachNonZero(f, [&](int i, int j, double v) { out[static_cast<std::size_t>(i) * n + j] = v; });
  return a;
}

/// F as scipy.sparse.csr_matrix (zeros of a dense F left out).
py::object sparseMatrix(const FormFactorMatrix& f) {
  const int n = matrixSize(f);
  std::vector<std::int64_t> start(n + 1, 0);
  std::vector<std::int32_t> column;
  std::vector<double> value;
  forEachNonZero(f, [&](int i, int j, double v) {  // row by row, columns ascending
    ++start[i + 1];
    column.push_back(j);
    value.push_back(v);
  });
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  py::module_ sparse = py::module_::import("scipy.sparse");
  py::array_t<double> data(static_cast<py::ssize_t>(value.size()), value.data());
  py::array_t<std::int32_t> indices(static_cast<py::ssize_t>(column.size()), column.data());
  py::array_t<std::int64_t> indptr(static_cast<py::ssize_t>(start.size()), start.data());
  return sparse.attr("csr_matrix")(py::make_tuple(data, indices, indptr),
                                   py::arg("shape") = py::make_tuple(n, n));
}

// ---- arrays from Python, checked by solvers/system_input.h ----

/// A real array (bool, integer or floating dtype) as doubles in C order; `what` names it.
/// Complex, object and text dtypes are refused rather than cast (a cast drops imaginary parts).
Array realArray(const py::handle& object, const std::string& what) {
  // A masked array's data still holds the values behind its mask, which would be read as given.
  const py::module_ ma = py::module_::import("numpy.ma");
  if (ma.attr("isMaskedArray")(object).cast<bool>()) {
    const py::object masked =
        py::module_::import("numpy").attr("argwhere")(ma.attr("getmaskarray")(object));
    if (py::len(masked) > 0) {
      std::string index;
      for (const py::handle k : masked[py::int_(0)])
        index += (index.empty() ? "" : ", ") + py::str(k).cast<std::string>();
      throw py::value_error(what + "[" + index + "] is masked. Fix: " + what +
                            ".filled(value) with the value it stands for");
    }
  }
  const py::array a = py::array::ensure(object);
  if (!a) throw py::value_error(what + ": expected an array of numbers");
  const char kind = a.dtype().kind();
  if (kind != 'b' && kind != 'i' && kind != 'u' && kind != 'f')
    throw py::value_error(what + ": dtype " + py::str(a.dtype()).cast<std::string>() +
                          " is not real. Fix: a float array");
  return Array::ensure(a);
}

using IndexArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

/// A 1-D integer array as int64; uint64 values above 2^63 - 1 are refused, not wrapped.
IndexArray indexArray(const py::handle& object, const std::string& what) {
  const py::array a = py::array::ensure(object);
  if (!a || a.ndim() != 1) throw py::value_error(what + ": expected a 1-D integer array");
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::value_error(what + ": dtype " + py::str(a.dtype()).cast<std::string>() +
                          " is not an integer type. Fix: int32 or int64 indices");
  if (kind == 'u' && a.itemsize() == 8) {
    const auto u = py::array_t<std::uint64_t, py::array::c_style>::ensure(a);
    for (py::ssize_t k = 0; k < u.size(); ++k)
      if (u.data()[k] > std::uint64_t(INT64_MAX))
        throw py::value_error(what + "[" + std::to_string(k) +
                              "] = " + std::to_string(u.data()[k]) +
                              " is beyond int64. Fix: indices of an n x n matrix are 0 .. n - 1");
  }
  IndexArray out = IndexArray::ensure(a);
  if (!out) throw py::value_error(what + ": cannot be read as int64 indices");
  return out;
}

template <typename T, int Flags>
ArrayRef<T> refOf(const py::array_t<T, Flags>& a) {
  return {a.data(), static_cast<std::size_t>(a.size())};
}

ArrayInput inputOf(const Array& a) {
  return {refOf(a), std::vector<std::int64_t>(a.shape(), a.shape() + a.ndim())};
}

/// scipy's shape tuple as two integers (anything else refused).
std::pair<std::int64_t, std::int64_t> sparseShape(const py::object& f) {
  const py::tuple shape = py::tuple(f.attr("shape"));
  if (shape.size() != 2)
    throw py::value_error("F: expected a square (n, n) matrix, got " +
                          std::to_string(shape.size()) + " dimensions");
  return {shape[0].cast<std::int64_t>(), shape[1].cast<std::int64_t>()};
}

/// A matrix from Python: a dense (n, n) array or any scipy.sparse matrix or array. CSR, CSC
/// and COO arrays are read as they are and checked before scipy computes anything from them
/// (its sum_duplicates and tocsr index memory by them unchecked); other formats through tocoo(),
/// A sparse matrix's stored values, one real number per stored entry.
Array dataVector(const py::object& sparse) {
  Array data = realArray(sparse.attr("data"), "F.data");
  if (data.ndim() != 1) throw py::value_error("F.data: expected a 1-D array");
  return data;
}

/// which for them is Python and numpy code (bounds-checked), and the COO checks.
std::shared_ptr<FormFactorMatrix> matrixFromPython(const py::object& f) {
  py::module_ sparse = py::module_::import("scipy.sparse");
  if (!sparse.attr("issparse")(f).cast<bool>())
    return std::make_shared<FormFactorMatrix>(checkedDenseFormFactors(inputOf(realArray(f, "F"))));
  const std::string format = py::str(f.attr("format")).cast<std::string>();
  if (format == "csr" || format == "csc") {
    const auto [rows, cols] = sparseShape(f);
    const auto indptr = indexArray(f.attr("indptr"), "F.indptr");
    const auto indices = indexArray(f.attr("indices"), "F.indices");
    const Array data = dataVector(f);
    CompressedInput in;
    in.columns = format == "csc";
    in.rows = rows, in.cols = cols;
    in.indptr = refOf(indptr), in.indices = refOf(indices), in.data = refOf(data);
    return std::make_shared<FormFactorMatrix>(checkedCompressedFormFactors(in));
  }
  const py::object coo = format == "coo" ? f : f.attr("tocoo")();
  const auto [rows, cols] = sparseShape(coo);
  const auto row = indexArray(coo.attr("row"), "F.row");
  const auto col = indexArray(coo.attr("col"), "F.col");
  const Array data = dataVector(coo);
  CooInput in;
  in.rows = rows, in.cols = cols;
  in.row = refOf(row), in.col = refOf(col), in.data = refOf(data);
  return std::make_shared<FormFactorMatrix>(checkedCooFormFactors(in));
}

// ---- systems and solvers ----

PySystem systemFromFormFactors(const PyFormFactors& ff) {
  PySystem s;
  s.matrix = std::shared_ptr<const FormFactorMatrix>(ff.result, &ff.result->matrix);
  s.mesh = ff.mesh;
  s.system = makeRadiositySystem(*ff.mesh.scene, *ff.mesh.mesh, *s.matrix);
  return s;
}

PySystem systemFromArrays(const py::object& f, const py::object& area,
                          const py::object& reflectance, const py::object& emission) {
  PySystem s;
  s.matrix = matrixFromPython(f);
  s.system = checkedSystem(*s.matrix, inputOf(realArray(area, "area")),
                           inputOf(realArray(reflectance, "reflectance")),
                           inputOf(realArray(emission, "emission")));
  s.system.validate();
  return s;
}

ResidualNorm parseNorm(const std::string& norm) {
  if (norm == "relative") return ResidualNorm::Relative;
  if (norm == "per-patch") return ResidualNorm::PerPatch;
  throw py::value_error("norm '" + norm + "' is not known. Fix: 'relative' or 'per-patch'");
}

/// A solver written in Python, run by the same driver (stopping rules, history) as the
/// built-in ones. The object has start(system) and step(), and radiosity() returning B as
/// (n, 3); optionally name and sweeps(). The residual is computed here from F, exactly, so a
/// student's solver is held to the measure the built-in solvers report.
class PythonSolver final : public Solver {
 public:
  PythonSolver(py::object object, py::object system)
      : m_object(std::move(object)), m_pySystem(std::move(system)) {}
  std::string name() const override {
    return py::hasattr(m_object, "name") ? py::str(m_object.attr("name")).cast<std::string>()
                                         : std::string("python");
  }
  std::string describe() const override {
    return "Python solver " + py::str(m_object.get_type().attr("__name__")).cast<std::string>();
  }
  void start(const RadiositySystem& system, const SolverSettings& settings) override {
    system.validate();
    m_system = &system;
    m_norm = settings.norm;
    m_steps = 0;
    m_object.attr("start")(m_pySystem);
    update();
  }
  void step() override {
    m_object.attr("step")();
    ++m_steps;
    update();
  }
  const Channels& radiosity() const override { return m_b; }
  double residual() const override { return m_residual; }
  double unshotPower() const override { return m_power; }
  double sweeps() const override {
    return py::hasattr(m_object, "sweeps") ? m_object.attr("sweeps")().cast<double>()
                                           : static_cast<double>(m_steps);
  }

 private:
  void update() {
    const Array b = m_object.attr("radiosity")().cast<Array>();
    m_b = toChannels(b, m_system->size(), "radiosity() of the Python solver");
    const Channels r = residualVector(*m_system, m_b);
    m_residual = residualMeasure(*m_system, r, m_b, m_norm);
    m_power = residualPower(*m_system, r);
  }
  py::object m_object, m_pySystem;
  const RadiositySystem* m_system = nullptr;
  ResidualNorm m_norm = ResidualNorm::Relative;
  Channels m_b;
  double m_residual = 0, m_power = 0;
  long m_steps = 0;
};

py::dict resultDict(const SolveResult& r) {
  py::dict d;
  d["solver"] = r.solver;
  d["description"] = r.description;
  d["converged"] = r.converged;
  d["exit"] = r.exit;
  d["reason"] = r.reason;
  d["iterations"] = r.iterations;
  d["seconds"] = r.seconds;
  d["residual"] = r.residual;
  d["checked_residual"] = r.checkedResidual;
  d["spectral_radius"] = r.spectralRadius;
  d["radiosity"] = channelsArray(r.radiosity);
  const py::ssize_t rows = static_cast<py::ssize_t>(r.history.size());
  py::array_t<long> iteration(rows);
  Array seconds(rows), residual(rows), power(rows), sweeps(rows);
  for (py::ssize_t k = 0; k < rows; ++k) {
    const HistoryRow& h = r.history[k];
    iteration.mutable_at(k) = h.iteration, seconds.mutable_at(k) = h.seconds;
    residual.mutable_at(k) = h.residual, power.mutable_at(k) = h.unshotPower;
    sweeps.mutable_at(k) = h.sweeps;
  }
  py::dict history;
  history["iteration"] = iteration, history["seconds"] = seconds;
  history["residual"] = residual, history["unshot_power"] = power, history["sweeps"] = sweeps;
  d["history"] = history;
  return d;
}

/// A built-in solver's parameters: "key=value,..." text or a dict {key: value} of numbers,
/// bools (1 or 0) or number texts. A dict's texts go through the text parser and its values
/// are checked by the solver as the text form's are, so both forms refuse the same values with
/// the same message; unknown keys are left for makeSolver.
Params solverParams(const py::object& params) {
  if (py::isinstance<py::str>(params)) return Params::parse(params.cast<std::string>());
  if (!py::isinstance<py::dict>(params))
    throw py::type_error("params: expected text \"key=value,...\" or a dict {key: value}, got " +
                         py::str(params.get_type().attr("__name__")).cast<std::string>() +
                         ". Fix: e.g. params={\"omega\": 1.2}");
  Params result;
  for (const auto& [k, v] : params.cast<py::dict>()) {
    if (!py::isinstance<py::str>(k))
      throw py::value_error("params: key " + py::repr(k).cast<std::string>() +
                            " is not a string. Fix: the parameter's name, e.g. \"omega\"");
    const std::string key = k.cast<std::string>();
    // The text form separates items by ',' and key from value by '=': either inside a key or
    // a text value would be read as another parameter (and it trims spaces around keys).
    if (key.empty() || key.find_first_of(",= \t") != std::string::npos)
      throw py::value_error("params: key '" + key +
                            "' is not a parameter name. Fix: a name such as \"omega\"");
    if (py::isinstance<py::bool_>(v)) {
      result.set(key, v.cast<bool>() ? 1.0 : 0.0);
    } else if (py::isinstance<py::str>(v)) {
      const std::string item = key + "=" + v.cast<std::string>();
      if (item.find(',') != std::string::npos)
        throw py::value_error("solver parameter '" + item +
                              "': expected key=number, e.g. omega=1.5");
      result.set(key, Params::parse(item).values().at(key));
    } else {
      const py::object number = py::module_::import("numbers").attr("Real");
      if (!py::isinstance(v, number))
        throw py::value_error("solver parameter '" + key + "=" + py::repr(v).cast<std::string>() +
                              "': expected a number, e.g. {\"omega\": 1.5}");
      result.set(key, py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>());
    }
  }
  return result;
}

py::dict solvePy(const py::object& pySystem, const py::object& solver, const py::object& params,
                 double tolerance, long maxIterations, double maxSeconds, const std::string& norm) {
  const PySystem& s = pySystem.cast<const PySystem&>();
  SolverSettings settings;
  settings.tolerance = tolerance;
  settings.maxIterations = maxIterations;
  settings.maxSeconds = maxSeconds;
  settings.norm = parseNorm(norm);
  if (!(tolerance > 0)) throw py::value_error("tolerance must be > 0");
  if (py::isinstance<py::str>(solver)) {
    std::unique_ptr<Solver> builtIn = makeSolver(solver.cast<std::string>(), solverParams(params));
    SolveResult r;
    {
      py::gil_scoped_release release;
      r = solve(*builtIn, s.system, settings);
    }
    return resultDict(r);
  }
  if (!(py::isinstance<py::str>(params) || py::isinstance<py::dict>(params)) ||
      py::len(params) != 0)
    throw py::value_error("params are for built-in solvers; a Python solver takes its own");
  if (py::hasattr(solver, "step") && py::hasattr(solver, "start")) {
    PythonSolver adapter(solver, pySystem);
    return resultDict(solve(adapter, s.system, settings));
  }
  if (!PyCallable_Check(solver.ptr()))
    throw py::type_error(
        "solver: expected a built-in solver's name, an object with start(system), step() and "
        "radiosity(), or a function system -> B");
  // A function that returns B at once: one step, measured like any other.
  s.system.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const Array b = solver(pySystem).cast<Array>();
  SolveResult r;
  r.solver = "python";
  r.description = "Python function " + py::str(solver.attr("__name__")).cast<std::string>();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.iterations = 1;
  r.radiosity = toChannels(b, s.system.size(), "the Python function's B");
  const Channels res = residualVector(s.system, r.radiosity);
  r.checkedResidual = r.residual = residualMeasure(s.system, res, r.radiosity, settings.norm);
  r.converged = r.residual <= tolerance;
  r.exit = r.converged ? "converged" : "not_converged";
  r.reason = r.converged ? "residual within the tolerance" : "residual above the tolerance";
  r.history.push_back({1, r.seconds, r.residual, residualPower(s.system, res), 1.0});
  return resultDict(r);
}

// ---- images ----

Camera cameraFor(const PyMesh& m, const std::optional<std::string>& camera) {
  return camera ? parseCamera("camera", *camera) : sceneCamera(*m.scene, *m.mesh);
}

void checkImageSize(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw py::value_error("width and height must be in 1..16384");
}

Array renderRadiosityPy(const PyMesh& m, const Array& radiosity, int width, int height,
                        int samplesPerAxis, bool smooth, const std::optional<std::string>& camera) {
  checkImageSize(width, height);
  const Channels b = toChannels(radiosity, m.mesh->size(), "radiosity");
  ImageSettings settings;
  settings.width = width, settings.height = height;
  settings.samplesPerAxis = samplesPerAxis, settings.smooth = smooth;
  const Camera cam = cameraFor(m, camera);
  const std::vector<Vec3> bv = toVec3(b);
  const std::vector<bool> twoSided = m.scene->twoSidedSurfaces();
  const RayScene& rays = m.rayScene();
  RadianceImage img;
  {
    py::gil_scoped_release release;
    img = renderRadiosity(*m.mesh, rays, cam, bv, twoSided, settings);
  }
  return imageArray(img);
}

py::tuple pathTracePy(const PyMesh& m, int spp, int width, int height, std::uint64_t seed,
                      const std::string& sampler, const std::optional<std::string>& camera) {
  checkImageSize(width, height);
  if (spp < 1) throw py::value_error("spp must be >= 1");
  PathTraceSettings settings;
  settings.width = width, settings.height = height, settings.samplesPerPixel = spp;
  settings.seed = seed;
  settings.sampler = parseSamplerType(sampler);
  const Camera cam = cameraFor(m, camera);
  const RayScene& rays = m.rayScene();
  MonteCarloImage img;
  {
    py::gil_scoped_release release;
    const ShadingScene shading(*m.scene, *m.mesh, rays, BsdfSettings{});
    img = renderPathTraced(shading, cam, settings);
  }
  RadianceImage variance = img.image;
  variance.radiance = img.varianceOfMean;
  return py::make_tuple(imageArray(img.image), imageArray(variance));
}

/// One image of a scene by any of `radkit render`'s modes, through the integrator registry
/// (integrators/integrator.h) the command line uses: the same settings give the same image.
Array renderScenePy(const PyScene& s, const std::string& shading, int width, int height, int spp,
                    std::uint64_t seed, int patches, double maxArea, std::size_t photons,
                    const std::string& sampler, const std::optional<std::string>& camera) {
  checkImageSize(width, height);
  if (spp < 1) throw py::value_error("render_scene: spp must be >= 1");
  if (patches < 0 || !(maxArea >= 0) || !std::isfinite(maxArea))
    throw py::value_error("render_scene: patches and max_area must be finite and >= 0");
  if (photons < 1) throw py::value_error("render_scene: photons must be >= 1");
  integratorRegistry().at(splitPluginChoice(shading).name);  // refused before any work
  RenderSettings settings;
  settings.film.width = width, settings.film.height = height, settings.film.samplesPerPixel = spp;
  settings.film.seed = seed;
  settings.film.sampler = parseSamplerType(sampler);
  settings.formFactors.seed = seed;
  settings.mesh.targetPatches = patches;
  settings.mesh.maxArea = maxArea / squareMetres(*s.scene);  // m² to the scene's units²
  settings.photons = photons;
  settings.camera = chooseCamera(*s.scene, camera.value_or(""), "camera");
  RenderResult r;
  {
    py::gil_scoped_release release;
    r = renderImage(shading, *s.scene, settings);
  }
  return imageArray(r.image);
}

PhotonSettings photonSettings(const char* what, std::size_t photons, std::uint64_t seed) {
  if (photons < 1) throw py::value_error(std::string(what) + ": photons must be >= 1");
  PhotonSettings settings;
  settings.photons = photons;
  settings.seed = seed;
  return settings;
}

/// Traces the mesh's photons; call without the GIL.
PhotonTrace tracePy(const PyMesh& m, const RayScene& rays, const PhotonSettings& settings) {
  const EmitterSampler emitters = photonEmitters(*m.scene, *m.mesh);
  return tracePhotons(*m.scene, *m.mesh, rays, emitters, settings);
}

// ---- the main job ----

/// The options of radkit run, solvers and formfactors as keywords; None leaves a setting to the
/// preset or the method, as an option not given does.
struct RunOptions {
  std::optional<std::filesystem::path> out;
  std::string kind = "run";
  std::optional<std::string> method, preset, ff, camera;
  std::optional<int> patches, ffSamples;
  std::optional<double> maxArea, tolerance;
  std::optional<long> maxIterations;
  std::optional<std::size_t> memoryBudget;
  py::object solvers;
  std::uint64_t seed = 1;
  std::optional<double> epsilon, minArea;
  std::optional<int> raysPerLink, rounds;
  std::optional<std::string> gather;
  bool adaptive = false;
  int checkLinks = 0;
  bool render = true, photometric = false, smooth = false, writeMatrix = false;
  int width = 512, height = 512;
  std::string units;
  bool repair = false;
};

/// radkit's main job by the library call the command line makes (job/job.h): the run folder
/// written, report.json as a dict, and the solution (the patches, or the hierarchy's leaves,
/// as a Mesh with their radiosity). Areas are m² here, as everywhere in the module.
py::dict runPy(const py::object& sceneArg, const RunOptions& o) {
  JobSettings s;
  s.kind = o.kind == "run"           ? JobKind::Run
           : o.kind == "solvers"     ? JobKind::Solvers
           : o.kind == "formfactors" ? JobKind::FormFactors
                                     : throw py::value_error("run: kind '" + o.kind +
                                                             "' is not run, solvers or "
                                                             "formfactors");
  if (o.out) s.out = o.out->string();
  if (o.method) {
    if (*o.method != "dense" && *o.method != "hierarchical")
      throw py::value_error("run: method '" + *o.method + "' is not dense or hierarchical");
    s.method = *o.method == "hierarchical" ? JobMethod::Hierarchical : JobMethod::Dense;
  }
  if (o.preset) s.preset = *o.preset;
  if (o.camera) s.camera = *o.camera;
  s.formFactorMethod = o.ff;
  s.formFactorSamples = o.ffSamples;
  s.tolerance = o.tolerance;
  s.maxIterations = o.maxIterations;
  s.memoryBudget = o.memoryBudget;
  s.seed = o.seed;
  if (!o.solvers.is_none()) {
    std::string text;
    if (py::isinstance<py::str>(o.solvers)) {
      text = o.solvers.cast<std::string>();
    } else {
      for (const py::handle& name : o.solvers)
        text += (text.empty() ? "" : ",") + py::str(name).cast<std::string>();
    }
    s.solvers = parseSolverList(text);
  }
  if (o.adaptive) s.adaptive = AdaptiveSettings{};
  if (o.epsilon) s.hierarchical.epsilon = *o.epsilon;
  if (o.raysPerLink) s.hierarchical.raysPerLink = *o.raysPerLink;
  if (o.rounds) s.hierarchical.rounds = *o.rounds;
  if (o.gather) s.hierarchical.order = parseGatherOrder(*o.gather);
  s.checkLinks = o.checkLinks;
  s.render = o.render, s.photometric = o.photometric, s.smooth = o.smooth;
  s.writeMatrix = o.writeMatrix;
  s.imageWidth = o.width, s.imageHeight = o.height;

  std::vector<std::string> lines;
  PipelineLog log;
  log.message = [&](const std::string& line) { lines.push_back(line); };
  std::optional<JobResult> r;
  {
    Scene scene;
    LoadReport loaded;
    if (py::isinstance<PyScene>(sceneArg)) {
      if (!o.units.empty() || o.repair)
        throw py::value_error(
            "run: units and repair are for a scene file; this Scene is "
            "loaded (give them to load_scene)");
      scene = *sceneArg.cast<const PyScene&>().scene;
    } else {
      const std::string path = sceneArg.cast<std::filesystem::path>().string();
      LoadOptions load;
      load.units = o.units, load.repair = o.repair;
      py::gil_scoped_release release;
      scene = loadJobScene(path, load, "", log, &loaded);
    }
    // m² to the scene's units², as the job's settings take them
    const double unit2 = squareMetres(scene);
    if (o.patches || o.maxArea)
      s.mesh = SubdivisionSettings{o.maxArea.value_or(0) / unit2, o.patches.value_or(0)};
    if (o.minArea) s.hierarchical.minArea = *o.minArea / unit2;
    py::gil_scoped_release release;
    r.emplace(runJob(std::move(scene), s, log, loaded));
  }
  py::module_ warnings = py::module_::import("warnings");
  for (const std::string& line : lines)
    if (line.rfind("warning: ", 0) == 0) warnings.attr("warn")(line.substr(9));
  py::dict d;
  d["out"] = r->out;
  d["report"] = jsonToPython(r->report);
  d["log"] = lines;
  PyMesh mesh;
  mesh.scene = std::make_shared<const Scene>(std::move(r->scene));
  if (r->hierarchical) {
    mesh.mesh = std::make_shared<const PatchMesh>(std::move(r->hierarchical->leaves));
    d["radiosity"] = vec3Array(r->hierarchical->radiosity);
  } else {
    mesh.mesh = std::make_shared<const PatchMesh>(std::move(r->dense->mesh));
    if (!r->dense->solves.empty()) d["radiosity"] = vec3Array(r->dense->radiosity);
  }
  d["mesh"] = py::cast(std::move(mesh));
  return d;
}

// ---- hierarchical radiosity ----

/// The hierarchical method (docs/hierarchical.md) on a loaded scene, by the same library call
/// `radkit run --method hierarchical` makes: its leaves as a Mesh, their radiosity and
/// irradiance, and the solve's account.
py::dict hierarchicalPy(const PyScene& s, double epsilon, int raysPerLink, int rounds,
                        const std::string& order, std::uint64_t seed, double minArea,
                        double tolerance, long maxIterations) {
  if (!(minArea >= 0) || !std::isfinite(minArea))
    throw py::value_error("hierarchical: min_area must be finite and >= 0 (0: the default)");
  HierarchicalSettings settings;
  settings.epsilon = epsilon;
  settings.raysPerLink = raysPerLink;
  settings.rounds = rounds;
  settings.order = parseGatherOrder(order);
  settings.seed = seed;
  settings.minArea = minArea / squareMetres(*s.scene);  // m² to the scene's units²
  settings.stopping.tolerance = tolerance;
  settings.stopping.maxIterations = maxIterations;
  validateHierarchicalSettings(settings);
  std::optional<HierarchicalResult> r;
  {
    py::gil_scoped_release release;
    r.emplace(solveHierarchical(*s.scene, settings));
  }
  PyMesh leaves;
  leaves.scene = s.scene;
  leaves.mesh = std::make_shared<const PatchMesh>(std::move(r->leaves));
  py::dict d;
  d["mesh"] = py::cast(std::move(leaves));
  d["radiosity"] = vec3Array(r->radiosity);
  d["irradiance"] = vec3Array(r->irradiance);
  d["converged"] = r->solve.converged;
  d["reason"] = r->solve.reason;
  d["iterations"] = r->solve.iterations;
  long long links = 0;
  for (long long n : r->linksByKind) links += n;
  d["links"] = links;
  d["rays"] = r->raysCast;
  d["min_area"] = r->minArea * squareMetres(*s.scene);
  py::list roundList;
  for (const HierarchicalRound& round : r->rounds) {
    py::dict row;
    row["epsilon"] = round.epsilon, row["links"] = round.links, row["leaves"] = round.leaves;
    row["rays"] = round.rays, row["sweeps"] = round.sweeps;
    roundList.append(row);
  }
  d["rounds"] = roundList;
  d["relative_imbalance"] = r->energy.relativeImbalance;
  return d;
}

py::dict photonsPy(const PyMesh& m, std::size_t photons, std::uint64_t seed) {
  const PhotonSettings settings = photonSettings("photons", photons, seed);
  const RayScene& rays = m.rayScene();
  PhotonRadiosity estimate;
  PhotonTraceStats stats;
  {
    py::gil_scoped_release release;
    PhotonTrace trace = tracePy(m, rays, settings);
    stats = trace.stats;
    estimate = estimateRadiosity(*m.scene, *m.mesh, trace.photons, photons);
  }
  py::dict d;
  d["radiosity"] = vec3Array(estimate.radiosity);
  d["radiosity_error"] = vec3Array(estimate.radiosityError);
  d["irradiance"] = vec3Array(estimate.irradiance);
  py::list surfaces;
  for (const SurfaceEstimate& e : estimate.surfaces) {
    py::dict s;
    s["name"] = e.name, s["area"] = e.area * squareMetres(*m.scene);
    s["radiosity"] = vec3Array({e.radiosity}).attr("reshape")(3);
    s["radiosity_error"] = vec3Array({e.radiosityError}).attr("reshape")(3);
    s["photons"] = e.photons;
    surfaces.append(s);
  }
  d["surfaces"] = surfaces;
  d["stored"] = stats.stored, d["escaped"] = stats.escaped, d["seconds"] = stats.seconds;
  return d;
}

/// A traced photon map: the photons as arrays and the k-nearest irradiance estimate at any
/// points, the one `radkit photons` images use (lab 6 compares a student's with it).
struct PyPhotonMap {
  PyMesh mesh;  // the map points into the mesh
  std::shared_ptr<const PhotonMap> map;
  PhotonTraceStats stats;
  Vec3 emittedPower;
};

/// One Vec3 per stored photon times `scale`, (m, 3).
Array photonVectors(const PyPhotonMap& p, Vec3 (Photon::*get)() const, double scale) {
  std::vector<Vec3> v;
  v.reserve(p.map->size());
  for (const Photon& ph : p.map->photons()) v.push_back((ph.*get)() * scale);
  return vec3Array(v);
}

/// One integer per stored photon, (m,).
template <class Get>
py::array_t<std::int64_t> photonIndices(const PyPhotonMap& p, Get get) {
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(p.map->size()));
  std::size_t i = 0;
  for (const Photon& ph : p.map->photons()) a.mutable_at(i++) = get(ph);
  return a;
}

PyPhotonMap photonMapPy(const PyMesh& m, std::size_t photons, std::uint64_t seed) {
  const PhotonSettings settings = photonSettings("photon_map", photons, seed);
  const RayScene& rays = m.rayScene();
  PyPhotonMap out;
  out.mesh = m;
  {
    py::gil_scoped_release release;
    PhotonTrace trace = tracePy(m, rays, settings);
    out.stats = trace.stats;
    out.emittedPower = trace.emittedPower;
    out.map = std::make_shared<const PhotonMap>(*m.mesh, std::move(trace.photons));
  }
  return out;
}

IrradianceFilter parseFilterPy(const std::string& name) {
  if (name == "epanechnikov") return IrradianceFilter::Epanechnikov;
  if (name == "cone") return IrradianceFilter::Cone;
  throw py::value_error("filter '" + name + "' is not known. Fix: 'epanechnikov' or 'cone'");
}

/// (q, 3) points, or one point (3,) (then every row of the other argument uses it).
std::vector<Vec3> toPoints(const Array& a, const char* what) {
  std::vector<Vec3> v;
  if (a.ndim() == 1 && a.shape(0) == 3) {
    auto m = a.unchecked<1>();
    v.push_back({m(0), m(1), m(2)});
  } else if (a.ndim() == 2 && a.shape(1) == 3) {
    auto m = a.unchecked<2>();
    for (py::ssize_t i = 0; i < m.shape(0); ++i) v.push_back({m(i, 0), m(i, 1), m(i, 2)});
  } else {
    throw py::value_error(std::string(what) + ": expected shape (q, 3) or (3,)");
  }
  for (const Vec3& p : v)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw py::value_error(std::string(what) + ": every coordinate must be finite");
  return v;
}

// ---- materials, the sky and outdoor jobs ----

/// A plugin's parameters for Python as the registry's "key=value, key=r g b" text: given so, or
/// turned into it from a dict of numbers, three-number sequences (rgb) and texts, so both forms
/// are read, and refused, by the same parser (Params::parse).
std::string pluginParamsText(const py::object& params, const std::string& what) {
  if (params.is_none()) return "";
  if (py::isinstance<py::str>(params)) return params.cast<std::string>();
  if (!py::isinstance<py::dict>(params))
    throw py::type_error(what + " params: expected text \"key=value, ...\" or a dict");
  std::string text;
  for (const auto& [k, v] : params.cast<py::dict>()) {
    const std::string key = py::str(k).cast<std::string>();
    std::string value;
    if (py::isinstance<py::str>(v)) {
      value = v.cast<std::string>();
    } else if (py::isinstance<py::sequence>(v)) {
      for (const py::handle& x : v.cast<py::sequence>())
        value += (value.empty() ? "" : " ") +
                 py::repr(py::float_(py::reinterpret_borrow<py::object>(x))).cast<std::string>();
    } else {
      value = py::repr(py::float_(py::reinterpret_borrow<py::object>(v))).cast<std::string>();
    }
    if (key.find_first_of(",=") != std::string::npos || value.find(',') != std::string::npos)
      throw py::value_error(what + " params: '" + key + "=" + value +
                            "' holds a ',' or '=' the text form would split");
    text += (text.empty() ? "" : ", ") + key + "=" + value;
  }
  return text;
}

/// A BSDF of the registry, evaluated on arrays of local directions (+z the front normal).
struct PyBsdf {
  std::shared_ptr<const Bsdf> bsdf;
  std::string name;
};

PyBsdf makeBsdfPy(const std::string& name, const py::object& params) {
  return {std::shared_ptr<const Bsdf>(
              makeBsdf(name, Params::parse(pluginParamsText(params, "bsdf \"" + name + "\"")))),
          name};
}

/// Rows of wo and wi, one of them possibly a single (3,) direction for every row.
std::pair<std::vector<Vec3>, std::vector<Vec3>> directionPairs(const Array& wo, const Array& wi) {
  std::vector<Vec3> o = toPoints(wo, "wo"), i = toPoints(wi, "wi");
  if (o.size() == 1 && i.size() > 1) o.assign(i.size(), o.front());
  if (i.size() == 1 && o.size() > 1) i.assign(o.size(), i.front());
  if (o.size() != i.size())
    throw py::value_error("wo and wi: " + std::to_string(o.size()) + " and " +
                          std::to_string(i.size()) + " rows. Fix: the same count, or one (3,)");
  for (std::vector<Vec3>* v : {&o, &i})
    for (Vec3& d : *v) {
      if (!(length(d) > 0)) throw py::value_error("wo, wi: a direction of length 0");
      d = normalize(d);
    }
  return {o, i};
}

Array bsdfEvalPy(const PyBsdf& b, const Array& wo, const Array& wi) {
  const auto [o, i] = directionPairs(wo, wi);
  std::vector<Vec3> f(o.size());
  for (std::size_t k = 0; k < o.size(); ++k) f[k] = b.bsdf->eval(o[k], i[k]);
  return vec3Array(f);
}

Array bsdfPdfPy(const PyBsdf& b, const Array& wo, const Array& wi) {
  const auto [o, i] = directionPairs(wo, wi);
  Array pdf{py::ssize_t(o.size())};
  for (std::size_t k = 0; k < o.size(); ++k) pdf.mutable_at(k) = b.bsdf->pdf(o[k], i[k]);
  return pdf;
}

/// Samples wi for each wo from (n, 3) uniform numbers (the lobe, then the direction); a lost
/// sample has weight and pdf 0.
py::dict bsdfSamplePy(const PyBsdf& b, const Array& wo, const Array& u) {
  if (u.ndim() != 2 || u.shape(1) != 3) throw py::value_error("u: expected shape (n, 3)");
  const std::size_t n = std::size_t(u.shape(0));
  std::vector<Vec3> o = toPoints(wo, "wo");
  if (o.size() == 1) o.assign(n, o.front());
  if (o.size() != n) throw py::value_error("wo and u: different row counts");
  std::vector<Vec3> wi(n), weight(n);
  Array pdf{py::ssize_t(n)};
  py::array_t<bool> delta{py::ssize_t(n)};
  auto um = u.unchecked<2>();
  for (std::size_t k = 0; k < n; ++k) {
    const std::optional<BsdfSample> s =
        b.bsdf->sample(normalize(o[k]), um(k, 0), um(k, 1), um(k, 2));
    pdf.mutable_at(k) = s ? s->pdf : 0.0;
    delta.mutable_at(k) = s && s->delta;
    if (s) wi[k] = s->wi, weight[k] = s->weight;
  }
  py::dict d;
  d["wi"] = vec3Array(wi), d["weight"] = vec3Array(weight), d["pdf"] = pdf, d["delta"] = delta;
  return d;
}

/// The physical sky's radiance (atmosphere/) toward directions in the observer's frame
/// (x east, y north, z up), as radkit sky computes every pixel.
Array skyRadiancePy(const Array& directions, double elevation, double azimuth, double altitude,
                    double density, int viewSamples, int lightSamples, bool multiple,
                    const std::string& rayleigh) {
  if (!(density > 0) || !(altitude >= 0) || viewSamples < 1 || lightSamples < 1)
    throw py::value_error("sky_radiance: density > 0, altitude >= 0 and samples >= 1");
  const std::vector<Vec3> dirs = toPoints(directions, "directions");
  atmosphere::AtmosphereParameters parameters;
  parameters.relativeDensity = density;
  atmosphere::useRayleigh(parameters, atmosphere::rayleighAir(rayleigh));
  std::vector<Vec3> radiance(dirs.size());
  {
    py::gil_scoped_release release;
    const atmosphere::Atmosphere air(parameters);
    atmosphere::SkySettings sky;
    sky.viewSamples = viewSamples, sky.lightSamples = lightSamples;
    sky.multipleScattering = multiple;
    const Vec3 sun = atmosphere::sunDirection(elevation, azimuth);
    const Vec3 eye = air.pointAtAltitude(altitude);
    tbb::parallel_for(std::size_t(0), dirs.size(), [&](std::size_t k) {
      radiance[k] =
          length(dirs[k]) > 0 ? air.skyRadiance(eye, normalize(dirs[k]), sun, sky) : Vec3{};
    });
  }
  return vec3Array(radiance);
}

/// A phase function of the registry (phase/), on arrays of cos θ between the directions of
/// travel before and after scattering.
struct PyPhase {
  std::shared_ptr<const PhaseFunction> phase;
};

PyPhase makePhasePy(const std::string& name, const py::object& params) {
  const std::string text = pluginParamsText(params, "phase function \"" + name + "\"");
  return {std::shared_ptr<const PhaseFunction>(makePhaseFunction(name, text))};
}

Array phaseEvalPy(const PyPhase& p, const Array& mu) {
  Array out{mu.request().shape};
  const double* in = mu.data();
  double* o = out.mutable_data();
  for (py::ssize_t k = 0; k < mu.size(); ++k) {
    if (!(in[k] >= -1 && in[k] <= 1))
      throw py::value_error("mu[" + std::to_string(k) + "] = " + formatValue("%g", in[k]) +
                            " is not a cosine in [-1, 1]");
    o[k] = p.phase->eval(in[k]);
  }
  return out;
}

/// cos θ drawn from uniform numbers u, with the density (1/sr) of each.
py::tuple phaseSamplePy(const PyPhase& p, const Array& u) {
  Array mu{u.request().shape}, pdf{u.request().shape};
  const double* in = u.data();
  for (py::ssize_t k = 0; k < u.size(); ++k) {
    double density = 0;
    mu.mutable_data()[k] = p.phase->sample(in[k], density);
    pdf.mutable_data()[k] = density;
  }
  return py::make_tuple(mu, pdf);
}

/// A participating medium as a volume scene's "medium" describes it (docs/formats.md, "Volume
/// scenes"): a cloud layer or a homogeneous box, with its phase function.
struct PyMedium {
  std::shared_ptr<const media::Medium> medium;
  std::string kind, phaseName, phaseParams;
};

PyMedium makeMediumPy(const py::object& description) {
  const std::string text =
      py::isinstance<py::str>(description)
          ? description.cast<std::string>()
          : py::module_::import("json").attr("dumps")(description).cast<std::string>();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw py::value_error(std::string("Medium: not JSON: ") + e.what());
  }
  PyMedium m;
  m.medium = media::parseMedium(j, "Medium(...)", &m.kind, &m.phaseName, &m.phaseParams);
  return m;
}

Array mediumExtinctionPy(const PyMedium& m, const Array& points) {
  const std::vector<Vec3> p = toPoints(points, "points");
  Array out{py::ssize_t(p.size())};
  double* o = out.mutable_data();
  for (std::size_t k = 0; k < p.size(); ++k) o[k] = m.medium->extinction(p[k]);
  return out;
}

/// Transmittance along o + t·d for t in [0, distance) by ratio tracking (unbiased): the mean of
/// `samples` estimates per ray and its standard error. Ray k's stream is keyed (seed, k), so the
/// result does not depend on the thread count.
py::tuple mediumTransmittancePy(const PyMedium& m, const Array& origins, const Array& directions,
                                const Array& distances, int samples, std::uint64_t seed) {
  if (samples < 2) throw py::value_error("transmittance: samples must be >= 2 (for the error)");
  const std::vector<Vec3> o = toPoints(origins, "origins"), d = toPoints(directions, "directions");
  const double* t = distances.data();
  const std::size_t n = std::max({o.size(), d.size(), std::size_t(distances.size())});
  for (std::size_t size : {o.size(), d.size(), std::size_t(distances.size())})
    if (size != n && size != 1)
      throw py::value_error("transmittance: origins, directions and distances differ in length");
  for (const Vec3& dir : d)
    if (!(length(dir) > 0)) throw py::value_error("transmittance: a direction is zero");
  for (py::ssize_t k = 0; k < distances.size(); ++k)
    if (!(t[k] >= 0)) throw py::value_error("transmittance: a distance is negative or NaN");
  Array mean{py::ssize_t(n)}, error{py::ssize_t(n)};
  double* mo = mean.mutable_data();
  double* eo = error.mutable_data();
  {
    py::gil_scoped_release release;
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t k) {
      const Vec3 ok = o[o.size() == 1 ? 0 : k], dk = normalize(d[d.size() == 1 ? 0 : k]);
      const double tk = t[distances.size() == 1 ? 0 : k];
      Rng rng(seed, k, 0);
      double sum = 0, sum2 = 0;
      for (int s = 0; s < samples; ++s) {
        const double x = media::ratioTrack(*m.medium, ok, dk, tk, rng);
        sum += x, sum2 += x * x;
      }
      mo[k] = sum / samples;
      eo[k] = std::sqrt(std::max(0.0, sum2 / samples - mo[k] * mo[k]) / (samples - 1));
    });
  }
  return py::make_tuple(mean, error);
}

/// A sky model of the registry (sky/), prepared for a sun, on arrays of local directions.
struct PySky {
  std::shared_ptr<SkyRadiance> sky;
  std::string name;
};

PySky makeSkyPy(const std::string& name, const py::object& params, double sunElevation,
                double sunAzimuth) {
  const std::string text = pluginParamsText(params, "sky model \"" + name + "\"");
  std::shared_ptr<SkyRadiance> sky = skyRegistry().make(name, Params::parse(text));
  if (!(std::abs(sunElevation) <= 90 && std::isfinite(sunAzimuth)))
    throw py::value_error("sun_elevation must lie in [-90, 90] degrees, sun_azimuth be finite");
  {
    py::gil_scoped_release release;
    sky->prepare(true, sunElevation, sunAzimuth);
  }
  return {sky, name};
}

/// Radiance toward (n, 3) local directions; zero at and below the horizon, where a scene's
/// ground takes over.
Array skyModelRadiancePy(const PySky& s, const Array& directions) {
  const std::vector<Vec3> dirs = toPoints(directions, "directions");
  std::vector<Vec3> radiance(dirs.size());
  for (std::size_t k = 0; k < dirs.size(); ++k)
    if (length(dirs[k]) > 0 && dirs[k].z > 0) radiance[k] = s.sky->radiance(normalize(dirs[k]));
  return vec3Array(radiance);
}

py::dict reportDict(const std::string& out, const nlohmann::json& report) {
  py::dict d;
  d["out"] = out;
  d["report"] = jsonToPython(report);
  return d;
}

py::dict photonIrradiancePy(const PyPhotonMap& pm, const Array& points, const Array& normals, int k,
                            const std::string& filterName) {
  if (k < 2) throw py::value_error("irradiance: k must be >= 2 (the k-th photon has weight 0)");
  const IrradianceFilter filter = parseFilterPy(filterName);
  const std::vector<Vec3> x = toPoints(points, "points");
  std::vector<Vec3> n = toPoints(normals, "normals");
  if (n.size() != 1 && n.size() != x.size())
    throw py::value_error("normals: give one normal (3,) or one per point (q, 3)");
  for (Vec3& v : n) {
    const double len = length(v);
    if (!(len > 0)) throw py::value_error("normals: a normal has zero length");
    v = v / len;
  }
  std::vector<IrradianceEstimate> e(x.size());
  {
    py::gil_scoped_release release;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, x.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i)
                          e[i] = pm.map->irradiance(x[i], n[n.size() == 1 ? 0 : i], k, filter);
                      });
  }
  std::vector<Vec3> irradiance(e.size());
  py::array_t<double> radius(static_cast<py::ssize_t>(e.size()));
  py::array_t<int> count(static_cast<py::ssize_t>(e.size()));
  for (std::size_t i = 0; i < e.size(); ++i) {
    irradiance[i] = e[i].irradiance;
    radius.mutable_at(i) = e[i].radius;
    count.mutable_at(i) = e[i].photons;
  }
  py::dict d;
  d["irradiance"] = vec3Array(irradiance);
  d["radius"] = radius;
  d["photons"] = count;
  return d;
}

Array photonImagePy(const PyMesh& m, std::size_t photons, int k, const std::string& filter,
                    int gather, const std::string& view, int width, int height, std::uint64_t seed,
                    const std::optional<std::string>& camera) {
  checkImageSize(width, height);
  if (k < 2) throw py::value_error("photon_image: k must be >= 2");
  if (gather < 0) throw py::value_error("photon_image: gather must be >= 0 (0: the map itself)");
  PhotonView v = PhotonView::FinalGather;
  if (view == "map" || (view == "gather" && gather == 0))
    v = PhotonView::GlobalMap;
  else if (view == "caustic")
    v = PhotonView::CausticMap;
  else if (view != "gather")
    throw py::value_error("photon_image: view '" + view +
                          "' is not known. Fix: 'gather', 'map' or 'caustic'");
  PhotonSettings settings = photonSettings("photon_image", photons, seed);
  settings.neighbours = k;
  settings.filter = parseFilterPy(filter);
  settings.gatherRays = gather;
  const Camera cam = cameraFor(m, camera);
  const RayScene& rays = m.rayScene();
  RadianceImage img;
  {
    py::gil_scoped_release release;
    const EmitterSampler emitters = photonEmitters(*m.scene, *m.mesh);
    PhotonTrace trace = tracePhotons(*m.scene, *m.mesh, rays, emitters, settings);
    PhotonMaps maps = buildPhotonMaps(*m.mesh, std::move(trace.photons));
    if (v == PhotonView::FinalGather)
      maps.global->precomputeIrradiance(k, settings.filter, settings.precomputeStride);
    const PhotonScene in{*m.scene, *m.mesh, rays, emitters, *maps.global, *maps.caustic};
    img = renderPhotonImage(in, cam, width, height, v, settings);
  }
  return imageArray(img);
}

}  // namespace

/// Library messages name settings by key (util/setting_names.h); a Python user reads them as the
/// keyword arguments that set them, and the command line's flag for a setting only it has.
std::string pythonSpelling(const std::string& key) {
  static const std::map<std::string, std::string> renamed = {
      {"tol", "tolerance"}, {"hr_rays", "rays_per_link"}, {"hr_rounds", "rounds"}};
  static const char* const keywords[] = {
      "out",        "method",  "preset",    "patches",         "max_area",    "ff",
      "ff_samples", "solvers", "tolerance", "max_iterations",  "max_seconds", "memory_budget",
      "seed",       "epsilon", "min_area",  "rays_per_link",   "rounds",      "gather",
      "camera",     "smooth",  "units",     "repair",          "shading",     "photons",
      "width",      "height",  "coverage",  "camera_elevation"};
  const auto it = renamed.find(key);
  const std::string name = it == renamed.end() ? key : it->second;
  for (const char* k : keywords)
    if (name == k) return name + "=";
  return "the command line's " + flagSpelling(key);
}

PYBIND11_MODULE(radkit, mod) {
  setSettingSpeller(&pythonSpelling);
  mod.doc() =
      "radkit: radiosity and global illumination. Load a scene, mesh it into patches, compute "
      "the form-factor matrix, solve B = E + rho F B with a built-in or a Python solver, and "
      "render; every per-patch quantity is a numpy array (docs/python.md). Areas are m^2 "
      "(positions and lengths stay in the scene's units); array properties are read-only, "
      "arrays a function returns are yours to change.";
  mod.attr("__version__") = RADKIT_VERSION;

  py::register_exception<InputError>(mod, "InputError", PyExc_ValueError);
  py::register_exception<MemoryBudgetError>(mod, "MemoryBudgetError", PyExc_MemoryError);

  py::class_<PyScene>(mod, "Scene", "A loaded, validated scene (load_scene)")
      .def_property_readonly("name", [](const PyScene& s) { return s.scene->name; })
      .def_property_readonly("file", [](const PyScene& s) { return s.scene->file; })
      .def_property_readonly("units", [](const PyScene& s) { return s.scene->units; })
      .def_property_readonly("surface_names",
                             [](const PyScene& s) {
                               std::vector<std::string> names;
                               for (const Surface& f : s.scene->surfaces) names.push_back(f.name);
                               return names;
                             })
      .def("__repr__", [](const PyScene& s) {
        return "<radkit.Scene '" + s.scene->name + "', " +
               std::to_string(s.scene->surfaces.size()) + " surfaces>";
      });

  py::class_<PyMesh>(mod, "Mesh",
                     "The scene split into patches (mesh). Array properties are read-only copies; "
                     "positions in scene units, areas in m^2")
      .def("__len__", [](const PyMesh& m) { return m.mesh->size(); })
      .def_property_readonly("scene", [](const PyMesh& m) { return PyScene{m.scene}; })
      .def_property_readonly("warnings", [](const PyMesh& m) { return m.warnings; })
      .def_property_readonly(
          "area",
          [](const PyMesh& m) {
            const double m2 = squareMetres(*m.scene);
            Array a(m.mesh->size());
            for (int i = 0; i < m.mesh->size(); ++i) a.mutable_at(i) = m.mesh->patches[i].area * m2;
            return readOnly(a);
          },
          "(n,) patch areas in m^2 (as System.area), whatever the scene's units")
      .def_property_readonly(
          "centroid",
          [](const PyMesh& m) {
            std::vector<Vec3> v;
            for (const Patch& p : m.mesh->patches) v.push_back(p.centroid);
            return readOnly(vec3Array(v));
          },
          "(n, 3) patch centroids, scene units")
      .def_property_readonly(
          "normal",
          [](const PyMesh& m) {
            std::vector<Vec3> v;
            for (const Patch& p : m.mesh->patches) v.push_back(p.normal);
            return readOnly(vec3Array(v));
          },
          "(n, 3) unit normals of the patches' front sides")
      .def_property_readonly(
          "surface",
          [](const PyMesh& m) {
            py::array_t<int> a(m.mesh->size());
            for (int i = 0; i < m.mesh->size(); ++i) a.mutable_at(i) = m.mesh->patches[i].surface;
            return readOnly(a);
          },
          "index into scene.surface_names per patch")
      .def_property_readonly(
          "vertices", [](const PyMesh& m) { return readOnly(vec3Array(m.mesh->vertices)); },
          "(V, 3) vertex positions, scene units")
      .def_property_readonly(
          "patch_vertices",
          [](const PyMesh& m) {
            py::array_t<int> a({m.mesh->size(), 4});
            auto v = a.mutable_unchecked<2>();
            for (int i = 0; i < m.mesh->size(); ++i)
              for (int k = 0; k < 4; ++k) v(i, k) = m.mesh->patches[i].vertex[k];
            return readOnly(a);
          },
          "(n, 4) vertex indices, counter-clockwise from the front; -1 fourth for triangles")
      .def_property_readonly(
          "reflectance",
          [](const PyMesh& m) {
            const FormFactorMatrix none;
            return readOnly(
                channelsArray(makeRadiositySystem(*m.scene, *m.mesh, none).reflectance));
          },
          "(n, 3) diffuse reflectance")
      .def_property_readonly(
          "emission",
          [](const PyMesh& m) {
            const FormFactorMatrix none;
            return readOnly(channelsArray(makeRadiositySystem(*m.scene, *m.mesh, none).emission));
          },
          "(n, 3) emitted radiosity E, W/m^2")
      .def("__repr__", [](const PyMesh& m) {
        return "<radkit.Mesh " + std::to_string(m.mesh->size()) + " patches>";
      });

  py::class_<PyFormFactors>(mod, "FormFactors", "The form-factor matrix F of a mesh")
      .def_property_readonly("mesh", [](const PyFormFactors& f) { return f.mesh; })
      .def_property_readonly("storage",
                             [](const PyFormFactors& f) { return storageName(f.result->matrix); })
      .def(
          "dense", [](const PyFormFactors& f) { return denseArray(f.result->matrix); },
          "F as an (n, n) numpy array (a copy)")
      .def(
          "sparse", [](const PyFormFactors& f) { return sparseMatrix(f.result->matrix); },
          "F as scipy.sparse.csr_matrix (a copy, zeros left out)")
      .def_property_readonly(
          "diagnostics",
          [](const PyFormFactors& f) { return jsonToPython(toJson(f.result->diagnostics)); },
          "report.json's form_factors object: rays, seconds, row sums, reciprocity")
      .def("__repr__", [](const PyFormFactors& f) {
        return "<radkit.FormFactors " + std::to_string(matrixSize(f.result->matrix)) + "x" +
               std::to_string(matrixSize(f.result->matrix)) + " " + storageName(f.result->matrix) +
               ">";
      });

  py::class_<PySystem>(mod, "System", "The radiosity system B = E + rho F B, three channels")
      .def(py::init(&systemFromArrays), py::arg("F"), py::arg("area"), py::arg("reflectance"),
           py::arg("emission"),
           "A system from arrays: F (n, n) or scipy.sparse, area (n,) in m^2, reflectance and "
           "emission (n, 3) or (n,). Checked before use (ValueError naming the element): F's "
           "entries finite and >= 0, each row summing to at most 1.05, sparse indices in range; "
           "A > 0, rho in [0, 1), E >= 0, all finite; no masked entries. Sparse duplicates are "
           "summed")
      .def(py::init(&systemFromFormFactors), py::arg("form_factors"),
           "The system of a mesh: areas in m^2, reflectance and emission from its materials")
      .def("__len__", [](const PySystem& s) { return s.system.size(); })
      .def_property_readonly(
          "F", [](const PySystem& s) { return readOnly(denseArray(*s.matrix)); },
          "F as an (n, n) numpy array (a read-only copy)")
      // scipy's in-place methods (sort_indices, eliminate_zeros) fail on read-only arrays, so the
      // sparse copy stays writeable.
      .def_property_readonly(
          "F_sparse", [](const PySystem& s) { return sparseMatrix(*s.matrix); },
          "F as scipy.sparse.csr_matrix, a new copy on every access (changing it changes "
          "nothing in the system)")
      .def_property_readonly(
          "area",
          [](const PySystem& s) {
            return readOnly(
                Array(static_cast<py::ssize_t>(s.system.area.size()), s.system.area.data()));
          },
          "(n,) patch areas in m^2 (read-only)")
      .def_property_readonly(
          "reflectance",
          [](const PySystem& s) { return readOnly(channelsArray(s.system.reflectance)); },
          "(n, 3) diffuse reflectance (read-only)")
      .def_property_readonly(
          "emission", [](const PySystem& s) { return readOnly(channelsArray(s.system.emission)); },
          "(n, 3) emitted radiosity E, W/m^2 (read-only)")
      .def(
          "residual",
          [](const PySystem& s, const Array& b, const std::string& norm) {
            const Channels bc = toChannels(b, s.system.size(), "B");
            return residualMeasure(s.system, residualVector(s.system, bc), bc, parseNorm(norm));
          },
          py::arg("B"), py::arg("norm") = "relative",
          "The residual measure of B the solvers stop on: max|E + rho F B - B| / max|E|")
      .def(
          "multiply",
          [](const PySystem& s, const Array& b) {
            const Channels bc = toChannels(b, s.system.size(), "B");
            Channels out = makeChannels(s.system.size());
            multiply(*s.matrix, bc, out);
            return channelsArray(out);
          },
          py::arg("B"), "F B per channel, (n, 3), in the matrix's own parallel kernel");

  mod.def("load_scene", &loadScenePy, py::arg("path"), py::arg("units") = "",
          py::arg("repair") = false,
          "Loads and validates a scene (.json, or .obj with its MTL) from a path (str or "
          "os.PathLike); errors raise InputError naming the file, the element and the fix");
  mod.def("mesh", &meshPy, py::arg("scene"), py::arg("patches") = 0, py::arg("max_area") = 0.0,
          "Splits a scene into about `patches` patches (or patches of at most max_area m^2)");
  mod.def("form_factors", &formFactorsPy, py::arg("mesh"), py::arg("method") = "point-polygon",
          py::arg("samples") = 16, py::arg("seed") = 1, py::arg("precision") = "double",
          py::arg("pair_levels") = kMaxPairLevel,
          "Computes F (docs/formfactors.md): method point-polygon, monte-carlo or hemisphere; "
          "samples = rays per blockable pair");
  mod.def("solve", &solvePy, py::arg("system"), py::arg("solver") = "gauss-seidel",
          py::arg("params") = py::str(""), py::arg("tolerance") = 1e-6,
          py::arg("max_iterations") = 100000000L,
          py::arg("max_seconds") = std::numeric_limits<double>::infinity(),
          py::arg("norm") = "relative",
          "Solves from B = E with a built-in solver (solver_names()), a Python object with "
          "start(system), step() and radiosity(), or a function system -> B. params (built-in "
          "solvers): text \"omega=1.2,power_iterations=30\" or a dict {\"omega\": 1.2}. "
          "Returns a dict: "
          "radiosity (n, 3), converged, exit, iterations, residual, checked_residual, seconds, "
          "spectral_radius and history (numpy arrays per column)");
  mod.def("solver_names", &solverNames, "The built-in solvers' names");
  mod.def("render_scene", &renderScenePy, py::arg("scene"), py::arg("shading") = "path-trace",
          py::arg("width") = 256, py::arg("height") = 256, py::arg("spp") = 16, py::arg("seed") = 1,
          py::arg("patches") = 0, py::arg("max_area") = 0.0, py::arg("photons") = 200000,
          py::arg("sampler") = "sobol", py::arg("camera") = py::none(),
          "One image of a scene by a render mode (render_modes()), as radkit render --shading "
          "makes it: radiance (height, width, 3), W/m^2/sr");
  mod.def(
      "render_modes", [] { return integratorRegistry().names(); },
      "The image modes of render_scene and radkit render --shading");
  mod.def(
      "bsdf_names", [] { return bsdfRegistry().names(); },
      "The BSDFs a material may name (\"brdf\" in a scene file)");
  mod.def("form_factor_methods", &formFactorMethodNames, "The form-factor methods, default first");
  mod.def(
      "run",
      [](const py::object& scene, const std::optional<std::filesystem::path>& out,
         const std::string& kind, const std::optional<std::string>& method,
         const std::optional<std::string>& preset, const std::optional<int>& patches,
         const std::optional<double>& maxArea, const std::optional<std::string>& ff,
         const std::optional<int>& ffSamples, const py::object& solvers,
         const std::optional<double>& tolerance, const std::optional<long>& maxIterations,
         const std::optional<std::size_t>& memoryBudget, std::uint64_t seed,
         const std::optional<double>& epsilon, const std::optional<double>& minArea,
         const std::optional<int>& raysPerLink, const std::optional<int>& rounds,
         const std::optional<std::string>& gather, bool adaptive, int checkLinks,
         const std::optional<std::string>& camera, bool render, bool photometric, bool smooth,
         bool writeMatrix, int width, int height, const std::string& units, bool repair) {
        RunOptions o;
        o.out = out, o.kind = kind, o.method = method, o.preset = preset, o.patches = patches;
        o.maxArea = maxArea, o.ff = ff, o.ffSamples = ffSamples, o.solvers = solvers;
        o.tolerance = tolerance, o.maxIterations = maxIterations, o.memoryBudget = memoryBudget;
        o.seed = seed, o.epsilon = epsilon, o.minArea = minArea, o.raysPerLink = raysPerLink;
        o.rounds = rounds, o.gather = gather, o.adaptive = adaptive, o.checkLinks = checkLinks;
        o.camera = camera, o.render = render, o.photometric = photometric, o.smooth = smooth;
        o.writeMatrix = writeMatrix, o.width = width, o.height = height, o.units = units;
        o.repair = repair;
        return runPy(scene, o);
      },
      py::arg("scene"), py::kw_only(), py::arg("out") = py::none(), py::arg("kind") = "run",
      py::arg("method") = py::none(), py::arg("preset") = py::none(),
      py::arg("patches") = py::none(), py::arg("max_area") = py::none(), py::arg("ff") = py::none(),
      py::arg("ff_samples") = py::none(), py::arg("solvers") = py::none(),
      py::arg("tolerance") = py::none(), py::arg("max_iterations") = py::none(),
      py::arg("memory_budget") = py::none(), py::arg("seed") = 1, py::arg("epsilon") = py::none(),
      py::arg("min_area") = py::none(), py::arg("rays_per_link") = py::none(),
      py::arg("rounds") = py::none(), py::arg("gather") = py::none(), py::arg("adaptive") = false,
      py::arg("check_links") = 0, py::arg("camera") = py::none(), py::arg("render") = true,
      py::arg("photometric") = false, py::arg("smooth") = false, py::arg("write_matrix") = false,
      py::arg("width") = 512, py::arg("height") = 512, py::arg("units") = "",
      py::arg("repair") = false,
      "radkit's main job, as radkit run (kind \"solvers\", \"formfactors\": those commands) "
      "makes it with the options of the same names: writes the run folder `out` (default "
      "out/<scene name>, run only) and returns a dict: out, report (report.json), log (the "
      "lines the command line prints; warnings are also raised as Python warnings), mesh (the "
      "patches, or the hierarchy's leaves) and radiosity (n, 3). scene: a path or a Scene; "
      "areas in m^2; None leaves a setting to the preset or the method");
  py::class_<PyBsdf>(mod, "Bsdf",
                     "A BSDF of the registry (bsdf_names()) on local directions: +z is the "
                     "surface's front normal, wo toward the viewer, wi toward the light")
      .def(py::init(&makeBsdfPy), py::arg("name"), py::arg("params") = py::none())
      .def("eval", &bsdfEvalPy, py::arg("wo"), py::arg("wi"),
           "f(wo, wi) per channel, (n, 3), 1/sr; wo, wi (n, 3) or (3,)")
      .def("pdf", &bsdfPdfPy, py::arg("wo"), py::arg("wi"),
           "The density sample() draws wi with, per steradian, (n,)")
      .def("sample", &bsdfSamplePy, py::arg("wo"), py::arg("u"),
           "wi drawn from (n, 3) uniform numbers (the lobe, then the direction): dict wi, weight "
           "(f cos / pdf, (n, 3)), pdf, "
           "delta")
      .def_property_readonly("name", [](const PyBsdf& b) { return b.name; })
      .def_property_readonly(
          "diffuse_albedo",
          [](const PyBsdf& b) { return vec3Array({b.bsdf->diffuseAlbedo()}).attr("reshape")(3); },
          "The reflectance radiosity sees, (3,)")
      .def("__repr__", [](const PyBsdf& b) { return "<radkit.Bsdf " + b.bsdf->describe() + ">"; });
  py::class_<PyPhase>(mod, "PhaseFunction",
                      "A phase function of the registry (phase_function_names()) on cos theta "
                      "between the directions of travel before and after scattering")
      .def(py::init(&makePhasePy), py::arg("name"), py::arg("params") = py::none())
      .def("eval", &phaseEvalPy, py::arg("mu"), "The density over the sphere, 1/sr, per cosine")
      .def("sample", &phaseSamplePy, py::arg("u"),
           "(mu, pdf): cosines drawn from uniform numbers u and their density, 1/sr")
      .def_property_readonly("mean_cosine", [](const PyPhase& p) { return p.phase->meanCosine(); })
      .def_property_readonly("name", [](const PyPhase& p) { return p.phase->name(); })
      .def("__repr__",
           [](const PyPhase& p) { return "<radkit.PhaseFunction " + p.phase->name() + ">"; });
  mod.def("phase_function_names", &phaseFunctionNames, "The phase functions' names");
  py::class_<PyMedium>(mod, "Medium",
                       "A participating medium as a volume scene's \"medium\" describes it (a dict "
                       "or JSON text; docs/formats.md): a cloud layer or a homogeneous box")
      .def(py::init(&makeMediumPy), py::arg("description"))
      .def("extinction", &mediumExtinctionPy, py::arg("points"),
           "sigma_t (1/m) at (n, 3) points, zero outside the medium's bounds")
      .def("transmittance", &mediumTransmittancePy, py::arg("origins"), py::arg("directions"),
           py::arg("distances"), py::kw_only(), py::arg("samples") = 64, py::arg("seed") = 1,
           "(mean, standard error) of the transmittance over [0, distance) along each ray, by "
           "ratio tracking (unbiased); one origin, direction or distance serves every ray")
      .def_property_readonly("majorant", [](const PyMedium& m) { return m.medium->majorant(); })
      .def_property_readonly("albedo", [](const PyMedium& m) { return m.medium->albedo(); })
      .def_property_readonly("bounds",
                             [](const PyMedium& m) {
                               const Bounds3 b = m.medium->bounds();
                               return vec3Array({b.lo, b.hi});
                             })
      .def_property_readonly("kind", [](const PyMedium& m) { return m.kind; })
      .def_property_readonly(
          "phase",
          [](const PyMedium& m) {
            return PyPhase{std::shared_ptr<const PhaseFunction>(
                makePhaseFunction(m.phaseName, m.phaseParams))};
          },
          "its phase function, a PhaseFunction")
      .def("__repr__", [](const PyMedium& m) { return "<radkit.Medium " + m.kind + ">"; });
  py::class_<PySky>(mod, "SkyModel",
                    "A sky model of the registry (sky_models()), as a scene's \"sky\" names it, "
                    "with its sun placed (degrees, azimuth clockwise from north)")
      .def(py::init(&makeSkyPy), py::arg("name"), py::arg("params") = py::none(), py::kw_only(),
           py::arg("sun_elevation") = 45.0, py::arg("sun_azimuth") = 180.0)
      .def("radiance", &skyModelRadiancePy, py::arg("directions"),
           "(n, 3) W/m^2/sr toward (n, 3) directions in the local frame (x east, y north, z up); "
           "0 at and below the horizon")
      .def_property_readonly(
          "horizontal_irradiance",
          [](const PySky& s) { return vec3Array({s.sky->horizontalIrradiance()}); },
          "(1, 3) W/m^2 on an open horizontal plane from the sky (not the sun)")
      .def_property_readonly(
          "sun_irradiance", [](const PySky& s) { return vec3Array({s.sky->sunIrradiance()}); },
          "(1, 3) W/m^2 normal to the sun, for a model that makes its sun (else zero)")
      .def_property_readonly("name", [](const PySky& s) { return s.name; })
      .def("__repr__", [](const PySky& s) { return "<radkit.SkyModel " + s.name + ">"; });
  mod.def(
      "sky_models", [] { return skyRegistry().names(); },
      "The sky models a scene's \"sky\" may name (its \"type\") and SkyModel builds");
  mod.def("preset_names", &presetNames, "The presets run(preset=...) and radkit run --preset take");
  mod.def("sky_radiance", &skyRadiancePy, py::arg("directions"), py::arg("sun_elevation") = 30.0,
          py::arg("sun_azimuth") = 180.0, py::arg("altitude") = 1.0, py::arg("density") = 1.0,
          py::arg("view_samples") = 32, py::arg("light_samples") = 8,
          py::arg("multiple_scattering") = true, py::arg("rayleigh") = "bruneton",
          "The physical sky's radiance, (n, 3) W/m^2/sr, toward (n, 3) directions in the "
          "observer's frame (x east, y north, z up); degrees, azimuth clockwise from north; "
          "rayleigh names the air's Rayleigh model (rayleigh_optical_depth())");
  mod.def(
      "rayleigh_optical_depth",
      [](const std::string& rayleigh) {
        const atmosphere::RayleighAir air = atmosphere::rayleighAir(rayleigh);
        const atmosphere::AtmosphereParameters p;
        return vec3Array({atmosphere::rayleighOpticalDepth(air.scattering, air.scaleHeight,
                                                           p.topRadius - p.groundRadius)});
      },
      py::arg("rayleigh") = "bruneton",
      "(1, 3) vertical Rayleigh optical depth of the atmosphere at the channels' wavelengths "
      "(680, 550, 440 nm) for a Rayleigh model: bruneton (the default) or bodhaine[:co2=ppm]");
  mod.def(
      "sky",
      [](const std::filesystem::path& out, double elevation, double azimuth, int size,
         const std::string& projection, double density, double altitude, int viewSamples,
         int lightSamples, bool multiple, long long compare, std::uint64_t seed,
         const std::string& rayleigh) {
        SkyJobSettings s;
        s.out = out.string(), s.sunElevationDeg = elevation, s.sunAzimuthDeg = azimuth;
        s.size = size, s.projection = projection, s.relativeDensity = density;
        s.rayleigh = rayleigh;
        s.altitude = altitude, s.sky.viewSamples = viewSamples, s.sky.lightSamples = lightSamples;
        s.sky.multipleScattering = multiple, s.comparePaths = compare, s.seed = seed;
        SkyJobResult r;
        {
          py::gil_scoped_release release;
          r = runSkyJob(s);
        }
        return reportDict(r.out, r.report);
      },
      py::arg("out"), py::kw_only(), py::arg("sun_elevation") = 30.0,
      py::arg("sun_azimuth") = 180.0, py::arg("size") = 512, py::arg("projection") = "all",
      py::arg("density") = 1.0, py::arg("altitude") = 1.0, py::arg("view_samples") = 32,
      py::arg("light_samples") = 8, py::arg("multiple_scattering") = true, py::arg("compare") = 0,
      py::arg("seed") = 1, py::arg("rayleigh") = "bruneton",
      "radkit sky's job: the sky's images and report.json in `out`; returns dict out, report");
  mod.def(
      "clouds",
      [](const std::filesystem::path& out, const std::optional<std::filesystem::path>& scene,
         int width, int height, int samples, std::optional<double> sunElevation,
         std::optional<double> sunAzimuth, std::optional<double> cameraElevation,
         std::optional<double> fov, double coverage, std::uint64_t seed) {
        CloudsJobSettings s;
        s.out = out.string();
        if (scene) s.scene = scene->string();
        s.width = width, s.height = height, s.samples = samples;
        s.sunElevationDeg = sunElevation, s.sunAzimuthDeg = sunAzimuth;
        s.cameraElevationDeg = cameraElevation, s.fovDeg = fov;
        s.layer.coverage = coverage, s.seed = seed;
        CloudsJobResult r;
        {
          py::gil_scoped_release release;
          r = runCloudsJob(s);
        }
        return reportDict(r.out, r.report);
      },
      py::arg("out"), py::kw_only(), py::arg("scene") = py::none(), py::arg("width") = 128,
      py::arg("height") = 72, py::arg("samples") = 32, py::arg("sun_elevation") = py::none(),
      py::arg("sun_azimuth") = py::none(), py::arg("camera_elevation") = py::none(),
      py::arg("fov") = py::none(), py::arg("coverage") = media::CloudLayerSettings{}.coverage,
      py::arg("seed") = 1,
      "radkit clouds' job: the reference and real-time images and report.json in `out`; a "
      "volume scene file or the default layer; None takes the file's value, else the default");
  mod.def(
      "terrain",
      [](const std::filesystem::path& out, const std::string& type, int resolution, double size,
         double height, std::uint32_t seed, const std::string& format, const std::string& sky) {
        TerrainJobSettings s;
        s.out = out.string(), s.type = type, s.settings.resolution = resolution;
        s.settings.size = size, s.settings.height = height, s.settings.fractal.seed = seed;
        s.format = format, s.sky = sky;
        TerrainJobResult r;
        {
          py::gil_scoped_release release;
          r = runTerrainJob(s);
        }
        return reportDict(r.out, r.report);
      },
      py::arg("out"), py::kw_only(), py::arg("type") = "ridged",
      py::arg("resolution") = terrain::TerrainSettings{}.resolution,
      py::arg("size") = terrain::TerrainSettings{}.size,
      py::arg("height") = terrain::TerrainSettings{}.height, py::arg("seed") = 1,
      py::arg("format") = "obj", py::arg("sky") = "physical",
      "radkit terrain's job: meshes, terrain.json (a scene for run()) and report.json in `out`");
  mod.def("hierarchical", &hierarchicalPy, py::arg("scene"), py::arg("epsilon") = 1e-4,
          py::arg("rays_per_link") = 16, py::arg("rounds") = 3, py::arg("order") = "jacobi",
          py::arg("seed") = 1, py::arg("min_area") = 0.0, py::arg("tolerance") = 1e-6,
          py::arg("max_iterations") = long(kDefaultHierarchicalSweeps),
          "Hierarchical radiosity with clustering (docs/hierarchical.md), as radkit run "
          "--method hierarchical: a dict with the leaves as a Mesh, their radiosity and "
          "irradiance (n, 3), converged, reason, iterations, links, rays, min_area (m^2), "
          "rounds, relative_imbalance");
  mod.def("render", &renderRadiosityPy, py::arg("mesh"), py::arg("radiosity"),
          py::arg("width") = 256, py::arg("height") = 256, py::arg("samples_per_axis") = 2,
          py::arg("smooth") = false, py::arg("camera") = py::none(),
          "Radiance B/pi seen by the camera, (height, width, 3), linear W/m^2/sr; camera "
          "'px,py,pz,lx,ly,lz[,ux,uy,uz[,fov]]' or the scene's");
  mod.def("path_trace", &pathTracePy, py::arg("mesh"), py::arg("spp") = 16, py::arg("width") = 256,
          py::arg("height") = 256, py::arg("seed") = 1, py::arg("sampler") = "sobol",
          py::arg("camera") = py::none(),
          "Path-traced reference image and the variance of each pixel's mean, both "
          "(height, width, 3)");
  mod.def("photons", &photonsPy, py::arg("mesh"), py::arg("photons") = 200000, py::arg("seed") = 1,
          "Photon tracing tallied per patch: radiosity, radiosity_error (standard errors), "
          "irradiance as (n, 3) and per-surface estimates (area in m^2)");
  py::class_<PyPhotonMap>(mod, "PhotonMap",
                          "Traced photons (photon_map) and their k-nearest irradiance estimate")
      .def("__len__", [](const PyPhotonMap& p) { return p.map->size(); })
      .def_property_readonly(
          "positions",
          [](const PyPhotonMap& p) { return readOnly(photonVectors(p, &Photon::point, 1.0)); },
          "(m, 3) where each stored photon landed, scene units (stored as float: 7 digits)")
      .def_property_readonly(
          "power",
          [](const PyPhotonMap& p) {
            return readOnly(photonVectors(p, &Photon::flux, squareMetres(*p.mesh.scene)));
          },
          "(m, 3) incident power per channel, W (stored as float: 7 digits)")
      .def_property_readonly(
          "patch",
          [](const PyPhotonMap& p) {
            return readOnly(
                photonIndices(p, [](const Photon& ph) { return std::int64_t(ph.patch); }));
          },
          "(m,) the patch each photon landed on")
      .def_property_readonly(
          "path",
          [](const PyPhotonMap& p) {
            return readOnly(
                photonIndices(p, [](const Photon& ph) { return std::int64_t(ph.path); }));
          },
          "(m,) the emitted photon (path) that left each stored photon")
      .def_property_readonly("emitted", [](const PyPhotonMap& p) { return p.stats.emitted; })
      .def_property_readonly(
          "emitted_power",
          [](const PyPhotonMap& p) {
            const Vec3 watts = p.emittedPower * squareMetres(*p.mesh.scene);
            return readOnly(vec3Array({watts}).attr("reshape")(3));
          },
          "(3,) the emitted photons' total power per channel, W")
      .def("irradiance", &photonIrradiancePy, py::arg("points"), py::arg("normals"),
           py::arg("k") = 100, py::arg("filter") = "epanechnikov",
           "k-nearest-photon irradiance at points with the given normals (photons on surfaces "
           "within 25 degrees of the normal count): a dict of irradiance (q, 3), radius (q,), "
           "the distance to the k-th photon, and photons (q,), how many were found")
      .def("__repr__", [](const PyPhotonMap& p) {
        return "<radkit.PhotonMap " + std::to_string(p.map->size()) + " photons stored from " +
               std::to_string(p.stats.emitted) + " emitted>";
      });

  mod.def("photon_map", &photonMapPy, py::arg("mesh"), py::arg("photons") = 200000,
          py::arg("seed") = 1,
          "Traces `photons` photons (the same ones photons() tallies for the same seed) and "
          "builds their kd-tree: a PhotonMap");
  mod.def("photon_image", &photonImagePy, py::arg("mesh"), py::arg("photons") = 200000,
          py::arg("k") = 100, py::arg("filter") = "epanechnikov", py::arg("gather") = 64,
          py::arg("view") = "gather", py::arg("width") = 256, py::arg("height") = 256,
          py::arg("seed") = 1, py::arg("camera") = py::none(),
          "Photon-mapped radiance (height, width, 3), W/m^2/sr, as `radkit photons` renders "
          "photonmap.png: view 'gather' (final gathering with `gather` rays per pixel), 'map' "
          "(the global map's estimate) or 'caustic' (the caustic map alone)");
  mod.def("set_threads", &limitThreads, py::arg("n"),
          "Caps every parallel loop at n threads; 0 lifts the cap");
}
