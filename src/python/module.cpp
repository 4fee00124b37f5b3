// The `caustica` Python module (docs/python.md): scenes, renders, photon maps, error metrics and
// images as numpy arrays, over the libraries the command line is made of. Nothing here renders
// or measures on its own: it converts, and runs what `caustica render`, `photons`, `compare` and
// `converge` run.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <tbb/global_control.h>
#include "app/compare_command.h"
#include "app/converge_command.h"
#include "app/scene_setup.h"
#include "core/error.h"
#include "core/metrics.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "photon/photon_map.h"
#include "trace/render.h"

namespace py = pybind11;
using namespace caustica;

namespace {

static_assert(sizeof(Color) == 3 * sizeof(float), "an Image's pixels are packed RGB floats");

// An image as a float32 array of shape (H, W, 3), rows from the top.
py::array_t<float> to_array(const Image& image) {
  py::array_t<float> a({size_t(image.height), size_t(image.width), size_t(3)});
  if (!image.pixels.empty()) std::memcpy(a.mutable_data(), image.pixels.data(), image.pixels.size() * sizeof(Color));
  return a;
}

// An array of shape (H, W, 3) (or (H, W): grey) of any real type as an Image.
Image from_array(const py::handle& object, const char* what) {
  auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(object);
  if (!a) throw py::type_error(std::string(what) + ": expected a numpy array of shape (H, W, 3)");
  const bool grey = a.ndim() == 2;
  if (!(grey || (a.ndim() == 3 && a.shape(2) == 3)) || a.shape(0) < 1 || a.shape(1) < 1) {
    std::string shape;
    for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
    throw py::value_error(std::string(what) + ": expected shape (H, W, 3) or (H, W), not (" + shape + ")");
  }
  Image image(int(a.shape(1)), int(a.shape(0)));
  const float* p = a.data();
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = grey ? Color(p[i]) : Color(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  return image;
}

// A Python value (dict, number, string, list) as JSON, through Python's own json module.
nlohmann::json to_json(const py::handle& value) {
  const std::string text = py::module_::import("json").attr("dumps")(value).cast<std::string>();
  return nlohmann::json::parse(text);
}

// A value of **defines as Mitsuba's -D text: Python's str(), with True/False as true/false.
std::string define_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  return py::str(value).cast<std::string>();
}

struct PyScene {
  LoadedScene loaded;
  std::string name;        // the file, or "<dict>"
  SceneOptions options;    // what integrator_for reads (the scene's name for messages)
  std::atomic<bool> cancel{false};
  std::atomic<bool> busy{false};
};

// Runs `work` on a thread of its own while the calling thread, without the GIL, waits for it and
// every 50 ms takes the GIL to let Python handle signals (Ctrl-C; _thread.interrupt_main()). A
// signal's exception (KeyboardInterrupt) sets `cancel`, and is returned once the work has stopped.
std::optional<py::error_already_set> run_interruptible(std::atomic<bool>& cancel, const std::function<void()>& work) {
  std::exception_ptr failure;
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  std::optional<py::error_already_set> signal;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        work();
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(m);
      done = true;
      cv.notify_one();
    });
    std::unique_lock<std::mutex> lock(m);
    while (!cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
      if (signal) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) {
          signal.emplace();  // takes the pending exception
          cancel = true;
        }
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (failure) std::rethrow_exception(failure);
  return signal;
}

// Raises caustica.RenderInterrupted (a KeyboardInterrupt) carrying what was done.
[[noreturn]] void raise_interrupted(const std::string& message, py::object image, int passes) {
  py::object type = py::module_::import("caustica").attr("RenderInterrupted");
  py::object e = type(message);
  e.attr("image") = image;
  e.attr("passes") = passes;
  PyErr_SetObject(type.ptr(), e.ptr());
  throw py::error_already_set();
}

