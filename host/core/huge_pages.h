// Transparent huge pages for the heap: vkpath re-executes itself once at start-up with glibc's
// tunable glibc.malloc.hugetlb=1, so that malloc asks the kernel for 2 MiB pages (madvise) for its
// large blocks. Start-up is mostly first touches of fresh memory: the scene's arrays, the BVH
// build, lavapipe's shader compiler. With 4 KiB pages each touch is a page fault, and page faults
// are expensive on virtual machines (measured: docs/performance.md "Huge pages").
// glibc reads tunables only when a process starts, hence the re-execution.
#pragma once
#include <optional>
#include <string>

namespace vkp {

/// The GLIBC_TUNABLES value to re-execute with, given the current one (nullptr: unset): the current
/// one with glibc.malloc.hugetlb=1 appended; nullopt when the current one already names
/// glibc.malloc.hugetlb (with any value: GLIBC_TUNABLES=glibc.malloc.hugetlb=0 opts out).
std::optional<std::string> tunablesWithHugePages(const char* current);

/// Whether this process runs with glibc.malloc.hugetlb=1 (GLIBC_TUNABLES names it last with 1).
bool hugePagesRequested();

/// Re-executes this program (/proc/self/exe, the same argv and environment plus the tunable) when
/// tunablesWithHugePages asks for it; returns (and the process goes on as it is) if it cannot.
/// Call first in main, before any thread or signal handler exists.
void reexecWithHugePages(char** argv);

}  // namespace vkp
