#include "atomic_file.h"

#include "scene/scene.h"

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <pthread.h>
#include <set>
#include <sys/stat.h>
#include <unistd.h>

namespace ssgi {

namespace fs = std::filesystem;

namespace {

// Temporaries and backups that exist right now, so that a signal can remove them before the
// process dies. Fixed slots: the handler may not allocate or lock.
constexpr int kSlots = 64;
char gPendingPaths[kSlots][PATH_MAX];
std::atomic<bool> gPending[kSlots];
std::mutex gSlotsMutex;

// While files move into place a signal is only noted (any thread may receive it: lavapipe's
// threads do not block it), and the process dies of it once every file has moved.
std::atomic<bool> gDeferring{false};
std::atomic<int> gDeferredSignal{0};

extern "C" void removePendingAndDie(int signal);

void installCleanup(int signal) {
    struct sigaction cleanup {};
    cleanup.sa_handler = removePendingAndDie;
    cleanup.sa_flags = SA_RESETHAND | SA_NODEFER;
    sigemptyset(&cleanup.sa_mask);
    ::sigaction(signal, &cleanup, nullptr);
}

extern "C" void removePendingAndDie(int signal) {
    if (gDeferring.load()) {
        gDeferredSignal.store(signal);
        installCleanup(signal); // SA_RESETHAND removed it; a second signal is deferred too
        return;
    }
    for (int i = 0; i < kSlots; ++i)
        if (gPending[i].load()) ::unlink(gPendingPaths[i]);
    // SA_RESETHAND restored the default action and SA_NODEFER lets it happen now.
    ::raise(signal);
}

// Signals that end a process by default get the clean-up first; a program's own handlers stay.
void installSignalCleanup() {
    static std::once_flag once;
    std::call_once(once, [] {
        for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
            struct sigaction current {};
            if (::sigaction(signal, nullptr, &current) != 0 || current.sa_handler != SIG_DFL)
                continue;
            installCleanup(signal);
        }
    });
}

// A path a signal removes while it is registered.
class Pending {
public:
    explicit Pending(const std::string& path) {
        if (path.size() >= PATH_MAX) return;
        std::lock_guard lock(gSlotsMutex);
        for (int i = 0; i < kSlots; ++i)
            if (!gPending[i].load()) {
                std::memcpy(gPendingPaths[i], path.c_str(), path.size() + 1);
                gPending[i].store(true);
                slot_ = i;
                return;
            }
    }
    ~Pending() {
        if (slot_ >= 0) gPending[slot_].store(false);
    }
    Pending(const Pending&) = delete;
    Pending& operator=(const Pending&) = delete;

private:
    int slot_ = -1;
};

// A write past a file-size limit or into a closed pipe fails with an error instead of a signal
// while it lasts.
class QuietWriteSignals {
public:
    QuietWriteSignals() {
        struct sigaction ignore {};
        ignore.sa_handler = SIG_IGN;
        sigemptyset(&ignore.sa_mask);
        ::sigaction(SIGXFSZ, &ignore, &oldXfsz_);
        ::sigaction(SIGPIPE, &ignore, &oldPipe_);
    }
    ~QuietWriteSignals() {
        ::sigaction(SIGXFSZ, &oldXfsz_, nullptr);
        ::sigaction(SIGPIPE, &oldPipe_, nullptr);
    }

private:
    struct sigaction oldXfsz_ {
    }, oldPipe_{};
};

// Holds SIGINT, SIGTERM, SIGHUP and SIGQUIT while it lasts: blocked in this thread, noted by
// the clean-up handler in any other; one that arrived ends the process when it ends.
class HeldSignals {
public:
    HeldSignals() {
        gDeferring.store(true);
        sigset_t hold;
        sigemptyset(&hold);
        for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT})
            sigaddset(&hold, signal);
        ::pthread_sigmask(SIG_BLOCK, &hold, &old_);
    }
    ~HeldSignals() {
        gDeferring.store(false);
        ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); // one sent to this thread arrives now
        if (const int signal = gDeferredSignal.exchange(0)) removePendingAndDie(signal);
    }
    HeldSignals(const HeldSignals&) = delete;
    HeldSignals& operator=(const HeldSignals&) = delete;

private:
    sigset_t old_{};
};

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

