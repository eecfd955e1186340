// The module `ssgi`: the renderer, the path-traced reference, the error metrics and the image
// files of the programs, from Python with NumPy arrays (docs/python.md). Every function here calls
// the code the programs call; errors are the programs' messages as Python exceptions.
#include "module.h"

#include "image_io.h"
#include "metrics/comparison.h"
#include "metrics/error_map.h"
#include "metrics/golden.h"
#include "reference/cache.h"
#include "vk/context.h"

#include <pybind11/stl.h>

#include <filesystem>

namespace ssgi::python {

namespace {

// An image given as an array or as a file; `linear` says whether it holds linear radiance (an
// array unless told otherwise, a file when it is an .exr, as compare reads files).
metrics::Image imageArg(const py::handle& object, const std::string& what, const py::object& linear,
                        bool& isLinear, std::string& name, ImageAttributes* attributes = nullptr) {
    if (isPath(object)) {
        name = pathFrom(object);
        isLinear = std::filesystem::path(name).extension() == ".exr";
        py::gil_scoped_release release;
        metrics::Image image = metrics::loadImage(name, attributes);
        metrics::warnIfNotOpaque(image, name); // as compare warns
        return image;
    }
    name = what;
    isLinear = linear.is_none() || linear.cast<bool>();
    return imageFrom(object, what);
}

py::dict compare(const py::object& a, const py::object& b, const py::object& exposure,
                 const py::object& ppd, const py::object& maxDiff, const py::object& linear,
                 bool maps) {
    bool aLinear = true, bLinear = true;
    std::string aName, bName;
    const metrics::Image test = imageArg(a, "a", linear, aLinear, aName);
    ImageAttributes referenceHeader; // a reference's EXR records its own noise
    const metrics::Image reference = imageArg(b, "b", linear, bLinear, bName, &referenceHeader);
    const metrics::RecordedNoise referenceNoise = metrics::recordedNoise(referenceHeader);
    metrics::requireSize(reference, bName, test, aName);
    metrics::requireComparable(aName, aLinear, bName, bLinear, reference);
    metrics::ComparisonOptions options;
    options.linear = aLinear;
    options.exposure = numberArg("exposure", exposure, 1e-6, 1e6);
    options.ppd = numberArg("ppd", ppd, 1e-3, 1e4);
    if (!maxDiff.is_none()) options.maxDiff = numberArg("max_diff", maxDiff, 0.0, 255.0);
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

py::array reference(const std::shared_ptr<SceneObject>& scene, const std::string& mode,
                    const py::object& size, const py::object& spp, const py::object& noise,
                    const py::object& seed, const py::object& time, bool jitter,
                    const py::object& lightRadius, const py::object& threads, bool cache,
                    const py::object& cacheDir) {
    reference::ReferenceRequest request;
    reference::ReferenceOptions& o = request.options;
    o.mode = reference::parseMode(mode, "mode");
    sizeArg(size, o.width, o.height, 1, kMaxImageSide); // reference's range (--size)
    o.spp = countArg("spp", spp, 1, 1u << 24);
    if (!noise.is_none()) o.noiseTarget = numberArg("noise", noise, 1e-6, 1.0);
    o.seed = countArg("seed", seed, 0, UINT32_MAX);
    o.jitter = jitter;
    o.threads = countArg("threads", threads, 0, 1024);
    if (!time.is_none()) request.time = float(numberArg("time", time, 0.0, 1e9));
    if (!lightRadius.is_none())
        request.lightRadius = float(numberArg("light_radius", lightRadius, 0.0, 1e9));
    request.useCache = cache;
    if (!cacheDir.is_none()) request.cacheDir = pathFrom(cacheDir);
    reference::ReferenceImage image;
    {
        py::gil_scoped_release release;
        image = reference::requestedReference(*scene->scene, scene->path, request);
    }
    if (image.nonFiniteSamples > 0)
        throw std::runtime_error(std::to_string(image.nonFiniteSamples) +
                                 " samples were NaN or infinite and were dropped");
    return rgbArray(std::move(image.rgba), image.width, image.height);
}

} // namespace

void defineImages(py::module_& m) {
    m.def(
        "read_image",
        [](const py::object& path, bool alpha) {
            const std::string file = pathFrom(path);
            metrics::Image image;
            {
                py::gil_scoped_release release;
                image = metrics::loadImage(file);
            }
            return alpha ? rgbaArray(std::move(image.rgba), image.width, image.height)
                         : rgbArray(std::move(image.rgba), image.width, image.height);
        },
        py::arg("path"), py::arg("alpha") = false,
        "An .exr (linear) or .png (display values in [0, 1]) as float32, height x width x 3 (x 4 "
        "with alpha=True).");
    m.def(
        "write_image",
        [](const py::object& path, const py::object& array) {
            const std::string file = pathFrom(path);
            const metrics::Image image = imageFrom(array, "image");
            py::gil_scoped_release release;
            writeImage(file, image.width, image.height, image.rgba);
        },
        py::arg("path"), py::arg("image"),
        "Writes an array as render writes its files: .exr linear (half floats where they hold "
        "every value), .png 8-bit of values already display-encoded; whole or not at all.");
    m.def(
        "tonemap",
        [](const py::object& array, const py::object& exposure) {
            metrics::Image image = imageFrom(array, "image");
            const float e = float(numberArg("exposure", exposure, 1e-6, 1e6));
            for (size_t i = 0; i < image.rgba.size(); ++i)
                if (i % 4 != 3) image.rgba[i] = metrics::displayValue(image.rgba[i], e);
            return rgbArray(std::move(image.rgba), image.width, image.height);
        },
        py::arg("image"), py::arg("exposure") = 1.0,
        "The composite pass's display transform: times exposure, the ACES fit, sRGB encoding.");
    m.def("compare", &compare, py::arg("a"), py::arg("b"), py::arg("exposure") = 1.0,
          py::arg("ppd") = metrics::flip::kDefaultPpd, py::arg("max_diff") = py::none(),
          py::arg("linear") = py::none(), py::arg("maps") = true,
          "compare's figures of `a` against the reference `b` (arrays or files): relMSE, RMSE, "
          "MAE, SSIM, mean FLIP, and the per-pixel maps.");
    m.def("reference", &reference, py::arg("scene"), py::kw_only(), py::arg("mode") = "full",
          py::arg("size") = py::make_tuple(256, 256), py::arg("spp") = 256,
          py::arg("noise") = py::none(), py::arg("seed") = 1, py::arg("time") = py::none(),
          py::arg("jitter") = false, py::arg("light_radius") = py::none(), py::arg("threads") = 0,
          py::arg("cache") = true, py::arg("cache_dir") = py::none(),
          "The path-traced reference as the reference program renders it (and from the same "
          "cache), float32, height x width x 3.");
}

} // namespace ssgi::python

PYBIND11_MODULE(ssgi, m) {
    m.doc() = "The ssgi renderer, its path-traced reference and its error metrics (docs/python.md)";
    // Bad input is a ValueError (ssgi.InputError); a failure of the device a RuntimeError.
    pybind11::register_exception<ssgi::InputError>(m, "InputError", PyExc_ValueError);
    pybind11::register_exception<ssgi::vk::VulkanError>(m, "VulkanError", PyExc_RuntimeError);
    ssgi::python::defineScene(m);
    ssgi::python::defineRenderer(m);
    ssgi::python::defineImages(m);
    // The devices close while Python and the driver are both still there.
    pybind11::module_::import("atexit").attr("register")(m.attr("_release_devices"));
}
