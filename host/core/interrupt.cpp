#include "core/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>

namespace vkp {

namespace {
std::atomic<int> g_signal{0};
std::atomic<bool> g_installed{false};

/// A slot of the registry: 0 free, 1 being filled or emptied, 2 holds a path to delete.
struct Slot {
    std::atomic<int> state{0};
    char path[4096];
};
constexpr int kSlots = 64;
Slot g_slots[kSlots];

void writeStderr(const char* s) {
    ssize_t n = ::write(2, s, std::strlen(s));
    (void)n;
}

/// Async-signal-safe: atomics, write, unlink and _exit only.
void onSignal(int signo) {
    int expected = 0;
    if (g_signal.compare_exchange_strong(expected, signo)) {
        writeStderr(signo == SIGINT ? "\nvkpath: SIGINT: finishing the batch in flight, then writing the outputs (again to stop at once)\n"
                                    : "\nvkpath: SIGTERM: finishing the batch in flight, then writing the outputs (again to stop at once)\n");
        return;
    }
    for (Slot& s : g_slots)
        if (s.state.load() == 2) ::unlink(s.path);
    writeStderr("vkpath: stopped at once: no output written\n");
    ::_exit(128 + signo);
}
}  // namespace

void installInterruptHandlers() {
    if (g_installed.exchange(true)) return;
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // reads and writes in flight continue; the loop checks the flag
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

int interruptSignal() { return g_signal.load(); }

const char* signalName(int signo) {
    if (signo == SIGINT) return "SIGINT";
    if (signo == SIGTERM) return "SIGTERM";
    static thread_local char other[32];
    std::snprintf(other, sizeof other, "signal %d", signo);
    return other;
}

void resetInterruptForTests() { g_signal.store(0); }

TempFileGuard::TempFileGuard(const char* path) {
    const std::size_t n = std::strlen(path);
    if (n >= sizeof(Slot::path)) return;
    for (int i = 0; i < kSlots; ++i) {
        int expected = 0;
        if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
        std::memcpy(g_slots[i].path, path, n + 1);
        g_slots[i].state.store(2);
        slot_ = i;
        return;
    }
}

TempFileGuard::~TempFileGuard() {
    if (slot_ >= 0) g_slots[slot_].state.store(0);
}

}  // namespace vkp