std::unique_ptr<PyScene> load(const py::object& source, const py::object& defines, std::optional<int> width,
                              std::optional<int> height, std::optional<int> max_depth, const py::kwargs& more) {
  auto s = std::make_unique<PyScene>();
  MitsubaOptions mitsuba;
  auto add_defines = [&](const py::handle& dict) {
    for (const auto& [k, v] : dict.cast<py::dict>()) mitsuba.xml.defines.emplace_back(py::str(k).cast<std::string>(), define_text(v));
  };
  if (!defines.is_none()) add_defines(defines);
  add_defines(more);
  RenderOverrides overrides;
  overrides.width = width;
  overrides.height = height;
  overrides.max_depth = max_depth;
  if (py::isinstance<py::dict>(source)) {
    // A scene in our JSON format as a dict: its relative paths are the working folder's.
    s->name = "<dict>";
    const std::string text = to_json(source).dump();
    s->loaded = parse_scene(text, s->name, std::filesystem::current_path().string(), mitsuba, overrides);
  } else {
    s->name = py::str(py::module_::import("os").attr("fspath")(source)).cast<std::string>();
    s->loaded = load_scene(s->name, mitsuba, overrides);
  }
  s->options.scene = s->name;
  s->options.quiet = true;
  if (!s->loaded.warnings.empty()) {
    py::object warn = py::module_::import("warnings").attr("warn");
    for (const std::string& w : s->loaded.warnings) warn(w, py::module_::import("caustica").attr("SceneWarning"), 2);
  }
  return s;
}

// "photon" with {"photons": 1000} as "photon:photons=1000": settings are read as the command
// line's integrator variants are, and refused with the same messages.
std::string integrator_spec(const PyScene& s, const std::string& integrator, const py::kwargs& settings) {
  std::string spec = integrator.empty() ? s.loaded.integrator_type : integrator;
  for (const auto& [k, v] : settings) spec += ":" + py::str(k).cast<std::string>() + "=" + to_json(v).dump();
  return spec;
}

// Guards a scene against two renders at once (its film and seed are set per call).
struct BusyGuard {
  std::atomic<bool>& busy;
  explicit BusyGuard(std::atomic<bool>& b) : busy(b) {
    if (busy.exchange(true)) throw py::value_error("this scene is already rendering (load it again for a second render)");
  }
  ~BusyGuard() { busy = false; }
};

int threads_or_default(std::optional<int> threads) {
  if (threads && *threads < 1) throw py::value_error("threads: expected 1 or more, not " + std::to_string(*threads));
  SceneOptions o;
  o.threads = threads;
  return thread_count(o);
}

py::object render(PyScene& s, const std::string& integrator_name, std::optional<int> spp, std::optional<double> time,
                  std::optional<uint64_t> seed, std::optional<int> threads, bool aovs, bool progress,
                  const py::kwargs& settings) {
  BusyGuard guard(s.busy);
  Scene& scene = *s.loaded.scene;
  if (spp && *spp < 1) throw py::value_error("spp: expected 1 or more, not " + std::to_string(*spp));
  if (time && !(*time > 0)) throw py::value_error("time: expected seconds > 0");
  const RenderSettings saved = scene.render;
  if (spp) scene.render.spp = *spp;
  if (seed) scene.render.seed = *seed;
  struct Restore {
    Scene& scene;
    RenderSettings saved;
    ~Restore() { scene.render.seed = saved.seed, scene.render.spp = saved.spp; }
  } restore{scene, saved};
  std::unique_ptr<Integrator> integrator = integrator_for(s.loaded, integrator_spec(s, integrator_name, settings), s.options);
  if (aovs && !integrator->supports_aov()) {
    throw InputError("aovs=True needs a photon integrator (photon or photon-direct), not \"" + integrator->name() + "\"");
  }
  const RenderSettings& rs = scene.render;
  check_film_memory(rs.width, rs.height, aovs);
  const int n_threads = threads_or_default(threads);
  s.cancel = false;
  const RenderJob job = render_job(rs, time ? *time : 0.0);
  RenderStats stats;
  std::vector<Image> aov_images;
  Image image;
  const auto signal = run_interruptible(s.cancel, [&] {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(n_threads));
    PreprocessContext pre{job.seed, !progress, &s.cancel, 0, job.passes, job.time_budget, 1};
    integrator->preprocess(scene, pre);
    RenderOptions options;
    options.job = job;
    options.quiet = !progress;
    options.cancel = &s.cancel;
    options.aov = aovs;
    image = s.cancel ? Image(rs.width, rs.height) : render_image(scene, *integrator, options, stats, &aov_images);
    if (s.cancel) stats.interrupted = true;
  });
  if (signal && !signal->matches(PyExc_KeyboardInterrupt)) throw *signal;  // another handler's exception
  if (stats.interrupted) {
    raise_interrupted("render interrupted after " + std::to_string(stats.passes) + " passes",
                      stats.passes > 0 ? py::object(to_array(image)) : py::none(), stats.passes);
  }
  py::array_t<float> result = to_array(image);
  if (!aovs) return std::move(result);
  py::dict maps;
  if (aov_images.size() == 2) {
    maps["photons"] = to_array(aov_images[0]);  // red: global photons in the estimate, green: caustic
    maps["radius"] = to_array(aov_images[1]);   // red: global estimate's radius, green: caustic's
  }
  return py::make_tuple(result, maps);
}

