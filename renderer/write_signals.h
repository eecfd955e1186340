// The signals around a write of files (atomic_file.cpp): the temporaries and backups that a
// signal ending the process removes first (Pending), writes that fail with an error instead of
// raising SIGPIPE or SIGXFSZ (QuietWriteSignals), and the signals that end a process held while
// the files move into place (HeldSignals).
#pragma once

#include <csignal>
#include <string>

namespace ssgi::write_signals {

// Signals that end a process by default get the clean-up first; a program's own handlers stay.
// Once per process; before the first Pending.
void installSignalCleanup();

// A path a signal removes while it is registered.
class Pending {
public:
    explicit Pending(const std::string& path);
    ~Pending();
    Pending(const Pending&) = delete;
    Pending& operator=(const Pending&) = delete;

private:
    int slot_ = -1;
};

// A write past a file-size limit or into a closed pipe fails with an error instead of a signal
// while it lasts.
class QuietWriteSignals {
public:
    QuietWriteSignals();
    ~QuietWriteSignals();
    QuietWriteSignals(const QuietWriteSignals&) = delete;
    QuietWriteSignals& operator=(const QuietWriteSignals&) = delete;

private:
    struct sigaction oldXfsz_ {
    }, oldPipe_{};
};

// Holds SIGINT, SIGTERM, SIGHUP and SIGQUIT while it lasts: blocked in this thread, noted by
// the clean-up handler in any other; one that arrived ends the process when it ends.
class HeldSignals {
public:
    HeldSignals();
    ~HeldSignals();
    HeldSignals(const HeldSignals&) = delete;
    HeldSignals& operator=(const HeldSignals&) = delete;

private:
    sigset_t old_{};
};

} // namespace ssgi::write_signals
