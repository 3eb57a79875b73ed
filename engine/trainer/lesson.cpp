#include "trainer/lesson.hpp"

#include <cmath>
#include <stdexcept>

#include "exam/course_limits.hpp"
#include "exam/protocol_check.hpp"

namespace echosim::trainer {

const char* difficulty_name(Difficulty d)
{
    switch (d) {
    case Difficulty::beginner: return "beginner";
    case Difficulty::intermediate: return "intermediate";
    case Difficulty::expert: return "expert";
    }
    return "?";
}

exam::Scenario lesson_scenario(const exam::Scenario& c, exam::Protocol lesson)
{
    exam::Scenario s = c;
    s.protocol = lesson;
    if (lesson != exam::Protocol::extended) {
        const auto& all = c.stations;
        int groin = -1, sfj = -1, popliteal = -1, mid_fv = -1;
        const double mid_cm = 0.5 * (exam::course::kBifurcation_cm + exam::course::kHiatus_cm);
        for (std::size_t i = 0; i < all.size(); ++i) {
            const exam::Station& st = all[i];
            const int k = int(i);
            if (st.segment == echo::VeinSegment::cfv && st.s_cm < exam::course::kSfj_cm - exam::course::kAtLandmark_cm && groin < 0) groin = k;
            if (st.segment == echo::VeinSegment::cfv && std::abs(st.s_cm - exam::course::kSfj_cm) <= exam::course::kAtLandmark_cm && sfj < 0)
                sfj = k;
            if (st.segment == echo::VeinSegment::popliteal && popliteal < 0) popliteal = k;
            if (st.segment == echo::VeinSegment::fv &&
                (mid_fv < 0 || std::abs(st.s_cm - mid_cm) < std::abs(all[std::size_t(mid_fv)].s_cm - mid_cm)))
                mid_fv = k;
        }
        std::vector<exam::Station> kept;
        if (groin >= 0) kept.push_back(all[std::size_t(groin)]);
        if (lesson == exam::Protocol::three_point) {
            if (sfj >= 0) kept.push_back(all[std::size_t(sfj)]);
            else if (mid_fv >= 0) kept.push_back(all[std::size_t(mid_fv)]);
        }
        if (popliteal >= 0) kept.push_back(all[std::size_t(popliteal)]);
        s.stations = std::move(kept);
    }
    if (const exam::ProtocolDefect d = exam::protocol_defect(lesson, s.stations))
        throw std::invalid_argument("case " + c.id + " as a " + exam::protocol_name(lesson) + " lesson: " + d.why);
    return s;
}

}  // namespace echosim::trainer
