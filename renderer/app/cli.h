// What the command-line programs share: the options every one of them takes (scene, size,
// settings, device, validation), the checks on their values, and writing files whole.
#pragma once

#include "atomic_file.h"
#include "scene/scene.h"

#include <string>
#include <utility>
#include <vector>

namespace ssgi::cli {

struct CommonArgs {
    std::string scene;
    uint32_t width = 512, height = 512;
    std::string device;
    bool validation = false;
    std::vector<std::pair<std::string, double>> settings; // --set, checked before loading
};

// Usage lines of the common options.
extern const char* kCommonUsage;

// Takes argv[i] (and its value, advancing i) when it is a common option or the scene; returns
// false for anything else. Throws InputError for a malformed value.
bool parseCommonArg(int argc, char** argv, int& i, CommonArgs& args);
// Where the files a program ships with are (scenes/, docs/stability_plot.py): PREFIX/share/ssgi
// beside an installed program's PREFIX/bin, else the source tree it was built from.
std::string dataDirectory();
// scenes/cornell-box.json from the working directory when it is there, else from dataDirectory().
std::string defaultScene();
// The names of the shipped scenes (dataDirectory()'s scenes/*.json without the extension),
// sorted: the names resolveScene takes.
std::vector<std::string> shippedSceneNames();
// The scene file a program's SCENE argument names, the one place the programs resolve it: the
// path itself when something is there (a path always wins); a name with no folder and no
// extension that is no file, the shipped scene of that name (dataDirectory()/scenes/NAME.json),
// as `python -m ssgi` takes it; defaultScene() for "". A name that is neither is an InputError
// listing the shipped names; a missing path is left to the loader, which names it.
std::string resolveScene(const std::string& argument);
// Fills what was not given: the scene (resolveScene), then finishDeviceArgs.
void finishCommonArgs(CommonArgs& args);
// SSGI_DEVICE and SSGI_VALIDATION where not given; debug builds always validate.
void finishDeviceArgs(CommonArgs& args);
// The scene with the --set overrides applied and checked.
Scene loadSceneWithSettings(const CommonArgs& args);

// The files the scene loaders read (filesRead), as the inputs of checkRunFiles: "the scene file"
// (`scene`'s own) and "a file the scene reads" (its glTFs, buffers and images).
std::vector<RunFile> sceneInputs(const Scene& scene);

// The value of option argv[i], advancing i; InputError when there is none.
std::string optionValue(int argc, char** argv, int& i);
uint32_t parseCount(const std::string& option, const std::string& text);
// "KEY=NUMBER" (a setting); the key is checked when the scene takes it.
std::pair<std::string, double> parseSetting(const std::string& option, const std::string& text);
// parseCount, at least 1 (a number of frames, steps, ...).
uint32_t parsePositiveCount(const std::string& option, const std::string& text);
// A finite decimal number in [lo, hi] (hi may be infinity); InputError naming the option and
// the range otherwise, so a threshold of "-1", "0.1x" or "nan" is bad input, never a result.
double parseNumber(const std::string& option, const std::string& text, double lo, double hi);

// Runs `run` and turns what it throws into the exit status, with `error: ...` on stderr: 2 for
// bad input (InputError), 1 for anything else. Every program's main() is this.
int guardedMain(int argc, char** argv, int (*run)(int, char**));
// The exit status of a run whose validation layer reported `messages`: 1 (with a message)
// when there were any, else 0.
int validationStatus(uint32_t messages);

double median(std::vector<double> values);
// Writes text whole or not at all (writeFileAtomically), through a link such as /dev/stdout.
void writeTextAtomically(const std::string& path, const std::string& text);

} // namespace ssgi::cli