// The descriptor a path names when it is one of this process's own (/dev/stdout, /dev/stderr,
// /dev/fd/N, /proc/self/fd/N, or a link to one of them), else -1. Such a path is written to as
// a stream at the descriptor's position: opened again, a file behind it would be replaced whole
// or written over from its start, and what the process wrote there before would be lost.
int ownDescriptor(const std::string& path) {
    fs::path at(path);
    for (int hops = 0; hops < 40; ++hops) {
        const std::string text = at.lexically_normal().string();
        if (text == "/dev/stdin") return 0;
        if (text == "/dev/stdout") return 1;
        if (text == "/dev/stderr") return 2;
        for (const std::string& prefix : std::initializer_list<std::string>{
                 "/dev/fd/", "/proc/self/fd/", "/proc/" + std::to_string(getpid()) + "/fd/"})
            if (text.rfind(prefix, 0) == 0) {
                const std::string number = text.substr(prefix.size());
                if (!number.empty() && number.size() < 9 &&
                    number.find_first_not_of("0123456789") == std::string::npos)
                    return std::stoi(number);
            }
        struct stat link {};
        if (::lstat(at.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) return -1;
        std::error_code ec;
        const fs::path target = fs::read_symlink(at, ec);
        if (ec) return -1;
        at = target.is_absolute() ? target : at.parent_path() / target;
    }
    return -1;
}

// Where a path that names no file leads: the end of its chain of symbolic links (the file a
// write creates), or the path itself.
fs::path throughDanglingLinks(fs::path at) {
    for (int hops = 0; hops < 40; ++hops) {
        struct stat link {};
        if (::lstat(at.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) break;
        std::error_code ec;
        const fs::path target = fs::read_symlink(at, ec);
        if (ec) break;
        at = target.is_absolute() ? target : at.parent_path() / target;
    }
    return at;
}

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

// What a path resolves to, to find two names of one file: its absolute path with every link
// and `.`/`..` resolved, and the file's identity where it exists. Not `compared` where a write
// would not replace it (this process's descriptors, a device, a FIFO, a folder).
struct Identity {
    bool compared = false;
    std::string path;
    dev_t device = 0;
    ino_t inode = 0; // 0: no file there yet
};

class Identities {
public:
    Identity of(const std::string& path) {
        Identity id;
        if (path.empty() || path.find('\0') != std::string::npos || ownDescriptor(path) >= 0)
            return id;
        fs::path at(path);
        struct stat status {};
        if (::stat(path.c_str(), &status) == 0) {
            if (!S_ISREG(status.st_mode)) return id;
            id.device = status.st_dev;
            id.inode = status.st_ino;
        } else {
            at = throughDanglingLinks(at);
        }
        // The folder resolved once (a walkthrough's frames share one), then the name in it,
        // itself resolved only where it is a link. (Not lexically first: `link/..` is the
        // parent of the link's target.)
        struct stat link {};
        const bool isLink = ::lstat(at.c_str(), &link) == 0 && S_ISLNK(link.st_mode);
        std::error_code ec;
        fs::path absolute = fs::absolute(at, ec);
        if (ec) absolute = at;
        const fs::path name = absolute.filename();
        if (isLink || name.empty() || name == "." || name == "..") {
            const fs::path canonical = fs::weakly_canonical(absolute, ec);
            id.path = (ec ? absolute.lexically_normal() : canonical).string();
        } else {
            const fs::path parent = absolute.parent_path();
            auto found = folders_.find(parent.string());
            if (found == folders_.end()) {
                const fs::path canonical = fs::weakly_canonical(parent, ec);
                found =
                    folders_.emplace(parent.string(), ec ? parent.lexically_normal() : canonical)
                        .first;
            }
            id.path = (found->second / name).string();
        }
        id.compared = true;
        return id;
    }

private:
    std::map<std::string, fs::path> folders_;
};

// Finds, among identities added one by one, an earlier one of the same file.
class SameFiles {
public:
    // The index of an earlier identity of the same file, or -1; then remembers this one.
    long add(const Identity& id, long index) {
        if (!id.compared) return -1;
        long earlier = -1;
        if (id.inode != 0)
            if (const auto it = inodes_.find({id.device, id.inode}); it != inodes_.end())
                earlier = it->second;
        if (earlier < 0)
            if (const auto it = paths_.find(id.path); it != paths_.end()) earlier = it->second;
        if (id.inode != 0) inodes_.emplace(std::pair{id.device, id.inode}, index);
        paths_.emplace(id.path, index);
        return earlier;
    }

private:
    std::map<std::pair<dev_t, ino_t>, long> inodes_;
    std::map<std::string, long> paths_;
};

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
    installSignalCleanup();
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

void checkRunFiles(const std::vector<RunFile>& inputs, const std::vector<RunFile>& outputs) {
    const auto named = [](const RunFile& file) {
        return file.what.empty() ? file.path : file.what + " " + file.path;
    };
    Identities identities;
    SameFiles seen; // indices: the inputs, then the outputs
    for (size_t i = 0; i < inputs.size(); ++i)
        seen.add(identities.of(inputs[i].path), long(i)); // an input named twice is read twice
    for (size_t i = 0; i < outputs.size(); ++i) {
        const long earlier = seen.add(identities.of(outputs[i].path), long(inputs.size() + i));
        if (earlier < 0) continue;
        if (size_t(earlier) < inputs.size())
            throw InputError(named(outputs[i]) + " is the same file as " +
                             named(inputs[size_t(earlier)]) +
                             ": writing it would destroy an input of the run; nothing was written");
        throw InputError(named(outputs[size_t(earlier) - inputs.size()]) + " and " +
                         named(outputs[i]) +
                         " are the same file: both outputs cannot be written; nothing was written");
    }
}

void setAfterRenameHook(void (*hook)(size_t moved)) {
    gAfterRename = hook;
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
    writeFilesAtomically({{path, bytes}});
}

} // namespace ssgi