py::array photons(PyScene& s, const std::string& map, std::optional<uint64_t> seed, std::optional<int> threads,
                  const py::kwargs& settings) {
  BusyGuard guard(s.busy);
  if (map != "global" && map != "caustic" && map != "volume") {
    throw py::value_error("map: expected \"global\", \"caustic\" or \"volume\", not \"" + map + "\"");
  }
  Scene& scene = *s.loaded.scene;
  const uint64_t used_seed = seed ? *seed : scene.render.seed;
  std::unique_ptr<Integrator> integrator = integrator_for(s.loaded, integrator_spec(s, "photon", settings), s.options);
  const int n_threads = threads_or_default(threads);
  s.cancel = false;
  const auto signal = run_interruptible(s.cancel, [&] {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(n_threads));
    integrator->preprocess(scene, {used_seed, true, &s.cancel});
  });
  if (signal && !signal->matches(PyExc_KeyboardInterrupt)) throw *signal;
  if (s.cancel) raise_interrupted("photon pass interrupted", py::none(), 0);
  std::vector<const PhotonMap*> maps;
  if (map == "global") maps.push_back(integrator->global_map());
  if (map == "caustic") maps.push_back(integrator->caustic_map());
  if (map == "volume") maps = integrator->volume_maps();
  size_t n = 0;
  for (const PhotonMap* m : maps) n += m ? m->size() : 0;
  // position, normal (the surface's, on the side the photon came from; 0 in media), incoming
  // direction (towards where it came from), flux (RGB watts), bounces before this hit.
  py::list fields;
  for (const char* name : {"position", "normal", "direction", "flux"}) fields.append(py::make_tuple(name, "<f4", py::make_tuple(3)));
  fields.append(py::make_tuple("bounces", "<u2"));
  py::dtype dtype = py::dtype::from_args(fields);
  py::array out(dtype, std::vector<py::ssize_t>{py::ssize_t(n)});
  if (size_t(dtype.itemsize()) != 12 * sizeof(float) + sizeof(uint16_t)) throw std::logic_error("photon record size");
  char* bytes = static_cast<char*>(out.mutable_data());
  size_t at = 0;
  const bool volume = map == "volume";
  for (const PhotonMap* m : maps) {
    if (!m) continue;
    for (uint32_t i = 0; i < m->size(); ++i, ++at) {
      const Photon& ph = (*m)[i];
      const Vec3 nrm = volume ? Vec3(0.0f) : ph.surface_normal();
      const Vec3 dir = ph.incoming_dir();
      const Color flux = m->power(i);
      float values[12] = {ph.position.x, ph.position.y, ph.position.z, nrm.x, nrm.y, nrm.z,
                          dir.x, dir.y, dir.z, flux.x, flux.y, flux.z};
      std::memcpy(bytes + at * size_t(dtype.itemsize()), values, sizeof(values));
      std::memcpy(bytes + at * size_t(dtype.itemsize()) + sizeof(values), &ph.bounces, sizeof(uint16_t));
    }
  }
  return out;
}

