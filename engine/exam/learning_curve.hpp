// A trainee's learning curve from the records: the score of each session in order, and a CUSUM
// chart per station type (exam/station_status.hpp, station_type: cfv, sfj, fv, popliteal, ...).
//
// The CUSUM is the learning-curve CUSUM for procedural skills of Williams et al. (BMJ 1992;304:1359)
// as Bolsin and Colson applied it to trainees (Int J Qual Health Care 2000;12:433): each attempt
// is a success or a failure; with p0 the acceptable and p1 the unacceptable failure rate and
// alpha, beta the chances of a false alarm and of a missed one,
//   P = ln(p1 / p0),  Q = ln((1 - p0) / (1 - p1)),
//   s  = Q / (P + Q)                       (= ln((1-p0)/(1-p1)) / ln(p1 (1-p0) / (p0 (1-p1))))
//   h0 = ln((1 - alpha) / beta) / (P + Q),  h1 = ln((1 - beta) / alpha) / (P + Q);
// the sum starts at 0, falls by s at each success and rises by 1 - s at each failure. Reaching -h0
// says the trainee works at the acceptable rate p0 (with error beta), reaching +h1 at the
// unacceptable rate p1 (with error alpha). Our parameters, from Bolsin and Colson's for a new
// procedure: p0 = 0.10, p1 = 0.20, alpha = beta = 0.10; then s = 0.145 and h0 = h1 = 2.71, so 19
// successes in a row without a failure cross -h0. A success is a station reached, adequately
// pressed and called right; a station skipped is a failure.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "exam/records.hpp"
#include "io/png.hpp"

namespace echosim::exam {

struct CusumParameters {
    double p0 = 0.10;     // acceptable failure rate
    double p1 = 0.20;     // unacceptable failure rate
    double alpha = 0.10;  // type I error: a trainee at p0 flagged as at p1
    double beta = 0.10;   // type II error: a trainee at p1 taken as at p0
};

struct CusumLimits {
    double s = 0;   // the fall at a success; a failure adds 1 - s
    double h0 = 0;  // the sum at or below -h0: acceptable
    double h1 = 0;  // the sum at or above +h1: unacceptable
};

// Throws std::invalid_argument unless 0 < p0 < p1 < 1 and 0 < alpha, beta < 0.5.
CusumLimits cusum_limits(const CusumParameters& p);

// The sum after each attempt (successes[i]: attempt i succeeded).
std::vector<double> cusum_path(const std::vector<bool>& successes, const CusumLimits& limits);

enum class CusumVerdict { acceptable, unacceptable, undecided };
const char* cusum_verdict_name(CusumVerdict v);  // "acceptable", "unacceptable", "undecided"
// From the last sum: <= -h0 acceptable, >= h1 unacceptable, between undecided.
CusumVerdict cusum_verdict(const std::vector<double>& path, const CusumLimits& limits);

struct SessionPoint {
    std::int64_t session_id = 0;
    std::string case_id;
    double score = 0;
    bool passed = false;
};

struct StationTypeCurve {
    std::string type;
    std::vector<bool> successes;  // the attempts in order: sessions in order, stations in the protocol's
    std::vector<double> cusum;    // after each attempt
    CusumVerdict verdict = CusumVerdict::undecided;
};

struct LearningCurve {
    std::string trainee;
    std::vector<SessionPoint> sessions;      // in the order stored
    std::vector<StationTypeCurve> stations;  // by type, in the order first met
    CusumParameters parameters;
    CusumLimits limits;
};

LearningCurve learning_curve(const Records& records, const std::string& trainee, const CusumParameters& parameters = {});

// A text table for the terminal: the sessions' scores, then the CUSUM per station type with the
// parameters and the limits.
std::string learning_curve_table(const LearningCurve& curve);

// One row per trainee: the score per session against the pass mark, and the CUSUM per station type
// with the -h0 and +h1 lines.
io::RgbaImage learning_curve_plot(const std::vector<LearningCurve>& curves, double pass_mark = 0.8);

}  // namespace echosim::exam
