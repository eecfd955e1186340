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
