// The library's warnings: "warning: <text>" on stderr, or wherever a host that wants them
// elsewhere sends them (the Python module makes them Python warnings, which a user can filter).
#pragma once

#include <string>

namespace ssgi {

using WarningSink = void (*)(const std::string& text);

// Where warn() sends its text from now on; nullptr: stderr again.
void setWarningSink(WarningSink sink);

// Says `text` (no "warning: " prefix, no newline) to the sink, else on stderr.
void warn(const std::string& text);

} // namespace ssgi
