// The module `ssgi`: the renderer, the path-traced reference, the error metrics and the image
// files of the programs, from Python with NumPy arrays (docs/python.md). Every function here calls
// the code the programs call; errors are the programs' messages as Python exceptions.
#include "module.h"

#include "image_io.h"
#include "metrics/comparison.h"
#include "metrics/error_map.h"
#include "metrics/golden.h"
#include "reference/cache.h"
#include "reference/render.h"
#include "scene/warnings.h"
#include "vk/context.h"

#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <optional>

namespace ssgi::python {

namespace {

std::mutex warningsMutex;
std::vector<std::string> pendingWarnings; // said by the library since the last raiseWarnings()
PyObject* warningCategory = nullptr;      // ssgi.SsgiWarning

// The library's warnings come from any thread, the GIL held or not: kept until the call that
// caused them hands them to Python.
void keepWarning(const std::string& text) {
    std::lock_guard<std::mutex> lock(warningsMutex);
    pendingWarnings.push_back(text);
}

// An image given as an array or as a file; `linear` says whether it holds linear radiance (a
// float array unless told otherwise, an integer array never, a file when it is an .exr, as
// compare reads files).
metrics::Image imageArg(const py::handle& object, const std::string& what,
                        const std::optional<bool>& linear, bool& isLinear, std::string& name,
                        ImageAttributes* attributes = nullptr) {
    if (isPath(object)) {
        name = pathFrom(object, what);
        isLinear = std::filesystem::path(name).extension() == ".exr";
        py::gil_scoped_release release;
        metrics::Image image = metrics::loadImage(name, attributes);
        metrics::warnIfNotOpaque(image, name); // as compare warns
        return image;
    }
    name = what;
    isLinear = linear.value_or(!holdsIntegers(object));
    return imageFrom(object, what);
}

py::dict compare(const ImageOrPathArg& a, const ImageOrPathArg& b, const FloatArg& exposure,
                 const FloatArg& ppd, const std::optional<FloatArg>& maxDiff,
                 const std::optional<BoolArg>& linearArg, const BoolArg& mapsArg) {
    const std::optional<bool> linear =
        linearArg ? std::optional(boolArg("linear", linearArg->value)) : std::nullopt;
    const bool maps = boolArg("maps", mapsArg.value);
    bool aLinear = true, bLinear = true;
    std::string aName, bName;
    const metrics::Image test = imageArg(a.value, "a", linear, aLinear, aName);
    ImageAttributes referenceHeader; // a reference's EXR records its own noise
    const metrics::Image reference =
        imageArg(b.value, "b", linear, bLinear, bName, &referenceHeader);
    metrics::RecordedNoise referenceNoise = metrics::recordedNoise(referenceHeader);
    // A reference() image carries what a reference's EXR records of itself.
    if (!isPath(b.value) && py::hasattr(b.value, "samples") && !b.value.attr("samples").is_none()) {
        referenceNoise.samples = countArg("b.samples", b.value.attr("samples"), 1, UINT32_MAX);
        const py::object noise = b.value.attr("noise");
        referenceNoise.noise = noise.is_none() ? std::nan("") : noise.cast<double>();
    }
    metrics::requireSize(reference, bName, test, aName);
    metrics::requireComparable(aName, aLinear, bName, bLinear, reference);
    metrics::ComparisonOptions options;
    options.linear = aLinear;
    options.exposure = numberArg("exposure", exposure.value, 1e-6, 1e6);
    options.ppd = numberArg("ppd", ppd.value, 1e-3, 1e4);
    if (maxDiff) options.maxDiff = numberArg("max_diff", maxDiff->value, 0.0, 255.0);
    metrics::Comparison c;
    std::vector<double> relative;
    std::vector<float> errorColours, flipColours;
    {
        py::gil_scoped_release release;
        c = metrics::compareImages(test, reference, options);
        if (maps) {
            relative = metrics::relativeErrorPerPixel(test, reference);
            errorColours = metrics::errorMap(test, reference);
            flipColours = metrics::flip::flipErrorMap(c.flip.map);
        }
    }
    raiseWarnings();
    const metrics::Figures& f = c.regions.front().second;
    py::dict d;
    d["relmse"] = f.relMse;
    d["rmse"] = f.rmse;
    d["mae"] = f.mae;
    d["ssim"] = f.ssim;
    d["flip"] = c.flip.mean;
    d["pixels"] = f.pixels;
    d["non_finite_pixels"] = c.nonFinitePixels;
    d["reference_noise"] = referenceNoise.estimated() ? py::object(py::float_(referenceNoise.noise))
                                                      : py::object(py::none());
    d["reference_samples"] = referenceNoise.recorded()
                                 ? py::object(py::int_(referenceNoise.samples))
                                 : py::object(py::none());
    if (options.maxDiff >= 0.0) d["diff_fraction"] = c.diffFraction;
    if (maps) {
        const uint32_t w = test.width, h = test.height;
        py::dict m;
        m["relative_error"] = mapArray(relative, w, h);
        m["ssim"] = mapArray(c.ssim, w, h);
        m["flip"] = mapArray(c.flip.map, w, h);
        m["error_map"] = rgbArray(std::move(errorColours), w, h);
        m["flip_map"] = rgbArray(std::move(flipColours), w, h);
        d["maps"] = m;
    }
    return d;
}

ImageResult reference(const std::shared_ptr<SceneObject>& sceneObject, const SizeArg& size,
                      const std::string& mode, const IntArg& spp,
                      const std::optional<FloatArg>& noise, const IntArg& seed,
                      const std::optional<FloatArg>& time, const BoolArg& jitter,
                      const std::optional<FloatArg>& lightRadius, const IntArg& threads,
                      const BoolArg& cache, const std::optional<PathArg>& cacheDir,
                      const ProgressArg& progress) {
    SceneObject& scene = sceneArg(sceneObject);
    reference::ReferenceRequest request;
    reference::ReferenceOptions& o = request.options;
    o.mode = reference::parseMode(mode, "mode");
    sizeArg(size.value, o.width, o.height, 1, kMaxImageSide); // reference's range (--size)
    o.spp = countArg("spp", spp.value, 1, 1u << 24);
    // The noise target as the reference program reads --noise (renderReference refuses one
    // too small to reach): 0 or None renders every sample.
    o.noiseTarget = noise ? numberArg("noise", noise->value, 0.0, 1.0) : 0.0;
    o.seed = countArg("seed", seed.value, 0, UINT32_MAX);
    o.jitter = boolArg("jitter", jitter.value);
    o.threads = countArg("threads", threads.value, 0, 1024);
    if (time) request.time = float(numberArg("time", time->value, 0.0, 1e9));
    if (lightRadius)
        request.lightRadius = float(numberArg("light_radius", lightRadius->value, 0.0, 1e9));
    request.useCache = boolArg("cache", cache.value);
    if (cacheDir) request.cacheDir = pathFrom(cacheDir->value, "cache_dir");

    // Progress: reference's bar on stderr (True; None: when stderr is a terminal), or a
    // callable given (samples done per pixel, the spp limit, the noise). Either way the
    // render stops for a signal (Ctrl-C) or an exception the callable raises.
    py::object callback;
    const py::object shown = progress.value;
    if (PyCallable_Check(shown.ptr())) {
        callback = shown;
    } else if (shown.is_none()) {
        const py::object stderrFile = py::module_::import("sys").attr("stderr");
        o.progress = !stderrFile.is_none() && stderrFile.attr("isatty")().cast<bool>();
    } else {
        try {
            o.progress = boolArg("progress", shown);
        } catch (const ArgumentTypeError&) { // boolArg's words, with what else is taken
            throw ArgumentTypeError("progress: expected True, False, None or a callable of "
                                    "(samples, spp, noise), got " +
                                    std::string(py::repr(shown)) + " (" + typeName(shown) + ")");
        }
    }
    std::optional<py::error_already_set> stopped;
    // Signals are checked at every call (about every 10 ms); the callable is called at most
    // every 50 ms, and after every pass.
    auto lastCall = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    o.onProgress = [&](uint32_t done, uint32_t passEnd, double passFraction, double noise) {
        py::gil_scoped_acquire acquire;
        try {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            const auto now = std::chrono::steady_clock::now();
            if (callback && (done == passEnd || now - lastCall >= std::chrono::milliseconds(50))) {
                lastCall = now;
                callback(double(done) + (double(passEnd) - done) * passFraction, o.spp, noise);
            }
        } catch (py::error_already_set& error) {
            stopped.emplace(std::move(error));
            return false;
        }
        return true;
    };
    reference::ReferenceImage image;
    try {
        py::gil_scoped_release release;
        image = reference::requestedReference(*scene.scene, scene.path, request);
    } catch (const reference::Cancelled&) {
        if (stopped) throw *stopped;
        throw;
    }
    raiseWarnings();
    if (image.nonFiniteSamples > 0)
        throw std::runtime_error(std::to_string(image.nonFiniteSamples) +
                                 " samples were NaN or infinite and were dropped");
    py::object array = rgbArray(std::move(image.rgba), image.width, image.height);
    return imageObject(array, std::isnan(image.noise) ? std::nullopt : std::optional(image.noise),
                       image.samples);
}

void writeImageFile(const PathArg& path, const ImageArg& array, const BoolArg& linearArg,
                    const FloatArg& exposure) {
    const std::string file = pathFrom(path.value, "path");
    metrics::Image image = imageFrom(array.value, "image");
    const bool linear = boolArg("linear", linearArg.value);
    const float e = float(numberArg("exposure", exposure.value, 1e-6, 1e6));
    // A PNG holds display values in [0, 1]: a float image (linear radiance) is display-encoded
    // as render's PNG is (tonemap(): exposure, the ACES fit, sRGB), unless linear=True writes
    // its values as they are; integers (uint8, uint16) are display values already.
    const bool png = std::filesystem::path(file).extension() == ".png";
    if (png && !linear && !holdsIntegers(array.value)) displayEncode(image, e);
    if (png) {
        size_t outside = 0;
        for (float v : image.rgba)
            outside += v < 0.0f || v > 1.0f;
        if (outside > 0)
            warn(file + ": " + std::to_string(outside) +
                 " values outside [0, 1] are clipped to it in the PNG (it stores display values; "
                 "linear=False display-encodes a linear image)");
    }
    raiseWarnings();
    py::gil_scoped_release release;
    writeImage(file, image.width, image.height, image.rgba);
}

} // namespace

void displayEncode(metrics::Image& image, float exposure) {
    // The ACES fit is a curve over radiance, which is not negative: below 0 it rises again to
    // white. A negative value displays as no light; NaN stays NaN (std::max keeps its first).
    for (size_t i = 0; i < image.rgba.size(); ++i)
        if (i % 4 != 3)
            image.rgba[i] = metrics::displayValue(std::max(image.rgba[i], 0.0f), exposure);
}

ImageResult imageObject(const py::object& array, std::optional<double> noise,
                        std::optional<uint32_t> samples) {
    return {py::module_::import("ssgi._image")
                .attr("Image")(array, py::arg("noise") = noise, py::arg("samples") = samples)};
}

void raiseWarnings() {
    std::vector<std::string> texts;
    {
        std::lock_guard<std::mutex> lock(warningsMutex);
        texts.swap(pendingWarnings);
    }
    for (const std::string& text : texts)
        if (PyErr_WarnEx(warningCategory, text.c_str(), 1) != 0) throw py::error_already_set();
}

void defineImages(py::module_& m) {
    m.def(
        "read_image",
        [](const PathArg& path, const BoolArg& alphaArg) {
            const std::string file = pathFrom(path.value, "path");
            const bool alpha = boolArg("alpha", alphaArg.value);
            metrics::Image image;
            {
                py::gil_scoped_release release;
                image = metrics::loadImage(file);
            }
            raiseWarnings();
            return alpha ? rgbaArray(std::move(image.rgba), image.width, image.height)
                         : rgbArray(std::move(image.rgba), image.width, image.height);
        },
        py::arg("path"), py::arg("alpha") = false,
        "An .exr (linear) or .png (display values in [0, 1]) as float32, height x width x 3 (x 4 "
        "with alpha=True).");
    m.def("write_image", &writeImageFile, py::arg("path"), py::arg("image"),
          py::arg("linear") = false, py::arg("exposure") = 1.0,
          "Writes an array as render writes its files: .exr linear (half floats where they hold "
          "every value); .png 8-bit, a float image display-encoded as render's PNG is "
          "(tonemap(image, exposure)) unless `linear` writes its values as they are (clipped "
          "to [0, 1], with an ssgi.SsgiWarning); whole or not at all. The array is (h, w) grey "
          "or (h, w, 1, 3 or 4) of floats, uint8 (scaled by 1/255: display values) or uint16 "
          "(by 1/65535).");
    m.def(
        "tonemap",
        [](const ImageArg& array, const FloatArg& exposure) {
            metrics::Image image = imageFrom(array.value, "image");
            displayEncode(image, float(numberArg("exposure", exposure.value, 1e-6, 1e6)));
            return rgbArray(std::move(image.rgba), image.width, image.height);
        },
        py::arg("image"), py::arg("exposure") = 1.0,
        "The composite pass's display transform: times exposure, the ACES fit, sRGB encoding; "
        "negative values (no radiance) display as black, NaN stays NaN.");
    m.def(
        "compare", &compare, py::arg("a"), py::arg("b"), py::arg("exposure") = 1.0,
        py::arg("ppd") = metrics::flip::kDefaultPpd, py::arg("max_diff") = py::none(),
        py::arg("linear") = py::none(), py::arg("maps") = true,
        "compare's figures of `a` against the reference `b` (arrays or files): relmse, rmse, "
        "mae, ssim, flip, pixels, non_finite_pixels, reference_noise and reference_samples "
        "(what a reference's EXR records of itself, else None), diff_fraction (with max_diff) "
        "and the per-pixel maps. `linear`: whether arrays hold linear radiance (None: float arrays "
        "do, uint8/uint16 ones hold display values).");
    m.def("reference", &reference, py::arg("scene"), py::arg("size") = py::make_tuple(256, 256),
          py::kw_only(), py::arg("mode") = "full", py::arg("spp") = reference::kDefaultSampleCap,
          py::arg("noise") = reference::kDefaultNoiseTarget, py::arg("seed") = 1,
          py::arg("time") = py::none(), py::arg("jitter") = false,
          py::arg("light_radius") = py::none(), py::arg("threads") = 0, py::arg("cache") = true,
          py::arg("cache_dir") = py::none(), py::arg("progress") = py::none(),
          "The path-traced reference of `scene` at `size` (width, height) as the reference "
          "program renders it (and from the same cache): an ssgi.Image of float32, height x "
          "width x 3, carrying its `samples` per pixel and estimated `noise` (which compare() "
          "reads from it as from the program's EXR), by default as the program's: until its "
          "estimated "
          "noise is 1% (`noise`; 0 or None: no target), at most `spp` samples per pixel. "
          "`progress`: True shows reference's bar on "
          "stderr (None: when stderr is a terminal); a callable is called at most every 50 ms "
          "and after each pass with (samples done per pixel, spp, estimated noise). Ctrl-C "
          "stops it within about 10 ms (KeyboardInterrupt).");
}

} // namespace ssgi::python

PYBIND11_MODULE(_ssgi, m) {
    namespace py = pybind11;
    // The classes and functions say they are ssgi's (ssgi.Scene in signatures and reprs): the
    // package re-exports this module's names.
    const py::object name = m.attr("__name__");
    m.attr("__name__") = "ssgi";
    m.doc() = "The ssgi renderer, its path-traced reference and its error metrics (docs/python.md)";
    ssgi::python::defineErrors(m);
    ssgi::python::warningCategory =
        PyErr_NewExceptionWithDoc("ssgi.SsgiWarning",
                                  "What the renderer, the scene loader, the reference cache or "
                                  "the image writer warns about.",
                                  PyExc_UserWarning, nullptr);
    m.add_object("SsgiWarning", py::handle(ssgi::python::warningCategory));
    ssgi::python::defineScene(m);
    ssgi::python::defineRenderer(m);
    ssgi::python::defineDevices(m);
    ssgi::python::defineImages(m);
    m.attr("__name__") = name;
    ssgi::setWarningSink(&ssgi::python::keepWarning);
    // The devices close while Python and the driver are both still there.
    py::module_::import("atexit").attr("register")(m.attr("_release_devices"));
}
