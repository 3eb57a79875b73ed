#include "exam/exam_report.hpp"

namespace echosim::exam {

const char* call_name(Call c)
{
    switch (c) {
    case Call::none: return "none";
    case Call::compressible: return "compressible";
    case Call::not_compressible: return "not-compressible";
    }
    return "?";
}

const char* error_name(ErrorKind e)
{
    switch (e) {
    case ErrorKind::skipped_station: return "skipped-station";
    case ErrorKind::too_little_pressure: return "too-little-pressure";
    case ErrorKind::wrong_vessel: return "wrong-vessel";
    case ErrorKind::oblique_plane: return "oblique-plane";
    case ErrorKind::excessive_force: return "excessive-force";
    case ErrorKind::mimic_called_clot: return "mimic-called-clot";
    case ErrorKind::wrong_call: return "wrong-call";
    }
    return "?";
}

}  // namespace echosim::exam
