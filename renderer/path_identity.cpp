// Two names of one file found by what each resolves to (checkRunFiles, atomic_file.h), and what
// a path names where a write goes through it (path_identity.h).
#include "path_identity.h"

#include "atomic_file.h"
#include "scene/scene.h"

#include <map>
#include <sys/stat.h>
#include <unistd.h>

namespace ssgi {

namespace fs = std::filesystem;

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

namespace {

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

} // namespace

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

} // namespace ssgi
