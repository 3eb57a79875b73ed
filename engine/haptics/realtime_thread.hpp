// What a real-time thread does for itself at its start, beside its priority (haptic_loop.cpp): its
// stack faulted in before the first deadline, its CPU fixed, and its own page faults counted, so
// that "no page fault after the start" is a measured figure, not a hope.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace echosim::haptics {

// The stack the loop may use, touched once at its thread's start [bytes]: far more than a tick
// needs (a few KiB), far less than a thread's stack (8 MiB by default).
inline constexpr std::size_t kPrefaultStackBytes = 256 * 1024;

// Writes one byte in every page of the next kPrefaultStackBytes of the calling thread's stack.
void prefault_stack();

// Reads one byte in every page of [data, data + bytes): what construction wrote is then mapped for
// this thread too (a no-op where it already is, which is the point: nothing is left to fault).
void prefault_read(const void* data, std::size_t bytes);

// The calling thread's page faults so far, minor and major (getrusage(RUSAGE_THREAD)); -1 where
// the kernel cannot say.
std::int64_t thread_page_faults();

// Fixes the calling thread on the last CPU this process may run on (on a 2-core machine the second:
// the first takes most of the interrupts). Returns the CPU, or -1 with `why` said: one CPU only (no
// choice to make; `why` stays empty), or the kernel's refusal.
int pin_to_last_cpu(std::string& why);

}  // namespace echosim::haptics
