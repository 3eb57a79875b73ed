// The exam's observers of the runner (runner/runner.hpp): the scorer's adapter, which hands it each
// step's view as plain values and the script's calls at their times, and the force log. Both keep
// what they see in memory; `echosim exam` writes it when the run has ended.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "exam/exam_script.hpp"
#include "exam/scorer.hpp"
#include "runner/runner.hpp"

namespace echosim::app {

class ScorerObserver final : public runner::Observer {
public:
    // `calls` in time order (a script's); each is made at the first step at or after its time.
    ScorerObserver(exam::Scorer& scorer, std::vector<exam::TimedCall> calls) : scorer_(scorer), calls_(std::move(calls)) {}

    void on_step(runner::StepContext& step) override
    {
        const session::SessionView& v = step.view;
        scorer_.observe({v.time_s, v.probe, v.probe_force_N, v.echo});
        while (next_ < calls_.size() && calls_[next_].t_s <= v.time_s + 1e-9) {
            scorer_.call(v.time_s, calls_[next_].call);
            ++next_;
        }
        // the force log: one row a step
        const std::optional<std::size_t> at = scorer_.current_station();
        rows_.push_back({v.time_s, v.probe_force_N, v.press_mm, v.probe, at ? int(*at) : -1});
    }

    // The force log as CSV: time, force, press, the probe's position, the station it is at ("" none).
    std::string force_csv() const
    {
        std::string text = "t_s,force_N,press_mm,x_mm,y_mm,z_mm,station\n";
        char row[256];
        for (const Row& r : rows_) {
            std::snprintf(row, sizeof row, "%.4f,%.4f,%.4f,%.3f,%.3f,%.3f,", r.t_s, r.force_N, r.press_mm, double(r.probe.position.x),
                          double(r.probe.position.y), double(r.probe.position.z));
            text += row;
            if (r.station >= 0) text += csv_quoted(scorer_.truth()[std::size_t(r.station)].name);
            text += "\n";
        }
        return text;
    }

private:
    // a case's station name as one CSV field, whatever it holds (RFC 4180)
    static std::string csv_quoted(const std::string& s)
    {
        std::string q = "\"";
        for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
    }
    struct Row {
        double t_s, force_N, press_mm;
        Pose probe;
        int station;
    };
    exam::Scorer& scorer_;
    std::vector<exam::TimedCall> calls_;
    std::size_t next_ = 0;
    std::vector<Row> rows_;
};

}  // namespace echosim::app
