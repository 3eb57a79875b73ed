#include <algorithm>
#include <stdexcept>

#include "core/assets.hpp"
#include "core/printable_text.hpp"
#include "exam/scenario.hpp"

namespace echosim::exam {
namespace {

// The folder holding the shipped cases (assets/cases), beside their schema.
std::filesystem::path cases_folder()
{
    return asset_path("cases");
}

// SplitMix64's finaliser: consecutive seeds (1, 2, 3, ...) land on unrelated cases.
std::uint64_t mix(std::uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

}  // namespace

std::vector<std::filesystem::path> shipped_cases()
{
    std::vector<std::filesystem::path> out;
    for (const auto& entry : std::filesystem::directory_iterator(cases_folder())) {
        const std::filesystem::path& p = entry.path();
        // the schema sits beside the cases: *.schema.json is not a case
        if (entry.is_regular_file() && p.extension() == ".json" && p.stem().extension() != ".schema") out.push_back(p);
    }
    std::sort(out.begin(), out.end());  // the directory's order is the file system's: sorted, a seed draws the same case everywhere
    return out;
}

std::filesystem::path shipped_case(const std::string& id)
{
    const std::vector<std::filesystem::path> all = shipped_cases();
    std::string ids;
    for (const auto& p : all) {
        if (p.stem().string() == id) return p;
        ids += (ids.empty() ? "" : ", ") + p.stem().string();
    }
    throw std::runtime_error(printable("no shipped case '" + id + "' (the shipped cases: " + ids + ")"));
}

std::filesystem::path random_case(std::uint64_t seed)
{
    const std::vector<std::filesystem::path> all = shipped_cases();
    if (all.empty()) throw std::runtime_error("no shipped cases in " + cases_folder().string());
    // modulo a handful of cases, 2^64 mixed values share out evenly to within 1 part in 10^17
    return all[std::size_t(mix(seed) % all.size())];
}

}  // namespace echosim::exam
