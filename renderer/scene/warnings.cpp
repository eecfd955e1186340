#include "scene/warnings.h"

#include <atomic>
#include <iostream>

namespace ssgi {

namespace {
std::atomic<WarningSink> sink{nullptr};
}

void setWarningSink(WarningSink to) {
    sink = to;
}

void warn(const std::string& text) {
    if (const WarningSink to = sink.load()) {
        to(text);
        return;
    }
    std::cerr << "warning: " << text << "\n";
}

} // namespace ssgi
