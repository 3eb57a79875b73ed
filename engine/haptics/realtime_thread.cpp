#include "haptics/realtime_thread.hpp"

#include <cerrno>
#include <cstring>

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

namespace echosim::haptics {

[[gnu::noinline]] void prefault_stack()
{
    unsigned char stack[kPrefaultStackBytes];
    const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
    for (std::size_t i = 0; i < sizeof stack; i += page) stack[i] = 0;
    // the writes must happen: the array is never read, and the compiler would drop them
    asm volatile("" : : "r"(stack) : "memory");
}

void prefault_read(const void* data, std::size_t bytes)
{
    const auto* p = static_cast<const volatile unsigned char*>(data);
    const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
    for (std::size_t i = 0; i < bytes; i += page) (void)p[i];
    if (bytes > 0) (void)p[bytes - 1];
}

std::int64_t thread_page_faults()
{
    rusage u{};
    if (getrusage(RUSAGE_THREAD, &u) != 0) return -1;
    return std::int64_t(u.ru_minflt) + std::int64_t(u.ru_majflt);
}

int pin_to_last_cpu(std::string& why)
{
    why.clear();
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (int e = pthread_getaffinity_np(pthread_self(), sizeof allowed, &allowed); e != 0) {
        why = std::string("its CPUs cannot be read: ") + std::strerror(e);
        return -1;
    }
    if (CPU_COUNT(&allowed) < 2) return -1;
    int last = -1;
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &allowed)) last = c;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(last, &one);
    if (int e = pthread_setaffinity_np(pthread_self(), sizeof one, &one); e != 0) {
        why = "not pinned to CPU " + std::to_string(last) + ": " + std::strerror(e);
        return -1;
    }
    return last;
}

}  // namespace echosim::haptics
