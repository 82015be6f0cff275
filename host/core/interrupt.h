// SIGINT and SIGTERM during a render (docs/farm.md "Interruption"): the first signal only raises a
// flag, which the render loop reads between batches; it then writes its outputs and exits with
// 128 + the signal's number. A second signal exits at once (exit 128 + its number) after deleting
// the temporary files of the atomic writes in flight (core/atomic_file.h), so that neither a
// temporary nor a truncated output is left behind.
#pragma once

namespace vkp {

/// Installs the handlers for SIGINT and SIGTERM (idempotent). Before this, signals kill the
/// process as usual.
void installInterruptHandlers();

/// The number of the first SIGINT or SIGTERM received since installInterruptHandlers, or 0.
int interruptSignal();

/// "SIGINT", "SIGTERM", or "signal N" for another.
const char* signalName(int signo);

/// The conventional exit code of a process stopped by signal `signo`: 128 + signo (130 for
/// SIGINT, 143 for SIGTERM).
inline int exitCodeForSignal(int signo) { return 128 + signo; }

/// While alive, names a temporary file that a second signal deletes before the process exits.
/// At most 64 are registered at once (further ones are not deleted by a signal, only by their
/// owners as usual). Paths longer than 4095 bytes are not registered.
class TempFileGuard {
public:
    explicit TempFileGuard(const char* path);
    ~TempFileGuard();
    TempFileGuard(const TempFileGuard&) = delete;
    TempFileGuard& operator=(const TempFileGuard&) = delete;

private:
    int slot_ = -1;
};

/// Tests only: forget a received signal (the handlers stay installed).
void resetInterruptForTests();

}  // namespace vkp
