// Every file every program writes lands whole or not at all: on a full disk (a file-size limit,
// /dev/full) the program says so and exits 2 with nothing at the path; a signal in the middle
// of a write leaves no temporary; a name near the 255-byte limit works; a symbolic link is
// written through, never replaced.
#include "atomic_file.h"
#include "bad_input.h"
#include "image_io.h"
#include "support.h"

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>

namespace fs = std::filesystem;
using namespace ssgi;
using ssgi::test::BadInput;

namespace {

// Files and folders whose names start with '.' (temporaries, backups) under `dir`.
std::string hiddenFiles(const fs::path& dir) {
    std::string found;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.path().filename().string()[0] == '.') found += entry.path().string() + " ";
    return found;
}

std::string program(const char* name) {
    return (fs::read_symlink("/proc/self/exe").parent_path().parent_path() / name).string();
}

TEST_F(BadInput, EveryProgramWritesWholeOrNothing) {
    // Two noisy images for compare: its maps and JSON are larger than the limit below.
    std::mt19937 random(7);
    std::vector<float> a(64 * 64 * 4, 1.0f), b = a;
    for (size_t i = 0; i < a.size(); ++i)
        if (i % 4 != 3)
            a[i] = float(random() % 256) / 255.0f, b[i] = float(random() % 256) / 255.0f;
    const std::string pngA = (dir_ / "a.png").string(), pngB = (dir_ / "b.png").string();
    writeImage(pngA, 64, 64, a);
    writeImage(pngB, 64, 64, b);

    const std::string box = test::sourcePath("tests/scenes/empty-box.json");
    const fs::path out = dir_ / "out";
    // A file-size limit of one or two KiB stands for a full disk: every write past it fails
    // (with the signal it would also send ignored, as a full disk sends none).
    const std::string full = "trap '' XFSZ; ulimit -f 2; ";
    const std::pair<std::string, std::string> cases[] = {
        {full + program("render") + " " + box + " --size 64x64 --output " +
             (out / "r.png").string(),
         "too large"},
        {full + program("walkthrough") + " " + box + " --still --frames 1 --size 64x64 --exr " +
             "--frames-dir " + (out / "frames").string(),
         "too large"},
        {full + program("reference") + " " + box + " --size 32x32 --spp 1 --no-cache --quiet " +
             "--output " + (out / "ref.exr").string() + " --png " + (out / "ref.png").string(),
         "too large"},
        {full + program("compare") + " " + pngA + " " + pngB + " --error-map " +
             (out / "map.png").string(),
         "too large"},
        {program("compare") + " " + pngA + " " + pngB + " --json /dev/full", "No space left"},
    };
    for (const auto& [command, reason] : cases) {
        SCOPED_TRACE(command);
        const test::CommandResult run = test::runCommand(command);
        EXPECT_EQ(run.status, 2) << run.output;
        EXPECT_NE(run.output.find("error: "), std::string::npos) << run.output;
        EXPECT_NE(run.output.find(reason), std::string::npos) << run.output;
        // Nothing at all: no truncated file, no temporary (the folders may stay).
        if (fs::exists(out)) {
            for (const auto& entry : fs::recursive_directory_iterator(out))
                EXPECT_TRUE(entry.is_directory()) << entry.path();
        }
    }

    // A name of 255 bytes, the most a file name may have: the temporary's is short.
    const fs::path longName = out / (std::string(251, 'n') + ".png");
    const test::CommandResult longRun = test::runCommand(
        program("render") + " " + box + " --size 16x16 --output " + longName.string());
    EXPECT_EQ(longRun.status, 0) << longRun.output;
    EXPECT_TRUE(fs::is_regular_file(longName) &&
                fs::is_regular_file(fs::path(longName).replace_extension(".exr")));

    // Links are written through: to a regular file, that file is replaced and the link stays;
    // to /dev/stdout, the JSON comes out on stdout.
    fs::create_symlink("real.json", out / "link.json");
    fs::create_symlink("/dev/stdout", out / "stdout.json");
    for (const char* name : {"link.json", "stdout.json"}) {
        const test::CommandResult run = test::runCommand(program("compare") + " " + pngA + " " +
                                                         pngA + " --json " + (out / name).string());
        EXPECT_EQ(run.status, 0) << run.output;
        EXPECT_TRUE(fs::is_symlink(out / name)) << name;
        if (std::string(name) == "stdout.json") {
            EXPECT_NE(run.output.find("\"regions\""), std::string::npos) << run.output;
        }
    }
    std::ifstream real(out / "real.json");
    EXPECT_NE(std::string(std::istreambuf_iterator<char>(real), {}).find("\"regions\""),
              std::string::npos);

    // A signal while a large file is being written: the process dies of it and takes its
    // temporary along.
    const fs::path big = out / "big.bin";
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        writeFileAtomically(big.string(), std::string(size_t(64) << 20, 'x'));
        _exit(0);
    }
    const auto start = std::chrono::steady_clock::now();
    while (hiddenFiles(out).empty() &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(20))
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    ::kill(child, SIGTERM);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the write finished before the signal; make it longer";
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
    EXPECT_FALSE(fs::exists(big));
    EXPECT_EQ(hiddenFiles(dir_), "");
}

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// One check for every path a program writes: what it cannot write as asked is refused with
// `error:` naming the path, exit 2, before anything is replaced; what names this process's own
// output is written to it as a stream.
TEST_F(BadInput, EveryOutputPathIsCheckedBeforeAnythingIsWritten) {
    const std::string box = test::sourcePath("tests/scenes/empty-box.json") + " --size 16x16";
    const std::string render = program("render");
    // A NUL cuts a path short: the file at the cut name must not be written.
    write("cut", "kept");
    try {
        writeFileAtomically((dir_ / "cut").string() + std::string(1, '\0') + ".png", "new");
        ADD_FAILURE() << "a path holding a NUL was written";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("NUL"), std::string::npos) << e.what();
    }
    EXPECT_EQ(readAll(dir_ / "cut"), "kept");

    // A read-only file is not replaced.
    const std::string readOnly = write("ro.png", "kept");
    ::chmod(readOnly.c_str(), 0444);
    test::CommandResult run = test::runCommand(render + " " + box + " --output " + readOnly);
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("error: " + readOnly + ": the file is read-only"), std::string::npos)
        << run.output;
    EXPECT_EQ(readAll(readOnly), "kept");
    EXPECT_FALSE(fs::exists(dir_ / "ro.exr"));

    // A link from one output to the other: both cannot be written, so neither is.
    fs::create_symlink("pair.exr", dir_ / "pair.png");
    run = test::runCommand(render + " " + box + " --output " + (dir_ / "pair.png").string());
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("are the same file"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir_ / "pair.exr"));

    // A FIFO nobody reads: refused at once (it blocked forever).
    const fs::path fifo = dir_ / "fifo.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const auto start = std::chrono::steady_clock::now();
    run = test::runCommand("timeout 60 " + render + " " + box + " --output " + fifo.string());
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("no process is reading"), std::string::npos) << run.output;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
    EXPECT_FALSE(fs::exists(dir_ / "fifo.exr"));

    // /dev/stdout, and a link to it, with standard output redirected to a file: the JSON is
    // added to what the log holds, after the program's own lines; the log is not replaced.
    fs::create_symlink("/dev/stdout", dir_ / "stdout.json");
    for (const std::string json : {std::string("/dev/stdout"), (dir_ / "stdout.json").string()}) {
        const fs::path log = dir_ / "log.txt";
        run = test::runCommand("(echo 'the log so far'; " + render + " " + box + " --output " +
                               (dir_ / "o.png").string() + " --profile-json " + json + ") > " +
                               log.string());
        EXPECT_EQ(run.status, 0) << run.output;
        const std::string text = readAll(log);
        EXPECT_EQ(text.rfind("the log so far\nwrote ", 0), 0u) << text;
        EXPECT_NE(text.find("\"passes\""), std::string::npos) << text;
        EXPECT_TRUE(fs::is_symlink(dir_ / "stdout.json"));
    }
}

