#include "fit/measurements.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "test_files.hpp"

namespace echosim::fit {
namespace {

std::filesystem::path temp(const char* name)
{
    return std::filesystem::temp_directory_path() / (std::string("echosim_meas_") + std::to_string(::getpid()) + name);
}

const char* kHeader = "point,probe,x_mm,y_mm,z_mm,nx,ny,nz,depth_mm,force_N\n";
const char* kGoodRow = "3,indenter,-40.0,-50.0,-90.0,0.6,-0.8,0.0,2.0,0.45\n";

// The error message for a file with this content, or "no error".
std::string error_for(const std::string& content)
{
    const auto path = temp("bad.csv");
    std::ofstream(path) << content;
    try {
        read_measurements(path);
    } catch (const MeasurementError& e) {
        std::filesystem::remove(path);
        return e.what();
    }
    std::filesystem::remove(path);
    return "no error";
}

TEST(Measurements, ReadsWhatItWrites)
{
    MeasurementSet set;
    set.comments = {" a comment"};
    set.samples.push_back({0, ProbeKind::indenter, {1, 2, 3}, {0, -1, 0}, 2.0, 0.5});
    set.samples.push_back({1, ProbeKind::probe, {4, 5, 6}, {0.6, -0.8, 0}, 4.0, 3.25});
    const auto path = temp("ok.csv");
    write_measurements(path, set);
    const MeasurementSet back = read_measurements(path);
    ASSERT_EQ(back.samples.size(), 2u);
    EXPECT_EQ(back.samples[1].probe, ProbeKind::probe);
    EXPECT_DOUBLE_EQ(back.samples[1].force_N, 3.25);
    EXPECT_DOUBLE_EQ(back.samples[0].position.z, 3.0);
    EXPECT_EQ(back.comments, set.comments);
    EXPECT_EQ(back.point_count(), 2);
    std::filesystem::remove(path);
}

TEST(Measurements, ColumnsMayComeInAnyOrder)
{
    const auto path = temp("order.csv");
    std::ofstream(path) << "force_N,depth_mm,probe,point,x_mm,y_mm,z_mm,nx,ny,nz\n1.5,2,probe,7,0,0,0,0,0,1\n";
    const MeasurementSet set = read_measurements(path);
    EXPECT_EQ(set.samples[0].point, 7);
    EXPECT_DOUBLE_EQ(set.samples[0].force_N, 1.5);
    std::filesystem::remove(path);
}

TEST(Measurements, MalformedFilesNameFileLineAndField)
{
    const std::string missing_column = error_for("point,probe,x_mm,y_mm,z_mm,nx,ny,nz,depth_mm\n");
    EXPECT_NE(missing_column.find("echosim_meas_"), std::string::npos) << missing_column;
    EXPECT_NE(missing_column.find(":1:"), std::string::npos) << missing_column;
    EXPECT_NE(missing_column.find("'force_N'"), std::string::npos) << missing_column;

    const std::string nan = error_for(std::string(kHeader) + kGoodRow + "3,indenter,-40,-50,-90,0.6,-0.8,0,4.0,nan\n");
    EXPECT_NE(nan.find(":3: field 'force_N': not a finite number"), std::string::npos) << nan;

    const std::string negative = error_for(std::string(kHeader) + "3,probe,-40,-50,-90,0.6,-0.8,0,-2.0,1.0\n");
    EXPECT_NE(negative.find(":2: field 'depth_mm': negative depth"), std::string::npos) << negative;

    const std::string probe = error_for(std::string(kHeader) + "3,finger,-40,-50,-90,0.6,-0.8,0,2.0,1.0\n");
    EXPECT_NE(probe.find(":2: field 'probe': unknown probe 'finger'"), std::string::npos) << probe;

    const std::string short_row = error_for(std::string(kHeader) + "3,probe,-40,-50,-90,0.6,-0.8,0,2.0\n");
    EXPECT_NE(short_row.find(":2: 9 fields, the header has 10"), std::string::npos) << short_row;

    const std::string normal = error_for(std::string(kHeader) + "3,probe,-40,-50,-90,0.3,0.3,0,2.0,1\n");
    EXPECT_NE(normal.find("'nx,ny,nz'"), std::string::npos) << normal;

    const std::string point = error_for(std::string(kHeader) + "2.5,probe,-40,-50,-90,0.6,-0.8,0,2.0,1\n");
    EXPECT_NE(point.find("field 'point'"), std::string::npos) << point;

    EXPECT_NE(error_for("").find("empty file"), std::string::npos);
    EXPECT_NE(error_for(kHeader).find("no samples"), std::string::npos);
    EXPECT_EQ(error_for(std::string("# comment\n") + kHeader + kGoodRow), "no error");
}

// Issue 13: /dev/zero given as the CSV made the reader take gigabytes looking for the first line's end.
TEST(Measurements, RefusesWhatIsNotARegularFile)
{
    test::expect_special_files_refused<MeasurementError>("meas", [](const std::filesystem::path& p) { read_measurements(p); });
}

}  // namespace
}  // namespace echosim::fit
