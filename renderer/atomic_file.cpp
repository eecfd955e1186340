// Writing files whole or not at all (atomic_file.h): each to a temporary beside its target,
// then renamed over it; with the signals around it (write_signals.cpp) and the check that no
// output is an input or another output (path_identity.cpp).
#include "atomic_file.h"

#include "path_identity.h"
#include "scene/scene.h"
#include "write_signals.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <sys/stat.h>
#include <unistd.h>

namespace ssgi {

namespace fs = std::filesystem;

namespace {

using write_signals::HeldSignals;
using write_signals::Pending;
using write_signals::QuietWriteSignals;

void (*gAfterRename)(size_t) = nullptr;

std::string reason(int error) {
    return std::strerror(error);
}

// Writes all the bytes to fd; the errno of the failure, or 0.
int writeAll(int fd, const std::string& bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return n < 0 ? errno : ENOSPC;
        done += size_t(n);
    }
    return 0;
}

// Where the bytes end up: the path itself, or what a chain of symbolic links leads to.
struct Destination {
    fs::path path;
    bool direct = false; // not a regular file (a device, a pipe): written to as it is
    bool exists = false; // a regular file is there
    mode_t mode = 0;     // its permissions, kept
    int stream = -1;     // a descriptor of this process the path names (/dev/stdout): written to
    dev_t device = 0;    // the file's identity, to find two outputs that are one file
    ino_t inode = 0;
};

Destination resolve(const std::string& path, bool writeThrough) {
    Destination d{fs::path(path)};
    // One check for every path any program writes: a NUL cuts a path short (the file at the cut
    // name would be replaced), and a name must be there.
    if (path.empty()) throw InputError("an output path is empty");
    if (path.find('\0') != std::string::npos)
        throw InputError("output path '" + path.substr(0, path.find('\0')) +
                         "\\0...' holds a NUL character: it names no file");
    if (!writeThrough) return d;
    if ((d.stream = ownDescriptor(path)) >= 0) {
        d.direct = true;
        return d;
    }
    struct stat status {};
    if (::stat(path.c_str(), &status) == 0) {
        d.device = status.st_dev;
        d.inode = status.st_ino;
        if (S_ISREG(status.st_mode)) {
            // A file nobody may write is not replaced (renaming over it would work in a
            // writable folder, and its owner's protection would be lost without a word).
            if ((status.st_mode & 0222) == 0 || ::access(path.c_str(), W_OK) != 0)
                throw InputError(path + ": the file is read-only; it is not replaced");
            // The file itself, wherever links lead (realpath also reads /proc's fd links).
            if (char* real = ::realpath(path.c_str(), nullptr)) {
                d.path = real;
                std::free(real);
            }
            d.exists = true;
            d.mode = status.st_mode & 07777;
        } else if (!S_ISDIR(status.st_mode)) {
            d.direct = true; // a device, a pipe, a terminal, a socket
        }
        return d;
    }
    // A dangling link: the file it names is created, the link stays.
    d.path = throughDanglingLinks(d.path);
    return d;
}

// The PID in a temporary's or backup's name (`.ssgi-PID-N`, `.ssgi-old-PID-N`), or 0.
pid_t temporaryOwner(const std::string& name) {
    std::string rest;
    if (name.rfind(".ssgi-old-", 0) == 0)
        rest = name.substr(10);
    else if (name.rfind(".ssgi-", 0) == 0)
        rest = name.substr(6);
    else
        return 0;
    const size_t dash = rest.find('-');
    const auto digits = [](const std::string& text) {
        return !text.empty() && text.size() < 10 &&
               text.find_first_not_of("0123456789") == std::string::npos;
    };
    if (dash == std::string::npos || !digits(rest.substr(0, dash)) ||
        !digits(rest.substr(dash + 1)))
        return 0;
    return pid_t(std::stol(rest.substr(0, dash)));
}

// What a process that died without its clean-up (SIGKILL, a crash, a power cut) left in a
// folder: its temporaries and backups, removed by the first write of a later process into the
// folder once no process of their PID is alive. (A temporary of a live process, this one's
// included, is never touched.)
void removeStaleTemporaries(const fs::path& folder) {
    static std::mutex mutex;
    static std::set<std::string> cleaned;
    const std::string at = folder.empty() ? "." : folder.string();
    {
        std::lock_guard lock(mutex);
        if (!cleaned.insert(at).second) return;
    }
    DIR* dir = ::opendir(at.c_str());
    if (!dir) return;
    while (const dirent* entry = ::readdir(dir)) {
        const pid_t owner = temporaryOwner(entry->d_name);
        if (owner <= 0 || owner == ::getpid()) continue;
        if (::kill(owner, 0) == 0 || errno != ESRCH) continue; // alive (or not ours to judge)
        struct stat status {};
        if (::fstatat(::dirfd(dir), entry->d_name, &status, AT_SYMLINK_NOFOLLOW) == 0 &&
            S_ISREG(status.st_mode))
            ::unlinkat(::dirfd(dir), entry->d_name, 0);
    }
    ::closedir(dir);
}

fs::path uniqueBeside(const fs::path& target, const char* kind) {
    static std::atomic<unsigned> counter{0};
    return target.parent_path() / (std::string(".ssgi-") + kind + std::to_string(getpid()) + "-" +
                                   std::to_string(counter++));
}

void writeDirect(const std::string& path, const Destination& d, const std::string& bytes) {
    if (d.stream >= 0) {      // this process's own descriptor, at its position
        std::fflush(nullptr); // what the program printed before comes first
        if (::fcntl(d.stream, F_GETFL) < 0)
            throw InputError(path + ": cannot write: descriptor " + std::to_string(d.stream) +
                             " is not open");
        if (const int error = writeAll(d.stream, bytes))
            throw InputError(path + ": writing failed: " + reason(error));
        return;
    }
    // Non-blocking: a FIFO that no process reads would block the open forever.
    const int fd = ::open(d.path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
    if (fd < 0 && errno == ENXIO)
        throw InputError(path + ": a FIFO (named pipe) that no process is reading; nothing "
                                "written");
    if (fd < 0) throw InputError(path + ": cannot open for writing: " + reason(errno));
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    const int error = writeAll(fd, bytes);
    if (::close(fd) != 0 && error == 0 && errno != EINTR)
        throw InputError(path + ": writing failed: " + reason(errno));
    if (error != 0) throw InputError(path + ": writing failed: " + reason(error));
}

} // namespace

void writeFilesAtomically(const std::vector<FileBytes>& files) {
    write_signals::installSignalCleanup();
    const QuietWriteSignals quiet;
    std::vector<Destination> destinations;
    for (const FileBytes& file : files)
        destinations.push_back(resolve(file.path, !file.replace));
    // Two outputs that are one file (a.png a link to a.exr) would leave one of them.
    std::vector<RunFile> outputs;
    for (const FileBytes& file : files)
        outputs.push_back({"", file.path});
    checkRunFiles({}, outputs);

    // Every temporary complete and on the disk before anything moves.
    std::vector<fs::path> temporaries(files.size());
    std::vector<std::unique_ptr<Pending>> pending;
    auto removeTemporaries = [&] {
        for (const fs::path& tmp : temporaries)
            if (!tmp.empty()) ::unlink(tmp.c_str());
    };
    for (size_t i = 0; i < files.size(); ++i) {
        const Destination& d = destinations[i];
        const std::string& path = files[i].path;
        if (d.direct) continue;
        const fs::path parent = d.path.parent_path();
        std::error_code ec;
        if (!parent.empty() && !fs::is_directory(parent, ec)) {
            fs::create_directories(parent, ec);
            if (ec) {
                removeTemporaries();
                throw InputError(path + ": cannot create folder " + parent.string() + ": " +
                                 ec.message());
            }
        }
        removeStaleTemporaries(parent);
        const fs::path tmp = uniqueBeside(d.path, "");
        pending.push_back(std::make_unique<Pending>(tmp.string()));
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            const int error = errno;
            removeTemporaries();
            throw InputError(path + ": cannot create a file in " +
                             (parent.empty() ? std::string(".") : parent.string()) + ": " +
                             reason(error));
        }
        temporaries[i] = tmp;
        if (d.exists) ::fchmod(fd, d.mode);
        int error = writeAll(fd, files[i].bytes);
        if (error == 0 && ::fsync(fd) != 0) error = errno;
        if (::close(fd) != 0 && error == 0 && errno != EINTR) error = errno;
        if (error != 0) {
            removeTemporaries();
            throw InputError(path + ": writing failed: " + reason(error) + " (nothing written)");
        }
    }
    try {
        for (size_t i = 0; i < files.size(); ++i)
            if (destinations[i].direct) writeDirect(files[i].path, destinations[i], files[i].bytes);
    } catch (...) {
        removeTemporaries();
        throw;
    }