// An output pair lands together: a signal that arrives between the two renames (sent there by
// the hook) is held until both files have moved, so the pair is the new one, never a new PNG
// beside an old EXR; the process still dies of it.
TEST_F(BadInput, ASignalNeverSplitsAnOutputPair) {
    const fs::path png = dir_ / "pair.png", exr = dir_ / "pair.exr";
    writeFilesAtomically({{png.string(), "old"}, {exr.string(), "old"}});
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        setAfterRenameHook([](size_t moved) {
            if (moved == 1) ::kill(::getpid(), SIGTERM);
        });
        writeFilesAtomically({{png.string(), "new"}, {exr.string(), "new"}});
        _exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
    EXPECT_EQ(readAll(png), "new");
    EXPECT_EQ(readAll(exr), "new");
    EXPECT_EQ(hiddenFiles(dir_), "");

    // The same with the signal taken by another thread, as the renderer's driver threads may
    // take it: the process still dies only once both files have moved.
    writeFilesAtomically({{png.string(), "old"}, {exr.string(), "old"}});
    const pid_t threaded = fork();
    ASSERT_GE(threaded, 0);
    if (threaded == 0) {
        static pthread_t other;
        std::thread sleeper([] { std::this_thread::sleep_for(std::chrono::seconds(30)); });
        other = sleeper.native_handle();
        setAfterRenameHook([](size_t moved) {
            if (moved != 1) return;
            ::pthread_kill(other, SIGTERM);
            std::this_thread::sleep_for(std::chrono::milliseconds(200)); // let it be handled
        });
        writeFilesAtomically({{png.string(), "new"}, {exr.string(), "new"}});
        _exit(0);
    }
    ::waitpid(threaded, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
    EXPECT_EQ(readAll(png), "new");
    EXPECT_EQ(readAll(exr), "new");
}

} // namespace

