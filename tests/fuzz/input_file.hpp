// The one piece every fuzz target shares: libFuzzer hands a target bytes, our readers take a path.
// input_file() writes the bytes to a file of the given name in a private folder (made once per
// process, on /dev/shm when there is one, removed at exit) and returns its path. The name's extension
// matters to readers that go by it (.seq.nrrd, .mha) and keeps messages readable.
//
// refusing<Errors...>(read) runs read() and swallows the exceptions its reader documents (the format's
// own error types): a refusal naming the file and field is what bad input should get. Anything else
// escaping LLVMFuzzerTestOneInput (another exception, a crash, a sanitizer report, a hang, an
// allocation over libFuzzer's -malloc_limit_mb) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace echosim::fuzz {

std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, std::string_view name);

template <class Read>
void refusing(Read&& read)
{
    read();
}
template <class Error, class... Errors, class Read>
void refusing(Read&& read)
{
    try {
        refusing<Errors...>(read);
    } catch (const Error&) {
    }
}

// A modest budget for the readers that take one [bytes]: inputs are a few KB, so any size above this
// is a header's claim, refused by the budget check. Targets that keep the default budget (8 GiB) are
// the ones that find what a claim costs before the budget stops it.
inline constexpr std::uint64_t fuzz_memory_budget = std::uint64_t(64) << 20;

}  // namespace echosim::fuzz
