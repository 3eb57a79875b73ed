// Replays fuzz inputs without libFuzzer: in the normal (GCC) builds every fuzz target is also linked
// with this main and run by CTest over its seed corpus and its regressions (tests/fuzz/corpus/T,
// tests/fuzz/regressions/T), so the Release and sanitizer suites check every input ever found.
//     fuzz_replay_T FOLDER_OR_FILE...
// Runs LLVMFuzzerTestOneInput on every file (folders recursively, in name order), printing each; a
// folder that does not exist is skipped (a target's regressions/ appears with its first finding), but
// no input at all fails.
// a crash, sanitizer report or escaping exception fails the test, as under libFuzzer.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv)
{
    std::vector<std::filesystem::path> inputs;
    for (int a = 1; a < argc; ++a) {
        const std::filesystem::path arg = argv[a];
        if (std::filesystem::is_directory(arg)) {
            for (const auto& entry : std::filesystem::recursive_directory_iterator(arg))
                if (entry.is_regular_file()) inputs.push_back(entry.path());
        } else if (std::filesystem::is_regular_file(arg)) {
            inputs.push_back(arg);
        } else if (!std::filesystem::exists(arg)) {
            std::printf("%s: none yet\n", arg.c_str());  // regressions/T appears with T's first finding
        } else {
            std::fprintf(stderr, "%s: not a file or folder\n", arg.c_str());
            return 2;
        }
    }
    std::sort(inputs.begin(), inputs.end());
    for (const auto& path : inputs) {
        std::printf("%s\n", path.c_str());
        std::fflush(stdout);
        std::ifstream in(path, std::ios::binary);
        const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
    }
    std::printf("%zu inputs replayed\n", inputs.size());
    return inputs.empty() ? 1 : 0;
}
