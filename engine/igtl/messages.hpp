// A live frame as the bytes that go on the wire (live_frame.hpp says what and in which frame):
// the IMAGE message, then the two TRANSFORM messages, each packed by the OpenIGTLink library
// (protocol 2 headers, CRC filled in), one after the other in one buffer that every client is sent.
#pragma once

#include <cstddef>
#include <vector>

#include "igtl/live_frame.hpp"

namespace echosim::igtl {

// Throws std::invalid_argument when the frame's pixels do not fill columns x rows, or a side is 0.
std::vector<std::byte> pack_frame(const LiveFrame& frame);

// Throws std::invalid_argument naming what is wrong with the frame (pack_frame's checks).
void check_frame(const LiveFrame& frame);

}  // namespace echosim::igtl