// A reference given as one array or as a list of independent renders.
Reference reference_from(const py::object& references) {
  std::vector<Image> renders;
  std::vector<std::string> names;
  if (py::isinstance<py::list>(references) || py::isinstance<py::tuple>(references)) {
    for (const auto& r : references) {
      renders.push_back(py::isinstance<py::str>(r) ? read_image(r.cast<std::string>()) : from_array(r, "reference"));
      names.push_back(py::isinstance<py::str>(r) ? r.cast<std::string>() : "reference " + std::to_string(names.size()));
    }
  } else {
    renders.push_back(py::isinstance<py::str>(references) ? read_image(references.cast<std::string>()) : from_array(references, "reference"));
    names.push_back("reference");
  }
  return combine_references(renders, names);
}

// What `caustica compare --json` prints, as a dict (an infinite PSNR, JSON's null, as inf).
py::dict metrics_dict(const ErrorMetrics& m, const Reference& ref) {
  py::dict d = py::module_::import("json").attr("loads")(format_metrics(m, true, &ref));
  if (d["psnr"].is_none()) d["psnr"] = m.psnr;
  return d;
}

py::dict compare(const py::object& image, const py::object& references) {
  const Reference ref = reference_from(references);
  return metrics_dict(compare_images(from_array(image, "image"), ref.mean, "image", "reference"), ref);
}

py::list converge(PyScene& s, const std::vector<std::string>& integrators, double time,
                  std::optional<std::vector<double>> checkpoints, const py::object& references,
                  std::optional<uint64_t> seed, std::optional<int> threads) {
  BusyGuard guard(s.busy);
  if (!(time > 0)) throw py::value_error("time: expected seconds > 0");
  const Reference ref = reference_from(references);
  Scene& scene = *s.loaded.scene;
  if (ref.mean.width != scene.render.width || ref.mean.height != scene.render.height) {
    throw InputError("reference is " + std::to_string(ref.mean.width) + "x" + std::to_string(ref.mean.height) +
                     ", the render " + std::to_string(scene.render.width) + "x" + std::to_string(scene.render.height));
  }
  std::vector<double> marks = checkpoints ? *checkpoints : default_checkpoints(time);
  std::sort(marks.begin(), marks.end());
  std::vector<std::unique_ptr<Integrator>> made;
  for (const std::string& name : integrators) made.push_back(integrator_for(s.loaded, name, s.options, true));
  const int n_threads = threads_or_default(threads);
  const uint64_t saved_seed = scene.render.seed;
  if (seed) scene.render.seed = *seed;
  s.cancel = false;
  std::vector<ConvergeRow> rows;
  const auto signal = run_interruptible(s.cancel, [&] {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(n_threads));
    for (size_t i = 0; i < made.size() && !s.cancel; ++i) {
      ConvergeRunOptions o;
      o.cancel = &s.cancel;
      o.quiet = true;
      converge_integrator(scene, *made[i], integrators[i], time, marks, ref.mean, o, rows);
    }
  });
  scene.render.seed = saved_seed;
  if (signal && !signal->matches(PyExc_KeyboardInterrupt)) throw *signal;
  py::list out;
  for (const ConvergeRow& r : rows) {
    py::dict d;
    d["integrator"] = r.integrator;
    d["seconds"] = r.seconds;
    d["passes"] = r.passes;
    d["rmse"] = r.rmse;
    d["relmse"] = r.relmse;
    if (ref.has_floor()) d["relmse_floor_free"] = r.relmse - ref.floor;
    out.append(d);
  }
  if (s.cancel) raise_interrupted("converge interrupted", py::none(), 0);
  return out;
}

}  // namespace

