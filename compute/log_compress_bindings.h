// Bindings of compute/log_compress.comp, shared with engine/echo/log_compress.cpp (the CPU
// reference) and engine/image/log_compress_gpu.cpp (the dispatcher), so all read one definition of
// the parameters.
#ifndef ECHOSIM_LOG_COMPRESS_BINDINGS_H
#define ECHOSIM_LOG_COMPRESS_BINDINGS_H

#include "kernel_shared.h"

#ifdef __cplusplus
namespace echosim::kernels {
#endif

#define LOG_COMPRESS_GROUP_SIZE 64
#define LOG_COMPRESS_ENVELOPE_BINDING 0  // float per pixel: echo envelope amplitude (linear, >= 0)
#define LOG_COMPRESS_IMAGE_BINDING 1     // uint per pixel: RGBA8 grey, alpha 255

struct LogCompressParams {
    uint pixel_count;
    float reference;         // envelope amplitude shown at 0 dB (full white before gain)
    float gain_db;           // overall gain [dB]
    float dynamic_range_db;  // dB below the reference that map to black
};

// The display's grey level for an echo `db` [dB] relative to full white (gain included): the
// `dynamic_range_db` below it map linearly onto 0..255, as a scanner's log compression does; from
// the level 0..1 that dB makes.
KERNEL_FN uint grey_of_level(float level) { return uint(clamp(level, 0.0f, 1.0f) * 255.0f + 0.5f); }
KERNEL_FN uint display_grey(float db, float dynamic_range_db) { return grey_of_level((db + dynamic_range_db) / dynamic_range_db); }

#ifdef __cplusplus
}  // namespace echosim::kernels
#endif
#endif
