#include <set>
#include <string>

#include <gtest/gtest.h>

#include "exam/exam_report.hpp"

namespace echosim::exam {

// report.json and the records store errors and calls by these names: each must be its own, and
// written as the files write them (lower case, words joined by '-').
TEST(ExamReport, ErrorAndCallNamesAreDistinctKebabCase)
{
    std::set<std::string> seen;
    for (ErrorKind e : {ErrorKind::skipped_station, ErrorKind::too_little_pressure, ErrorKind::wrong_vessel, ErrorKind::oblique_plane,
                        ErrorKind::excessive_force, ErrorKind::mimic_called_clot, ErrorKind::wrong_call}) {
        const std::string name = error_name(e);
        EXPECT_TRUE(seen.insert(name).second) << name;
        EXPECT_EQ(name.find_first_not_of("abcdefghijklmnopqrstuvwxyz-"), std::string::npos) << name;
    }
    EXPECT_EQ(std::string(call_name(Call::not_compressible)), "not-compressible");
    EXPECT_EQ(std::string(call_name(Call::compressible)), "compressible");
    EXPECT_EQ(std::string(call_name(Call::none)), "none");
}

}  // namespace echosim::exam
