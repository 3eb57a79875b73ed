// The echographic volume of an exam's case (issue 31 item 2): its anatomy (the fat, the thrombi
// per segment, the mimics) imaged and reconstructed over everywhere the probe can go, made on first
// use and cached under a digest of its anatomy, so an instructor's edited anatomy is made anew, and cases
// that differ only in their stations or bands share one volume.
#pragma once

#include <functional>
#include <string>

#include "app/volume_source.hpp"
#include "exam/scenario.hpp"
#include "gpu/context.hpp"

namespace echosim::app {

// `coarse`: 0.6 mm voxels from a sparser sweep (seconds to make; tests and benchmarks).
// Its sweep is imaged on the GPU `gpu` picks when there is one (app/bmode_imager.hpp).
VolumePair exam_volume(const exam::Scenario& scenario, bool coarse, const gpu::ContextOptions& gpu,
                       const std::function<void(const std::string& stage, double done)>& progress);

// Whether exam_volume would read the case's volume from the cache (not make it).
bool exam_volume_cached(const exam::Scenario& scenario, bool coarse);

// The digest of the anatomy's every number (FNV-1a 64 over their shortest round-trip text): the
// cache's key, the same on every machine.
std::string anatomy_digest(const echo::Anatomy& anatomy);

}  // namespace echosim::app
