// Every allocation of a test binary that links counting_new.cpp is counted, so a test can assert
// that a hot path (a physics step, a haptic tick) makes none.
#pragma once

namespace echosim::test {
long allocations();  // operator new calls so far, all threads
}