// No program writes over one of its own inputs or writes two outputs into one file: an output
// naming the scene file, a file the scene reads, the reference image, or another output (by
// `./x`, a symbolic link, a hard link) is refused before any work with `error:` naming both and
// exit 2, and nothing is written (the input was replaced with exit 0; of two outputs one was
// kept while "wrote" was printed for both).
TEST_F(BadInput, NoOutputReplacesAnInputOrAnotherOutput) {
    const std::string original = readAll(test::sourcePath("tests/scenes/empty-box.json"));
    const fs::path box = dir_ / "box.json";
    // A bare glTF whose buffer is a file beside it.
    const std::vector<uint32_t> indices = {0, 1, 2};
    nlohmann::json gltf = test::meshJson(test::kTriangle.size(), indices.size());
    gltf["buffers"][0]["uri"] = "tri.bin";
    const std::string bin = test::meshBytes(test::kTriangle, indices);
    const std::string model = write("tri.gltf", gltf.dump());
    const fs::path buffer = dir_ / "tri.bin";
    std::vector<float> pixels(16 * 16 * 4, 0.5f);
    const std::string pngA = (dir_ / "a.png").string(), pngB = (dir_ / "b.png").string();
    writeImage(pngA, 16, 16, pixels);
    pixels[0] = 0.25f;
    writeImage(pngB, 16, 16, pixels);
    const std::string imageA = readAll(pngA), imageB = readAll(pngB);
    const std::string here = (dir_ / ".").string() + "/"; // `./x`: another name of x

    // The first case the stability suite lists (stability and benchmark are built where the
    // reference is).
    const bool withReference = fs::exists(program("stability"));
    const test::CommandResult list =
        withReference ? test::runCommand(program("stability") + " --list") : test::CommandResult{};
    ASSERT_TRUE(!withReference || list.status == 0) << list.output;
    const std::string stabilityCase = list.output.substr(0, list.output.find(' '));

    struct Case {
        std::string command, expected;
        fs::path kept; // an input that must stay as it was ("" when none is at stake)
        std::string keptBytes;
    };
    const std::string size = " --size 16x16";
    const Case cases[] = {
        // render: the scene file through `./`, a hard link to the glTF's buffer, two outputs.
        {program("render") + " " + box.string() + size + " --output " + here + "r1.png" +
             " --profile-json " + here + "box.json",
         "--profile-json " + here + "box.json is the same file as the scene file " + box.string(),
         box, original},
        {program("render") + " " + model + size + " --output " + here + "r2.png" +
             " --profile-trace " + (dir_ / "hard.json").string(),
         "is the same file as a file the scene reads", buffer, bin},
        {program("render") + " " + box.string() + size + " --output " + here + "r3.png" +
             " --profile-json " + (dir_ / "p.json").string() + " --profile-trace " + here +
             "p.json",
         "--profile-json " + (dir_ / "p.json").string() + " and --profile-trace " + here +
             "p.json are the same file",
         "", ""},
        // walkthrough: two outputs through a (dangling) link; a frame over the scene file.
        {program("walkthrough") + " " + box.string() + size + " --still --frames 1 --timings " +
             (dir_ / "t.json").string() + " --profile-trace " + (dir_ / "t-link.json").string(),
         "are the same file", "", ""},
        {program("walkthrough") + " " + box.string() + size + " --still --frames 2 --frames-dir " +
             (dir_ / "frames").string(),
         "frame_0001.png is the same file as the scene file", box, original},
        // reference: the display image over the scene file, through a link.
        {program("reference") + " " + box.string() +
             " --size 8x8 --spp 1 --no-cache --quiet --output " + (dir_ / "ref.exr").string() +
             " --png " + (dir_ / "scene-link.png").string(),
         "--png " + (dir_ / "scene-link.png").string() + " is the same file as the scene file", box,
         original},
        // compare: a map over the reference image; two maps in one file; JSON over A by a hard
        // link.
        {program("compare") + " " + pngA + " " + pngB + " --error-map " + here + "b.png",
         "--error-map " + here + "b.png is the same file as the reference image " + pngB, pngB,
         imageB},
        {program("compare") + " " + pngA + " " + pngB + " --error-map " +
             (dir_ / "m.png").string() + " --flip-map " + here + "m.png",
         "are the same file", "", ""},
        {program("compare") + " " + pngA + " " + pngB + " --json " +
             (dir_ / "a-hard.json").string(),
         "is the same file as the image to judge " + pngA, pngA, imageA},
        // stability: two of its fixed outputs made one by a link.
        {program("stability") + " " + stabilityCase + " --quick --no-plot --out " +
             (dir_ / "stability").string(),
         "are the same file", "", ""},
        // benchmark: its results over the scene file.
        {program("benchmark") + " sweep " + box.string() + size +
             " --no-error --no-series --frames 1 --warmup 0 --out " + here + "box.json",
         "--out " + here + "box.json is the same file as the scene file", box, original},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.command);
        if (!withReference && (c.command.rfind(program("stability"), 0) == 0 ||
                               c.command.rfind(program("benchmark"), 0) == 0))
            continue;
        // Each case on fresh files: a run that replaced an input must not spoil the next.
        for (const auto& entry : fs::directory_iterator(dir_))
            if (entry.path().filename() != "a.png" && entry.path().filename() != "b.png")
                fs::remove_all(entry.path());
        write("box.json", original);
        write("tri.gltf", gltf.dump());
        write("tri.bin", bin);
        fs::create_hard_link(buffer, dir_ / "hard.json");
        fs::create_hard_link(pngA, dir_ / "a-hard.json");
        fs::create_symlink("t.json", dir_ / "t-link.json");
        fs::create_symlink("box.json", dir_ / "scene-link.png");
        fs::create_directories(dir_ / "frames");
        fs::create_symlink("../box.json", dir_ / "frames" / "frame_0001.png");
        fs::create_directories(dir_ / "stability");
        fs::create_symlink("frames.csv", dir_ / "stability" / "stability.csv");

        const test::CommandResult run = test::runCommand(c.command);
        EXPECT_EQ(run.status, 2) << run.output;
        EXPECT_NE(run.output.find("error: "), std::string::npos) << run.output;
        EXPECT_NE(run.output.find(c.expected), std::string::npos) << run.output;
        EXPECT_EQ(run.output.find("wrote"), std::string::npos) << run.output;
        if (!c.kept.empty()) {
            EXPECT_EQ(readAll(c.kept), c.keptBytes) << c.kept;
        }
        // Nothing written: no output, no temporary.
        for (const char* name : {"r1.png", "r2.png", "r3.png", "p.json", "t.json", "ref.exr",
                                 "m.png", "frames/frame_0000.png", "stability/frames.csv"})
            EXPECT_FALSE(fs::exists(dir_ / name)) << name;
        EXPECT_EQ(hiddenFiles(dir_), "");
    }
    EXPECT_EQ(readAll(pngA), imageA);
}

