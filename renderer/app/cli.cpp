#include "app/cli.h"

#include "atomic_file.h"
#include "scene/gltf_loader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <new>
#include <unistd.h>

namespace fs = std::filesystem;

namespace ssgi::cli {

const char* kCommonUsage =
    R"(  SCENE                 scene file (.json) or glTF (.gltf/.glb), or a shipped scene's name
                        (cornell-box, sponza, ...; an unknown name lists them); default
                        cornell-box
  --size WxH            image size (default 512x512)
  --set KEY=VALUE       override a method setting (repeatable; see docs/settings.md)
  --device NAME         use the Vulkan device whose name contains NAME (or SSGI_DEVICE)
  --validation          enable the Khronos validation layer with synchronization validation
                        (or SSGI_VALIDATION=1); any message makes the exit status non-zero
)";

std::vector<RunFile> sceneInputs(const Scene& scene) {
    std::vector<RunFile> inputs;
    for (const std::string& file : filesRead())
        inputs.push_back(
            {file == scene.sourcePath ? "the scene file" : "a file the scene reads", file});
    return inputs;
}

std::string optionValue(int argc, char** argv, int& i) {
    if (i + 1 >= argc) throw InputError(std::string(argv[i]) + " needs a value");
    return argv[++i];
}

namespace {

// A whole number in lo..1000000, the one range an error states.
uint32_t parseCountFrom(const std::string& option, const std::string& text, long long lo) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE || v < lo || v > 1000000)
        throw InputError(option + ": '" + text + "' is not a whole number in " +
                         std::to_string(lo) + "..1000000");
    return uint32_t(v);
}

} // namespace

uint32_t parseCount(const std::string& option, const std::string& text) {
    return parseCountFrom(option, text, 0);
}

std::pair<std::string, double> parseSetting(const std::string& option, const std::string& text) {
    const size_t eq = text.find('=');
    char* end = nullptr;
    const double number = eq == std::string::npos ? 0.0 : std::strtod(text.c_str() + eq + 1, &end);
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size() || *end != '\0')
        throw InputError(option + ": expected KEY=NUMBER, got '" + text + "'");
    return {text.substr(0, eq), number};
}

uint32_t parsePositiveCount(const std::string& option, const std::string& text) {
    return parseCountFrom(option, text, 1);
}

double parseNumber(const std::string& option, const std::string& text, double lo, double hi) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v) || !(v >= lo && v <= hi)) {
        char range[96];
        if (std::isinf(hi))
            std::snprintf(range, sizeof range, "a number >= %g", lo);
        else
            std::snprintf(range, sizeof range, "a number in [%g, %g]", lo, hi);
        throw InputError(option + ": '" + text + "' is not " + range);
    }
    return v;
}

bool parseCommonArg(int argc, char** argv, int& i, CommonArgs& a) {
    const std::string arg = argv[i];
    if (arg == "--size") {
        std::string v = optionValue(argc, argv, i);
        size_t x = v.find('x');
        if (x == std::string::npos) throw InputError("--size: expected WxH, got '" + v + "'");
        a.width = parseCount("--size", v.substr(0, x));
        a.height = parseCount("--size", v.substr(x + 1));
    } else if (arg == "--set") {
        a.settings.push_back(parseSetting("--set", optionValue(argc, argv, i)));
    } else if (arg == "--device") {
        a.device = optionValue(argc, argv, i);
    } else if (arg == "--validation") {
        a.validation = true;
    } else if (arg.rfind("--", 0) == 0) {
        return false;
    } else if (a.scene.empty()) {
        a.scene = arg;
    } else {
        throw InputError("more than one scene given: " + a.scene + " and " + arg);
    }
    return true;
}

std::string dataDirectory() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path installed = exe.parent_path().parent_path() / "share" / "ssgi";
        if (fs::is_directory(installed / "scenes", ec)) return installed.string();
    }
    return SSGI_SOURCE_DIR;
}

std::string defaultScene() {
    const std::string local = "scenes/cornell-box.json";
    return fs::exists(local) ? local : dataDirectory() + "/" + local;
}

std::vector<std::string> shippedSceneNames() {
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(fs::path(dataDirectory()) / "scenes", ec), end; !ec && it != end;
         it.increment(ec))
        if (it->path().extension() == ".json" && it->is_regular_file(ec))
            names.push_back(it->path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string resolveScene(const std::string& argument) {
    if (argument.empty()) return defaultScene();
    std::error_code ec;
    const fs::path path(argument);
    // A path wins; so does anything that is not a bare name (the loader says it is missing).
    if (fs::exists(fs::symlink_status(path, ec)) || path.has_extension() ||
        argument.find('/') != std::string::npos)
        return argument;
    const std::vector<std::string> names = shippedSceneNames();
    if (std::find(names.begin(), names.end(), argument) != names.end())
        return (fs::path(dataDirectory()) / "scenes" / (argument + ".json")).string();
    std::string list;
    for (const std::string& name : names)
        list += (list.empty() ? "" : ", ") + name;
    const std::string folder = (fs::path(dataDirectory()) / "scenes").string();
    throw InputError("'" + argument + "' is neither a file nor the name of a shipped scene; " +
                     (names.empty() ? "no shipped scenes were found in " + folder
                                    : "the shipped scenes: " + list + " (in " + folder + ")"));
}

void finishCommonArgs(CommonArgs& a) {
    a.scene = resolveScene(a.scene);
    finishDeviceArgs(a);
}

void finishDeviceArgs(CommonArgs& a) {
    if (const char* env = std::getenv("SSGI_DEVICE"); env && a.device.empty()) a.device = env;
#ifndef NDEBUG
    a.validation = true; // debug builds always validate
#endif
    if (const char* env = std::getenv("SSGI_VALIDATION"); env && std::string(env) == "1")
        a.validation = true;
}

Scene loadSceneWithSettings(const CommonArgs& args) {
    SettingOverrides overrides;
    for (const auto& [name, value] : args.settings)
        overrides[name] = checkSetting("--set", name, value);
    return loadScene(args.scene, overrides);
}

int guardedMain(int argc, char** argv, int (*run)(int, char**)) {
    try {
        return run(argc, argv);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        // What asked for it is not known here; what it means is.
        std::fprintf(stderr, "error: out of memory: the input or the sizes asked for need more "
                             "memory than this machine can give (std::bad_alloc); try a smaller "
                             "--size, fewer samples or a smaller scene\n");
        return 2;
    } catch (const fs::filesystem_error& e) {
        // Its own text ("filesystem error: status: ... [path]") said what failed in C++ terms.
        const std::string path = e.path1().string();
        std::fprintf(stderr, "error: %s%s\n", path.empty() ? "" : (path + ": ").c_str(),
                     e.code().message().c_str());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}

int validationStatus(uint32_t messages) {
    if (messages == 0) return 0;
    std::fprintf(stderr, "error: the validation layer reported %u message(s)\n", messages);
    return 1;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

void writeTextAtomically(const std::string& path, const std::string& text) {
    writeFileAtomically(path, text);
}

} // namespace ssgi::cli
