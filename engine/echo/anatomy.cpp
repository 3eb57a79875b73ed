#include "echo/anatomy.hpp"

#include <array>

namespace echosim::echo {
namespace {

constexpr std::array<const char*, kVeinSegmentCount> kSegmentNames = {"cfv", "gsv", "fv", "dfv", "popliteal"};
constexpr std::array<const char*, 2> kKindNames = {"acute", "chronic"};

}  // namespace

const char* segment_name(VeinSegment s)
{
    const auto i = std::size_t(s);
    return i < kSegmentNames.size() ? kSegmentNames[i] : "?";
}

bool parse_segment(const std::string& name, VeinSegment& out)
{
    for (std::size_t i = 0; i < kSegmentNames.size(); ++i)
        if (name == kSegmentNames[i]) {
            out = VeinSegment(i);
            return true;
        }
    return false;
}

const char* thrombus_kind_name(ThrombusKind k)
{
    const auto i = std::size_t(k);
    return i < kKindNames.size() ? kKindNames[i] : "?";
}

bool parse_thrombus_kind(const std::string& name, ThrombusKind& out)
{
    for (std::size_t i = 0; i < kKindNames.size(); ++i)
        if (name == kKindNames[i]) {
            out = ThrombusKind(i);
            return true;
        }
    return false;
}

}  // namespace echosim::echo
