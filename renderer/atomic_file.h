// Every file a program writes goes through here: written whole or not at all. The bytes go to a
// short temporary name beside the target (so a target name near the 255-byte limit still works),
// are flushed to the disk and checked, and only then is the temporary renamed over the target.
// A full disk, a write error or a signal leaves the target as it was and no temporary behind.
#pragma once

#include <string>
#include <vector>

namespace ssgi {

struct FileBytes {
    std::string path;
    std::string bytes;
    // Replace whatever is at the path (a link, a FIFO) with a regular file instead of writing
    // through it: for files only this program reads back, such as a cache's entries.
    bool replace = false;
};

// Writes every file, all of them or none (what was at their paths before stays). A path that is
// a symbolic link is written through: a link to a regular file has the file it points at
// replaced, a link to something else (/dev/stdout, a pipe, a terminal) is written to directly,
// as is such a file named itself. Throws InputError naming the target path and the system's
// reason; never leaves a temporary.
void writeFilesAtomically(const std::vector<FileBytes>& files);
void writeFileAtomically(const std::string& path, const std::string& bytes);

} // namespace ssgi