PYBIND11_MODULE(caustica, m) {
  m.doc() = "Caustica: photon mapping and path tracing from Python (docs/python.md)";
  m.attr("__version__") = CAUSTICA_VERSION;
  // Bad input (scene files, settings, images): the command line's message, file and place.
  static py::exception<InputError> scene_error(m, "SceneError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(scene_error.ptr(), e.what());
    }
  });
  m.attr("SceneWarning") = py::module_::import("builtins").attr("type")(
      "SceneWarning", py::make_tuple(py::module_::import("builtins").attr("UserWarning")), py::dict());
  m.attr("SceneWarning").attr("__module__") = "caustica";
  // Ctrl-C during a render: a KeyboardInterrupt carrying the passes done (.image, .passes).
  py::dict ns;
  ns["__module__"] = "caustica";
  ns["__doc__"] = "A render stopped by Ctrl-C or Scene.cancel(); .image holds the mean of the .passes completed (None without any).";
  m.attr("RenderInterrupted") = py::module_::import("builtins").attr("type")(
      "RenderInterrupted", py::make_tuple(py::handle(PyExc_KeyboardInterrupt)), ns);

  py::class_<PyScene>(m, "Scene", "A loaded scene (caustica.load)")
      .def_property_readonly("width", [](const PyScene& s) { return s.loaded.scene->render.width; })
      .def_property_readonly("height", [](const PyScene& s) { return s.loaded.scene->render.height; })
      .def_property_readonly("spp", [](const PyScene& s) { return s.loaded.scene->render.spp; })
      .def_property_readonly("seed", [](const PyScene& s) { return s.loaded.scene->render.seed; })
      .def_property_readonly("integrator", [](const PyScene& s) { return s.loaded.integrator_type; })
      .def_property_readonly("warnings", [](const PyScene& s) { return s.loaded.warnings; })
      .def_property_readonly("name", [](const PyScene& s) { return s.name; })
      .def("render", &render, py::arg("integrator") = "", py::kw_only(), py::arg("spp") = py::none(),
           py::arg("time") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = py::none(),
           py::arg("aovs") = false, py::arg("progress") = false,
           "Renders the scene; returns a float32 array (H, W, 3) of linear RGB, or (image, {name: array}) with aovs=True.\n"
           "integrator: path, photon, ... (the scene's when empty); further keywords are its settings (photons=100000).")
      .def("photons", &photons, py::arg("map") = "global", py::kw_only(), py::arg("seed") = py::none(),
           py::arg("threads") = py::none(),
           "The photon map the photon integrator builds for this seed, as a structured array "
           "(position, normal, direction, flux, bounces); keywords are photon settings.")
      .def("cancel", [](PyScene& s) { s.cancel = true; },
           "Stops this scene's render, photon pass or converge run (from another thread); it raises RenderInterrupted.")
      .def("__repr__", [](const PyScene& s) {
        return "<caustica.Scene " + s.name + " " + std::to_string(s.loaded.scene->render.width) + "x" +
               std::to_string(s.loaded.scene->render.height) + ", " + s.loaded.integrator_type + ">";
      });

  m.def("load", &load, py::arg("scene"), py::arg("defines") = py::none(), py::kw_only(), py::arg("width") = py::none(),
        py::arg("height") = py::none(), py::arg("max_depth") = py::none(),
        "Loads a JSON or Mitsuba XML scene file, or a dict in our JSON format. Other keywords (and `defines`) are the XML's -D values.");
  m.def("compare", &compare, py::arg("image"), py::arg("reference"),
        "Error metrics of an image against a reference: an array, a file name, or a list of independent renders "
        "(whose spread gives the floor, and relmse_floor_free).");
  m.def("converge", &converge, py::arg("scene"), py::arg("integrators"), py::arg("time"),
        py::arg("checkpoints") = py::none(), py::kw_only(), py::arg("references"), py::arg("seed") = py::none(),
        py::arg("threads") = py::none(),
        "Equal-time runs: each integrator for `time` seconds, its error against the references at each checkpoint; rows as dicts.");
  m.def("read_image", [](const std::string& path) {
        Image image;
        {
          py::gil_scoped_release release;
          image = read_image(path);
        }
        return to_array(image);
      }, py::arg("path"), "Reads an EXR, HDR, PFM or PNG (PNG: sRGB to linear) as float32 (H, W, 3).");
  m.def("write_image", [](const std::string& path, const py::object& array, float exposure) {
        const Image image = from_array(array, path.c_str());
        py::gil_scoped_release release;
        write_image(path, image, exposure);
      }, py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0f,
      "Writes linear RGB: EXR, HDR and PFM as they are, PNG tone-mapped (exposure in stops) and sRGB-encoded.");
}