// A process killed by a signal it cannot hold (SIGKILL) leaves its temporary behind; the next
// write into that folder removes it (no process of its PID lives), and leaves the temporaries of
// live processes alone (one was left for ever).
TEST_F(BadInput, AKilledRunsTemporaryIsRemovedByTheNextWrite) {
    const fs::path folder = dir_ / "out";
    fs::create_directories(folder);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        writeFileAtomically((folder / "big.bin").string(), std::string(size_t(256) << 20, 'x'));
        _exit(0);
    }
    const auto start = std::chrono::steady_clock::now();
    while (hiddenFiles(folder).empty() &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(20))
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the write finished before the signal; make it longer";
    const std::string left = hiddenFiles(folder);
    ASSERT_NE(left, "") << "SIGKILL leaves the temporary";
    // A live process's temporary (this one's parent's) and a file that only looks like one.
    const std::string live = ".ssgi-" + std::to_string(::getppid()) + "-0";
    write("out/" + live, "another run's, still being written");
    write("out/.ssgi-notes", "not a temporary");

    writeFileAtomically((folder / "next.txt").string(), "the next run");
    std::istringstream leftPaths(left);
    for (std::string path; leftPaths >> path;)
        EXPECT_FALSE(fs::exists(path)) << path << " was left by the killed run";
    EXPECT_TRUE(fs::exists(folder / live));
    EXPECT_TRUE(fs::exists(folder / ".ssgi-notes"));
    EXPECT_FALSE(fs::exists(folder / "big.bin"));
    EXPECT_EQ(readAll(folder / "next.txt"), "the next run");
}