    // Move them into place. A file already at a target is kept under a second name (a hard
    // link) until all have moved, so a failure puts back what was there. The signals that end
    // a process wait until every file has moved: one arriving between two renames would leave
    // a new PNG beside an old EXR.
    const HeldSignals held;
    std::vector<fs::path> backups(files.size());
    for (size_t i = 0; i < files.size(); ++i) {
        const Destination& d = destinations[i];
        if (d.direct) continue;
        if (d.exists) {
            const fs::path backup = uniqueBeside(d.path, "old-");
            pending.push_back(std::make_unique<Pending>(backup.string()));
            if (::link(d.path.c_str(), backup.c_str()) == 0) backups[i] = backup;
        }
        if (::rename(temporaries[i].c_str(), d.path.c_str()) != 0) {
            const int error = errno;
            for (size_t j = 0; j < i; ++j) // undo the ones already moved
                if (destinations[j].direct)
                    continue;
                else if (!backups[j].empty())
                    ::rename(backups[j].c_str(), destinations[j].path.c_str());
                else
                    ::unlink(destinations[j].path.c_str());
            if (!backups[i].empty()) ::unlink(backups[i].c_str());
            removeTemporaries();
            std::string others;
            for (size_t j = 0; j < files.size(); ++j)
                if (j != i && !destinations[j].direct)
                    others += (others.empty() ? "" : ", ") + files[j].path;
            throw InputError(files[i].path +
                             ": cannot move the finished file into place: " + reason(error) +
                             (others.empty() ? "" : " (so " + others + " was not written either)"));
        }
        temporaries[i].clear();
        if (gAfterRename) gAfterRename(i + 1);
    }
    for (const fs::path& backup : backups)
        if (!backup.empty()) ::unlink(backup.c_str());
}

void setAfterRenameHook(void (*hook)(size_t moved)) {
    gAfterRename = hook;
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
    writeFilesAtomically({{path, bytes}});
}

} // namespace ssgi
