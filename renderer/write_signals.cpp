// The signals around a write of files (write_signals.h): the clean-up handler, the slots of the
// paths it removes, and the signals held or ignored while files are written.
#include "write_signals.h"

#include <atomic>
#include <climits>
#include <cstring>
#include <mutex>
#include <pthread.h>
#include <unistd.h>

namespace ssgi::write_signals {

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

} // namespace

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

Pending::Pending(const std::string& path) {
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

Pending::~Pending() {
    if (slot_ >= 0) gPending[slot_].store(false);
}

QuietWriteSignals::QuietWriteSignals() {
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGXFSZ, &ignore, &oldXfsz_);
    ::sigaction(SIGPIPE, &ignore, &oldPipe_);
}

QuietWriteSignals::~QuietWriteSignals() {
    ::sigaction(SIGXFSZ, &oldXfsz_, nullptr);
    ::sigaction(SIGPIPE, &oldPipe_, nullptr);
}

HeldSignals::HeldSignals() {
    gDeferring.store(true);
    sigset_t hold;
    sigemptyset(&hold);
    for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT})
        sigaddset(&hold, signal);
    ::pthread_sigmask(SIG_BLOCK, &hold, &old_);
}

HeldSignals::~HeldSignals() {
    gDeferring.store(false);
    ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); // one sent to this thread arrives now
    if (const int signal = gDeferredSignal.exchange(0)) removePendingAndDie(signal);
}

} // namespace ssgi::write_signals
