#include "exam/station_status.hpp"

#include <cctype>

namespace echosim::exam {
namespace {

bool flagged_at(const ExamReport& report, std::size_t station, const ErrorKind* only)
{
    const std::string& name = report.stations[station].name;
    for (const FlaggedError& e : report.errors)
        if (e.station == name && (!only || e.kind == *only)) return true;
    return false;
}

}  // namespace

const char* station_status_name(StationStatus s)
{
    switch (s) {
    case StationStatus::covered: return "covered";
    case StationStatus::skipped: return "skipped";
    case StationStatus::wrong: return "wrong";
    }
    return "?";
}

StationStatus station_status(const ExamReport& report, std::size_t station)
{
    const StationResult& r = report.stations.at(station);
    if (!r.reached) return StationStatus::skipped;
    if (!r.call_correct || flagged_at(report, station, nullptr)) return StationStatus::wrong;
    return StationStatus::covered;
}

bool adequately_pressed(const ExamReport& report, std::size_t station)
{
    constexpr ErrorKind too_little = ErrorKind::too_little_pressure;
    return report.stations.at(station).reached && !flagged_at(report, station, &too_little);
}

bool pressed_within_bands(const ExamReport& report, std::size_t station)
{
    constexpr ErrorKind excessive = ErrorKind::excessive_force;
    return adequately_pressed(report, station) && !flagged_at(report, station, &excessive);
}

bool station_success(const ExamReport& report, std::size_t station)
{
    return adequately_pressed(report, station) && report.stations[station].call_correct;
}

std::string station_type(const std::string& name, const std::string& segment)
{
    std::string type;
    std::size_t i = 0;
    while (i < name.size() && std::isspace(static_cast<unsigned char>(name[i]))) ++i;
    for (; i < name.size() && !std::isspace(static_cast<unsigned char>(name[i])); ++i) {
        const auto c = static_cast<unsigned char>(name[i]);
        if (c < 0x80 && std::isalnum(c)) type += char(std::tolower(c));
    }
    return type.empty() ? segment : type;
}

}  // namespace echosim::exam
