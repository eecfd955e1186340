// What a path names (atomic_file.cpp, checkRunFiles): one of this process's own descriptors
// behind /dev/stdout and the like, which a write goes to as a stream, and the file at the end of
// a dangling link's chain, which a write creates. path_identity.cpp also holds checkRunFiles
// (atomic_file.h), which finds two names of one file by what each resolves to.
#pragma once

#include <filesystem>
#include <string>

namespace ssgi {

// The descriptor a path names when it is one of this process's own (/dev/stdout, /dev/stderr,
// /dev/fd/N, /proc/self/fd/N, or a link to one of them), else -1. Such a path is written to as
// a stream at the descriptor's position: opened again, a file behind it would be replaced whole
// or written over from its start, and what the process wrote there before would be lost.
int ownDescriptor(const std::string& path);

// Where a path that names no file leads: the end of its chain of symbolic links (the file a
// write creates), or the path itself.
std::filesystem::path throughDanglingLinks(std::filesystem::path at);

} // namespace ssgi
