// The suites `echosim bench` knows; each lives in its own file.
#pragma once

#include <memory>

#include "bench/harness.hpp"

namespace echosim::bench {

std::shared_ptr<void> register_render(const SuiteOptions& options);
std::shared_ptr<void> register_fit(const SuiteOptions& options);
std::shared_ptr<void> register_physics(const SuiteOptions& options);
std::shared_ptr<void> register_reconstruct(const SuiteOptions& options);
std::shared_ptr<void> register_slice(const SuiteOptions& options);
std::shared_ptr<void> register_haptics(const SuiteOptions& options);
std::shared_ptr<void> register_arm(const SuiteOptions& options);
std::shared_ptr<void> register_exam(const SuiteOptions& options);
std::shared_ptr<void> register_bmode(const SuiteOptions& options);
std::shared_ptr<void> register_e2e(const SuiteOptions& options);
std::shared_ptr<void> register_ui(const SuiteOptions& options);

}  // namespace echosim::bench
