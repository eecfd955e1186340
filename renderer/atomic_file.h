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

// Writes every file, all of them or none (what was at their paths before stays). Every path is
// checked first: an empty path or one holding a NUL, a regular file without write permission
// (not replaced), and two outputs that are one file (a link from one to the other) are
// refused. A path that is a symbolic link is written through: a link to a regular file has the
// file it points at replaced, a link to something else (a pipe, a terminal, a device) is
// written to directly, as is such a file named itself; a FIFO that no process reads is refused
// instead of waited on. A path naming one of this process's descriptors (/dev/stdout,
// /dev/stderr, /dev/fd/N, /proc/self/fd/N, or a link to one) is written to that descriptor as a
// stream, after what the program printed, and never replaced, whatever is behind it. The
// signals that end a process (SIGINT, SIGTERM, SIGHUP, SIGQUIT) are held while the files move
// into place, so none leaves some moved and some not. Throws InputError naming the target path
// and the system's reason; never leaves a temporary. Temporaries are named `.ssgi-PID-N` (and
// backups `.ssgi-old-PID-N`): one that a killed process (SIGKILL, a crash) left in a folder is
// removed by the next write into that folder once no process of that PID is alive.
void writeFilesAtomically(const std::vector<FileBytes>& files);
void writeFileAtomically(const std::string& path, const std::string& bytes);

// A file a run reads or writes, named in messages by what it is for ("--output", "the scene
// file").
struct RunFile {
    std::string what;
    std::string path;
};

// The one check of a run's files against each other, made before any work: an output that is
// one of the run's inputs (writing it would destroy the input) or two outputs that are one file
// (the second would replace the first) are refused with InputError naming both. Files are
// compared by what they resolve to: `./x` and `x`, a symbolic link (dangling or not) and its
// target, two hard links of one file. A path that is not replaced when written (this process's
// own descriptors such as /dev/stdout, a device, a FIFO, a folder) is not compared.
// writeFilesAtomically makes the same check among the files of one write.
void checkRunFiles(const std::vector<RunFile>& inputs, const std::vector<RunFile>& outputs);

// For the tests: called after each file has moved into place, with how many have, so that a
// test can send a signal between two renames.
void setAfterRenameHook(void (*hook)(size_t moved));

} // namespace ssgi
