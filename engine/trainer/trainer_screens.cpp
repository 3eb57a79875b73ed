#include "trainer/trainer_screens.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "exam/station_status.hpp"
#include "runner/frame.hpp"
#include "scene/leg.hpp"

namespace echosim::trainer {
namespace {

constexpr ImGuiWindowFlags kFixed = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                    ImGuiWindowFlags_NoSavedSettings;

const ImVec4 kGreen(0.30f, 0.80f, 0.40f, 1.0f), kRed(0.95f, 0.30f, 0.25f, 1.0f), kAmber(0.98f, 0.75f, 0.20f, 1.0f),
    kGrey(0.60f, 0.62f, 0.66f, 1.0f), kBlue(0.40f, 0.65f, 1.0f, 1.0f);

// where the item just drawn lies, kept under `name`
void remember(ScreenState& state, const char* name)
{
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    state.hotspots[name] = {a.x, a.y, b.x, b.y};
}

// `top` blended over the opaque `bottom`: opaque
ImVec4 over(const ImVec4& top, const ImVec4& bottom)
{
    auto mix = [&](float t, float b) { return top.w * t + (1 - top.w) * b; };
    return ImVec4(mix(top.x, bottom.x), mix(top.y, bottom.y), mix(top.z, bottom.z), 1.0f);
}

ImU32 u32(const ImVec4& c, float alpha = 1.0f) { return ImGui::GetColorU32(ImVec4(c.x, c.y, c.z, c.w * alpha)); }

const char* lesson_label(exam::Protocol p)
{
    switch (p) {
    case exam::Protocol::two_point: return "Two-point (CFV, popliteal)";
    case exam::Protocol::three_point: return "Three-point (CFV, SFJ, popliteal)";
    case exam::Protocol::extended: return "Extended (groin to knee, every 2 cm)";
    }
    return "?";
}

bool big_button(const char* label, const ImVec2& size, const ui::UiFonts& fonts, const ImVec4& colour, bool large = true)
{
    ImGui::PushFont(large ? fonts.large : fonts.bold);
    ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(colour.x * 0.55f, colour.y * 0.55f, colour.z * 0.55f, 1.0f));
    ImGui::PushStyleColor(ImGuiCol_ButtonHovered, ImVec4(colour.x * 0.75f, colour.y * 0.75f, colour.z * 0.75f, 1.0f));
    ImGui::PushStyleColor(ImGuiCol_ButtonActive, colour);
    const bool pressed = ImGui::Button(label, size);
    ImGui::PopStyleColor(3);
    ImGui::PopFont();
    return pressed;
}

// --- start screen

Action start_screen(Trainer& t, const session::SessionView& view, VkExtent2D extent, const ui::UiFonts& fonts, float scale, ScreenState& state)
{
    Action action = Action::none;
    StartForm& form = t.form();
    const float w = std::min(float(extent.width) * 0.9f, 760.0f * scale);
    const float h = std::min(float(extent.height) * 0.96f, 740.0f * scale);  // a long case description fits at 720
    ImGui::SetNextWindowPos(ImVec2((float(extent.width) - w) * 0.5f, (float(extent.height) - h) * 0.5f));
    ImGui::SetNextWindowSize(ImVec2(w, h));
    ImGui::Begin("echosim trainer", nullptr, kFixed | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoBackground);
    ui::solid_background();
    ImGui::PushFont(fonts.large);
    ImGui::TextUnformatted("Compression ultrasound of the leg's veins");
    ImGui::PopFont();
    ImGui::TextColored(kGrey, "A lesson: find each station of the protocol, press until the vein closes (or does not), and call it.");
    if (!t.message().empty()) ImGui::TextColored(kAmber, "%s", t.message().c_str());
    if (!t.last_error().empty()) ImGui::TextColored(kRed, "%s", t.last_error().c_str());
    ImGui::Separator();

    ImGui::TextUnformatted("Trainee");
    ImGui::SetNextItemWidth(w * 0.5f);
    if (state.last != Screen::start) ImGui::SetKeyboardFocusHere();  // a trainee walking up types at once
    ImGui::InputTextWithHint("##trainee", "your name, for the records", &form.trainee);
    remember(state, "trainee");

    ImGui::Spacing();
    ImGui::TextUnformatted("Lesson  (F1, F2, F3)");
    for (exam::Protocol p : Trainer::kLessons)
        if (ImGui::RadioButton(lesson_label(p), form.lesson == p)) form.lesson = p;

    ImGui::Spacing();
    ImGui::TextUnformatted("Case  (F4 / F5 previous / next, F6 random)");
    ImGui::SetNextItemWidth(w * 0.7f);
    const std::vector<exam::Scenario>& cases = t.cases();
    const std::string shown = form.case_index < 0 ? std::string("Random case (not told)") : cases[std::size_t(form.case_index)].title;
    if (ImGui::BeginCombo("##case", shown.c_str())) {
        if (ImGui::Selectable("Random case (not told)", form.case_index < 0)) form.case_index = -1;
        for (std::size_t i = 0; i < cases.size(); ++i)
            if (ImGui::Selectable(cases[i].title.c_str(), form.case_index == int(i))) form.case_index = int(i);
        ImGui::EndCombo();
    }
    if (form.case_index >= 0) {
        const exam::Scenario& c = cases[std::size_t(form.case_index)];
        ImGui::PushTextWrapPos(w - 20 * scale);
        ImGui::TextColored(kGrey, "%s", c.description.c_str());
        ImGui::PopTextWrapPos();
    }

    ImGui::Spacing();
    ImGui::TextUnformatted("Difficulty  (F7)");
    for (Difficulty d : {Difficulty::beginner, Difficulty::intermediate, Difficulty::expert}) {
        if (ImGui::RadioButton(difficulty_name(d), form.difficulty == d)) form.difficulty = d;
        ImGui::SameLine();
    }
    ImGui::NewLine();
    ImGui::TextColored(kGrey, "Beginner: guidance arrow, directions and distances. Intermediate: fainter, no distances. Expert: none.");

    ImGui::Spacing();
    // the chosen case's images not made yet (the first run, a kiosk's cases): how far they are; a
    // start asked for then begins the lesson once they are ready
    const CaseReadiness ready = t.readiness(t.chosen_case());
    const char* label = ready.ready ? "Start  (Enter)" : t.start_waiting() ? "Starts when ready" : "Start when ready  (Enter)";
    const bool start = big_button(label, ImVec2(w * 0.4f, 56 * scale), fonts, ready.ready ? kGreen : kGrey);
    remember(state, "start");
    if (start) action = t.request_start(view.time_s);
    if (ready.ready && !ready.line.empty()) {  // the other cases' images (a kiosk's)
        ImGui::SameLine();
        ImGui::PushTextWrapPos(w - 20 * scale);
        ImGui::TextColored(kGrey, "%s", ready.line.c_str());
        ImGui::PopTextWrapPos();
    }
    if (!ready.ready) {  // beside the button: the screen's height is taken
        ImGui::SameLine();
        ImGui::BeginGroup();
        ImGui::PushTextWrapPos(w - 20 * scale);
        ImGui::TextColored(kAmber, "%s", ready.line.c_str());
        ImGui::PopTextWrapPos();
        if (ready.done >= 0) {
            ImGui::PushStyleColor(ImGuiCol_PlotHistogram, kAmber);
            ImGui::ProgressBar(float(std::clamp(ready.done, 0.0, 1.0)), ImVec2(w * 0.5f, 0));
            ImGui::PopStyleColor();
        }
        ImGui::EndGroup();
    }
    ImGui::Separator();
    ImGui::TextColored(kGrey, "The exam: C compressible, N not compressible, End finish, H guidance on/off. %s",
                       t.options().kiosk ? "Ctrl+Alt+Q quits." : "Esc quits.");
    ImGui::TextColored(kGrey, "The probe: right-drag or arrows slide, W/S press, Q/E A/D tilt, R levels; green marker to the patient's right.");
    ImGui::TextColored(kGrey, "The scanner: ] and [ depth, + and - gain, Page Up/Down focus, Space freezes (then click twice to measure).");
    ImGui::End();
    return action;
}

// --- exam screen

// The leg map: the stations by their height on the leg (LPS z: the groin at the top), the probe's
// place, and the guidance arrow from it to the next station.
void leg_map(const Trainer& t, const Guidance* g, std::optional<std::size_t> target, float alpha, float width, float height, float scale)
{
    const std::vector<exam::StationTruth>& truth = t.scorer().truth();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 o = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(width, height));
    double top = -1e9, bottom = 1e9;
    for (const exam::StationTruth& s : truth) top = std::max(top, s.vein.centre.z), bottom = std::min(bottom, s.vein.centre.z);
    const double margin = std::max(40.0, 0.12 * (top - bottom));  // room for the arrow past the ends [mm]
    top += margin;
    bottom -= margin;
    const float x = o.x + width * 0.30f;
    // the leg between a line for "groin" above and one for "knee" below
    const float fs = ImGui::GetFontSize();
    const float y0 = o.y + fs + 4 * scale, y1 = o.y + height - fs - 4 * scale;
    auto y_of = [&](double z) { return y0 + float((top - z) / (top - bottom)) * (y1 - y0); };
    dl->AddRectFilled(ImVec2(x - 10 * scale, y0), ImVec2(x + 10 * scale, y1), u32(ImVec4(0.35f, 0.25f, 0.25f, 1)), 8 * scale);
    dl->AddText(ImVec2(x - ImGui::CalcTextSize("groin").x * 0.5f, o.y), u32(kGrey), "groin");
    dl->AddText(ImVec2(x - ImGui::CalcTextSize("knee").x * 0.5f, y1 + 4 * scale), u32(kGrey), "knee");
    const bool expert = t.form().difficulty == Difficulty::expert;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const float y = y_of(truth[i].vein.centre.z);
        ImVec4 c = kGrey;
        if (t.station_done(i)) c = expert ? kBlue : (t.station_wrong(i) ? kRed : kGreen);
        else if (!expert && t.station_wrong(i)) c = kRed;
        const float r = (target && *target == i ? 7.0f : 5.0f) * scale;
        dl->AddCircleFilled(ImVec2(x, y), r, u32(c));
        if (target && *target == i) dl->AddCircle(ImVec2(x, y), r + 3 * scale, u32(kAmber), 0, 2 * scale);
        if (truth.size() <= 4 || i == 0 || i + 1 == truth.size() || (target && *target == i))
            dl->AddText(ImVec2(x + 16 * scale, y - ImGui::GetFontSize() * 0.5f), u32(c), truth[i].name.c_str());
    }
    // the probe
    const double pz = double(t.last_sample().face.position.z);
    if (t.last_sample().time_s > 0 && pz < top && pz > bottom) {
        const float y = y_of(pz);
        const float px = x - 22 * scale;
        dl->AddTriangleFilled(ImVec2(px - 8 * scale, y - 7 * scale), ImVec2(px - 8 * scale, y + 7 * scale), ImVec2(px + 4 * scale, y), u32(kAmber));
        // the arrow to the next station
        if (g && target && alpha > 0 && !g->there && std::abs(g->along_mm) >= 3) {
            // from the probe towards the station, at least a thumb's length on the map
            const float dir = g->along_mm > 0 ? -1.0f : 1.0f;  // up the map: towards the groin
            float ty = y_of(truth[*target].vein.centre.z);
            if (std::abs(ty - y) < 36 * scale) ty = y + dir * 36 * scale;
            ty = std::clamp(ty, y0, y1);
            const float ax = px - 16 * scale;
            dl->AddLine(ImVec2(ax, y), ImVec2(ax, ty - dir * 12 * scale), u32(kAmber, alpha), 5 * scale);
            dl->AddTriangleFilled(ImVec2(ax - 10 * scale, ty - dir * 14 * scale), ImVec2(ax + 10 * scale, ty - dir * 14 * scale), ImVec2(ax, ty),
                                  u32(kAmber, alpha));
        }
    }
}

// The turn dial: the probe's array as a bar, the vein's course through it, the turn as an arc.
void turn_dial(const Guidance& g, float alpha, float size, float scale)
{
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 o = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(size, size));
    const ImVec2 c(o.x + size * 0.5f, o.y + size * 0.5f);
    const float r = size * 0.42f;
    dl->AddCircle(c, r, u32(kGrey), 48, 1.5f * scale);
    // the array across (the image's width) and the vein's course: transverse when they are square
    dl->AddLine(ImVec2(c.x - r * 0.8f, c.y), ImVec2(c.x + r * 0.8f, c.y), u32(kBlue), 5 * scale);
    const float a = float(g.turn_deg * 3.14159265358979 / 180.0);
    const ImVec2 v(std::sin(a) * r, -std::cos(a) * r);
    dl->AddLine(ImVec2(c.x - v.x, c.y - v.y), ImVec2(c.x + v.x, c.y + v.y), u32(ImVec4(0.45f, 0.55f, 0.95f, 1.0f), alpha), 2.5f * scale);
    if (std::abs(g.turn_deg) >= 5 && alpha > 0) {
        // the turn to make, an arc round the dial from where the array points (screen angles grow
        // clockwise) to where it should, with its head
        const float from = 0.0f, to = a;
        const float rr = r * 0.88f;
        dl->PathArcTo(c, rr, std::min(from, to), std::max(from, to), 24);
        dl->PathStroke(u32(kAmber, alpha), 0, 5 * scale);
        const ImVec2 tip(c.x + std::cos(to) * rr, c.y + std::sin(to) * rr);
        const float t = to > from ? 1.0f : -1.0f;  // the arc's direction at its end
        const ImVec2 along(-std::sin(to) * t, std::cos(to) * t), out(std::cos(to), std::sin(to));
        const float h = 11 * scale;
        dl->AddTriangleFilled(ImVec2(tip.x + along.x * h, tip.y + along.y * h), ImVec2(tip.x - along.x * 2 + out.x * h * 0.8f, tip.y - along.y * 2 + out.y * h * 0.8f),
                              ImVec2(tip.x - along.x * 2 - out.x * h * 0.8f, tip.y - along.y * 2 - out.y * h * 0.8f), u32(kAmber, alpha));
    }
}

// The force gauge: 0 to past the excessive limit, the adequate band green, beyond the limit red,
// the live force as a bar and a number.
void force_gauge(double force_N, const exam::ScoringBands& bands, float width, float scale)
{
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 o = ImGui::GetCursorScreenPos();
    const float h = 26 * scale;
    ImGui::Dummy(ImVec2(width, h + ImGui::GetFontSize() + 4 * scale));
    const double top = std::max(bands.excessive_force_N * 1.3, force_N * 1.05);
    auto x_of = [&](double f) { return o.x + float(std::clamp(f / top, 0.0, 1.0)) * width; };
    dl->AddRectFilled(o, ImVec2(o.x + width, o.y + h), u32(ImVec4(0.18f, 0.19f, 0.22f, 1)));
    dl->AddRectFilled(ImVec2(x_of(bands.adequate_force_N), o.y), ImVec2(x_of(bands.excessive_force_N), o.y + h), u32(ImVec4(0.20f, 0.45f, 0.25f, 1)));
    dl->AddRectFilled(ImVec2(x_of(bands.excessive_force_N), o.y), ImVec2(o.x + width, o.y + h), u32(ImVec4(0.50f, 0.18f, 0.16f, 1)));
    const ImVec4 c = force_N > bands.excessive_force_N ? kRed : force_N >= bands.adequate_force_N ? kGreen : kAmber;
    dl->AddRectFilled(ImVec2(o.x, o.y + h * 0.3f), ImVec2(x_of(force_N), o.y + h * 0.7f), u32(c));
    dl->AddLine(ImVec2(x_of(force_N), o.y - 2 * scale), ImVec2(x_of(force_N), o.y + h + 2 * scale), u32(ImVec4(1, 1, 1, 1)), 2 * scale);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.0f N", bands.adequate_force_N);
    dl->AddText(ImVec2(x_of(bands.adequate_force_N) - 8 * scale, o.y + h + 2 * scale), u32(kGreen), buf);
    std::snprintf(buf, sizeof buf, "%.0f N", bands.excessive_force_N);
    dl->AddText(ImVec2(x_of(bands.excessive_force_N) - 8 * scale, o.y + h + 2 * scale), u32(kRed), buf);
}

Action exam_screen(Trainer& t, const session::SessionView& view, const echo::ImagePlane& plane, VkExtent2D extent, const ui::UiFonts& fonts,
                   float scale, ScreenState& state)
{
    Action action = Action::none;
    const exam::Scenario& lesson = t.lesson();
    const exam::Scorer& scorer = t.scorer();
    const std::vector<exam::StationTruth>& truth = scorer.truth();
    // the panel over the leg's view, left of the echographic image
    const render::TargetRect image = runner::echo_panel_rect(extent, plane);
    const float image_left = image.x * float(extent.width);
    const float w = std::min(400.0f * scale, std::max(200.0f, image_left * 0.6f));
    ImGui::SetNextWindowPos(ImVec2(8 * scale, 8 * scale));
    // as tall as what it holds, at most the frame's height: the leg's view stays clear below it;
    // solid, its text on a steady background (and on lavapipe a blended panel costs every pixel
    // it covers: ui/ui_pass.hpp)
    ImGui::SetNextWindowSizeConstraints(ImVec2(w, 0), ImVec2(w, float(extent.height) - 16 * scale));
    ImGui::Begin("Lesson", nullptr,
                 kFixed | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoBackground);
    ui::solid_background();
    ImGui::TextColored(kGrey, "%s lesson, %s", exam::protocol_name(lesson.protocol), difficulty_name(t.form().difficulty));
    ImGui::PushTextWrapPos(w - 12 * scale);
    ImGui::TextUnformatted(t.form().case_index < 0 ? "Random case" : lesson.title.c_str());
    ImGui::PopTextWrapPos();
    ImGui::Separator();

    // the step
    const std::optional<std::size_t> target = t.target();
    std::size_t done = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) done += t.station_done(i) ? 1 : 0;
    ImGui::PushFont(fonts.large);
    if (target) ImGui::Text("Station %zu of %zu: %s", *target + 1, truth.size(), truth[*target].name.c_str());
    else ImGui::TextUnformatted("Every station done");
    ImGui::PopFont();
    const std::optional<std::size_t> at = scorer.current_station();
    if (at) ImGui::TextColored(kGreen, "The probe is at %s.", truth[*at].name.c_str());
    else ImGui::TextColored(kGrey, "The probe is at no station.");

    // guidance towards the next station
    const GuidanceLevel level = t.guidance_on() ? guidance_level(t.form().difficulty) : GuidanceLevel{0, false, false};
    std::optional<Guidance> g;
    if (target) g = guide(view.probe, truth[*target], lesson.bands);
    if (g && level.text) {
        ImGui::PushTextWrapPos(w - 12 * scale);
        ImGui::TextColored(kAmber, "%s", guidance_text(*g, level, plane.depth_mm).c_str());
        ImGui::PopTextWrapPos();
    } else if (!target) {
        ImGui::TextColored(kGreen, "Finish the exam to see the report (End).");
    }
    const float map_h = std::max(120.0f * scale, float(extent.height) * 0.30f);
    ImGui::BeginGroup();
    leg_map(t, g ? &*g : nullptr, target, level.arrow_alpha, w * 0.55f, map_h, scale);
    ImGui::EndGroup();
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextColored(kGrey, "Turn");
    if (g) turn_dial(*g, level.arrow_alpha, w * 0.32f, scale);
    ImGui::Text("%zu / %zu done", done, truth.size());
    ImGui::EndGroup();

    // the force
    ImGui::Separator();
    ImGui::Text("Force %.1f N", view.probe_force_N);
    force_gauge(view.probe_force_N, lesson.bands, w - 28 * scale, scale);
    if (at) {
        const exam::Scorer::StationProgress p = scorer.progress(*at);
        ImGui::TextColored(p.peak_force_N >= lesson.bands.adequate_force_N ? kGreen : kGrey, "Deepest press here %.1f N", p.peak_force_N);
    }

    // the calls
    ImGui::Separator();
    const float bw = (w - 34 * scale) * 0.5f;
    if (big_button("Compressible\n(C)", ImVec2(bw, 64 * scale), fonts, kGreen, false)) t.call(view.time_s, exam::Call::compressible);
    remember(state, "compressible");
    ImGui::SameLine();
    if (big_button("Not compressible\n(N)", ImVec2(bw, 64 * scale), fonts, kRed, false)) t.call(view.time_s, exam::Call::not_compressible);
    remember(state, "not-compressible");
    if (const std::optional<std::size_t> last = scorer.last_examined()) {
        const exam::Call c = scorer.progress(*last).call;
        ImGui::TextColored(kGrey, "%s: %s", truth[*last].name.c_str(), c == exam::Call::none ? "not called yet" : exam::call_name(c));
    }
    const bool finish = ImGui::Button("Finish the exam (End)", ImVec2(w - 24 * scale, 0));
    remember(state, "finish");
    if (finish) {
        t.finish();
        action = Action::finished;
    }
    const ImVec2 panel_at = ImGui::GetWindowPos(), panel_size = ImGui::GetWindowSize();
    state.exam_panel = ScreenState::Rect{panel_at.x, panel_at.y, panel_at.x + panel_size.x, panel_at.y + panel_size.y};
    ImGui::End();
    return action;
}

// --- report screen

// The force over the exam, the adequate band shaded and the excessive limit drawn across it; the
// trace one point a pixel column (the largest force in the column's span of samples), inset by the
// frame's padding, and a flat run one segment (a lesson's trace is mostly rests and plateaus: on
// lavapipe each segment is triangles to set up, ui/ui_pass.hpp).
void force_trace(const exam::ExamReport& r, float width, float height, float scale)
{
    if (r.force_trace.size() < 2) return;
    const ImVec2 o = ImGui::GetCursorScreenPos();
    ImGui::Dummy(ImVec2(width, height));
    const ImVec2 pad = ImGui::GetStyle().FramePadding;
    const std::size_t n = std::min<std::size_t>(r.force_trace.size(), std::size_t(std::max(2.0f, width - 2 * pad.x)));
    std::vector<float> values(n, 0.0f);
    for (std::size_t i = 0; i < r.force_trace.size(); ++i) {
        const std::size_t k = i * n / r.force_trace.size();
        values[k] = std::max(values[k], float(r.force_trace[i].second));
    }
    float top = float(std::max(r.excessive_force_N * 1.3, 1.0));
    for (float v : values) top = std::max(top, v);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    auto y_of = [&](double f) { return o.y + height - float(f / top) * height; };
    // the background and the band cleared under the window's content (ui::solid_rect), as they
    // looked blended over it: no blended pixels
    const ImVec4 back = over(ImVec4(0.12f, 0.13f, 0.15f, 0.8f), ImGui::GetStyleColorVec4(ImGuiCol_WindowBg));
    ui::solid_rect(o, ImVec2(o.x + width, o.y + height), back);
    if (r.adequate_force_N > 0 && r.excessive_force_N > 0) {
        ui::solid_rect(ImVec2(o.x, y_of(r.excessive_force_N)), ImVec2(o.x + width, y_of(r.adequate_force_N)), over(ImVec4(0.20f, 0.45f, 0.25f, 0.45f), back));
        dl->AddLine(ImVec2(o.x, y_of(r.excessive_force_N)), ImVec2(o.x + width, y_of(r.excessive_force_N)), u32(kRed), 1.5f * scale);
    }
    const float x0 = o.x + pad.x, x1 = o.x + width - pad.x, y1 = o.y + height - pad.y, h = height - 2 * pad.y;
    std::vector<ImVec2> points;
    for (std::size_t i = 0; i < n; ++i) {
        if (i > 0 && i + 1 < n && values[i] == values[i - 1] && values[i] == values[i + 1]) continue;  // inside a flat run
        points.emplace_back(x0 + (x1 - x0) * float(i) / float(n - 1), y1 - values[i] / top * h);
    }
    dl->AddPolyline(points.data(), int(points.size()), u32(kAmber), 0, 1.0f);
    char label[64];
    std::snprintf(label, sizeof label, "force over the exam, 0 to %.0f N", double(top));
    dl->AddText(ImVec2(o.x + 6 * scale, o.y + 2 * scale), u32(kGrey), label);
}

Action report_screen(Trainer& t, VkExtent2D extent, const ui::UiFonts& fonts, float scale, ScreenState& state)
{
    const exam::ExamReport& r = t.report();
    const float w = std::min(float(extent.width) * 0.94f, 1100.0f * scale);
    const float h = float(extent.height) * 0.94f;
    ImGui::SetNextWindowPos(ImVec2((float(extent.width) - w) * 0.5f, float(extent.height) * 0.03f));
    ImGui::SetNextWindowSize(ImVec2(w, h));
    ImGui::Begin("Report", nullptr, kFixed | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoBackground);
    ui::solid_background();
    ImGui::PushFont(fonts.large);
    ImGui::TextColored(r.passed ? kGreen : kRed, "Score %.0f %%  (pass mark %.0f %%): %s", 100 * r.score, 100 * r.pass_mark, r.passed ? "passed" : "not passed");
    ImGui::PopFont();
    // the way on, at the top right where a long report never pushes it out of sight
    ImGui::SameLine(w - w * 0.3f - 12 * scale);
    const bool again = big_button("New lesson  (Enter)", ImVec2(w * 0.3f, 0), fonts, kBlue, false);
    remember(state, "new-lesson");
    if (again) t.new_lesson();
    ImGui::Text("%s%s%s, %s protocol", r.trainee.empty() ? "" : r.trainee.c_str(), r.trainee.empty() ? "" : ": ", r.case_title.c_str(), r.protocol.c_str());
    ImGui::PushTextWrapPos(w - 20 * scale);
    ImGui::TextColored(kAmber, "%s", r.conclusion.c_str());
    ImGui::PopTextWrapPos();
    if (!t.last_error().empty()) ImGui::TextColored(kRed, "%s", t.last_error().c_str());

    const float table_h = h * 0.38f;
    // the station table, or in its place the stations' images at their deepest press
    const bool images = t.report_images_shown();
    const bool toggle = ImGui::Button(images ? "Station table  (I)" : "Station images  (I)");
    remember(state, "station-images");
    if (toggle) t.toggle_report_images();
    if (images) {
        const ImVec2 at = ImGui::GetCursorScreenPos();
        const float area_w = ImGui::GetContentRegionAvail().x;
        ImGui::Dummy(ImVec2(area_w, table_h));
        state.sheet_area = ScreenState::Rect{at.x, at.y, at.x + area_w, at.y + table_h};
    } else if (ImGui::BeginTable("stations", 7, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY, ImVec2(0, table_h))) {
        ImGui::TableSetupScrollFreeze(0, 1);
        for (const char* c : {"Station", "Reached", "Peak force", "Vein closed to", "Truth", "Call", ""}) ImGui::TableSetupColumn(c);
        ImGui::TableHeadersRow();
        for (std::size_t i = 0; i < r.stations.size(); ++i) {
            const exam::StationResult& s = r.stations[i];
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(s.name.c_str());
            ImGui::TableNextColumn();
            ImGui::TextColored(s.reached ? kGreen : kRed, "%s", s.reached ? "yes" : "no");
            ImGui::TableNextColumn();
            const bool ok_force = exam::pressed_within_bands(r, i);  // as scored (the force, or the walls met)
            ImGui::TextColored(ok_force ? kGreen : kAmber, "%.1f N", s.peak_force_N);
            ImGui::TableNextColumn();
            if (s.deepest_press_at_s >= 0) ImGui::Text("%.0f %%", 100 * s.collapse_ratio);
            else ImGui::TextColored(kGrey, "-");
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(s.thrombosed ? "thrombus" : "normal");
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(exam::call_name(s.call));
            ImGui::TableNextColumn();
            if (s.call == exam::Call::none) ImGui::TextColored(kGrey, "no call");
            else ImGui::TextColored(s.call_correct ? kGreen : kRed, "%s", s.call_correct ? "right" : "wrong");
        }
        ImGui::EndTable();
    }
    ImGui::Text("Errors flagged: %zu", r.errors.size());
    if (!r.errors.empty()) {
        ImGui::BeginChild("errors", ImVec2(0, std::min(h * 0.16f, float(r.errors.size()) * ImGui::GetTextLineHeightWithSpacing() + 8 * scale)), true);
        for (const exam::FlaggedError& e : r.errors)
            ImGui::TextColored(kRed, "%s at %s: %s", exam::error_name(e.kind), e.station.empty() ? "the exam" : e.station.c_str(), e.detail.c_str());
        ImGui::EndChild();
    }
    ImGui::Text("Time %.0f s, probe path %.0f mm", r.motion.duration_s, r.motion.path_mm);
    force_trace(r, w - 24 * scale, 70 * scale, scale);
    if (!t.report_dir().empty()) ImGui::TextColored(kGrey, "Report: %s", (t.report_dir() / "report.html").string().c_str());

    ImGui::Separator();
    const std::vector<exam::SessionRecord>& earlier = t.earlier();
    ImGui::Text("Sessions of %s in the records: %zu", r.trainee.empty() ? "this trainee" : r.trainee.c_str(), earlier.size());
    const float rest = h - (ImGui::GetCursorPosY() + 12 * scale);  // what the window has left for them
    if (!earlier.empty() && rest > 40 * scale &&
        ImGui::BeginTable("earlier", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY, ImVec2(0, std::min(rest, h * 0.2f)))) {
        for (const char* c : {"#", "Case", "Protocol", "Score"}) ImGui::TableSetupColumn(c);
        ImGui::TableHeadersRow();
        for (auto it = earlier.rbegin(); it != earlier.rend(); ++it) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%lld", static_cast<long long>(it->id));
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(it->case_title.c_str());
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(it->protocol.c_str());
            ImGui::TableNextColumn();
            ImGui::TextColored(it->passed ? kGreen : kRed, "%.0f %%", 100 * it->score);
        }
        ImGui::EndTable();
    }
    ImGui::End();
    return Action::none;
}

}  // namespace

Action draw_trainer(Trainer& trainer, const session::SessionView& view, const echo::ImagePlane& plane, VkExtent2D extent,
                    const ui::UiFonts& fonts, float scale, ScreenState& state)
{
    const Screen shown = trainer.screen();
    if (shown != state.last) state.hotspots.clear();
    state.sheet_area.reset();
    state.exam_panel.reset();
    Action a = Action::none;
    switch (shown) {
    case Screen::start: a = start_screen(trainer, view, extent, fonts, scale, state); break;
    case Screen::exam: a = exam_screen(trainer, view, plane, extent, fonts, scale, state); break;
    case Screen::report: a = report_screen(trainer, extent, fonts, scale, state); break;
    }
    state.last = shown;
    return a;
}

void draw_caliper(const Caliper& caliper, const ImagePanel& panel, const ui::UiFonts& fonts, float scale)
{
    ImDrawList* dl = ImGui::GetForegroundDrawList();
    const ImVec4 mark(0.55f, 1.0f, 0.35f, 1.0f), shade(0.0f, 0.0f, 0.0f, 0.75f);
    const auto at = [&](const glm::dvec2& mm) {
        const glm::vec2 p = pixel_of(panel, mm);
        return ImVec2(p.x, p.y);
    };
    // a cross, dark under bright so it reads on white speckle and black lumen alike
    const auto cross = [&](const ImVec2& c) {
        const float arm = 7 * scale;
        for (const auto& [colour, width] : {std::pair{shade, 4 * scale}, std::pair{mark, 2 * scale}}) {
            dl->AddLine(ImVec2(c.x - arm, c.y), ImVec2(c.x + arm, c.y), u32(colour), width);
            dl->AddLine(ImVec2(c.x, c.y - arm), ImVec2(c.x, c.y + arm), u32(colour), width);
        }
    };
    if (caliper.first()) cross(at(*caliper.first()));
    if (caliper.second()) {
        const ImVec2 a = at(*caliper.first()), b = at(*caliper.second());
        // dotted between the crosses, as a scanner draws it
        const float dx = b.x - a.x, dy = b.y - a.y, length = std::hypot(dx, dy), dash = 4 * scale;
        for (float d = 0; d + dash <= length; d += 2 * dash) {
            const ImVec2 p(a.x + dx * d / length, a.y + dy * d / length), q(a.x + dx * (d + dash) / length, a.y + dy * (d + dash) / length);
            dl->AddLine(p, q, u32(mark), 1.5f * scale);
        }
        cross(b);
    }
    // the line at the image's top: frozen, and what the caliper reads or how to use it
    char text[96];
    if (const std::optional<double> d = caliper.distance_mm())
        std::snprintf(text, sizeof text, "FROZEN   caliper %.1f mm (click to measure anew)", *d);
    else
        std::snprintf(text, sizeof text, "FROZEN   caliper: click %s point on the image", caliper.first() ? "the second" : "a first");
    ImGui::PushFont(fonts.bold);
    const ImVec2 size = ImGui::CalcTextSize(text);
    const ImVec2 o(panel.x + 0.5f * (panel.width - size.x), panel.y + 6 * scale);
    dl->AddRectFilled(ImVec2(o.x - 6 * scale, o.y - 3 * scale), ImVec2(o.x + size.x + 6 * scale, o.y + size.y + 3 * scale), u32(shade), 4 * scale);
    dl->AddText(o, u32(mark), text);
    ImGui::PopFont();
}

void draw_scanner_marks(const ImagePanel& panel, const echo::ScannerSettings& scanner, const ui::UiFonts& fonts, float scale)
{
    if (!(panel.depth_mm > 0) || panel.height <= 0) return;
    ImDrawList* dl = ImGui::GetForegroundDrawList();
    const ImVec4 text_colour(0.92f, 0.92f, 0.92f, 1.0f), shade(0.0f, 0.0f, 0.0f, 0.8f);
    // dark under light, a pixel down and right: it reads on bright speckle and dark lumen alike
    const auto label = [&](const ImVec2& at, const char* text) {
        dl->AddText(ImVec2(at.x + scale, at.y + scale), u32(shade), text);
        dl->AddText(at, u32(text_colour), text);
    };
    ImGui::PushFont(fonts.bold);
    char text[32];
    const float beside = panel.x + 0.03f * panel.width + 4 * scale;  // right of a major tick (3 % of the width)
    for (int cm = 1; 10.0 * cm < panel.depth_mm; ++cm) {
        std::snprintf(text, sizeof text, "%d", cm);
        const float y = panel.y + float(10.0 * cm / panel.depth_mm) * panel.height;
        label(ImVec2(beside, y - 0.5f * ImGui::GetTextLineHeight()), text);
    }
    std::snprintf(text, sizeof text, "%.1f cm", panel.depth_mm / 10);
    const ImVec2 size = ImGui::CalcTextSize(text);
    label(ImVec2(panel.x + panel.width - size.x - 6 * scale, panel.y + panel.height - size.y - 4 * scale), text);
    char settings[64];
    std::snprintf(settings, sizeof settings, "gain %+.0f dB   focus %.1f cm", scanner.gain_db, scanner.focus_mm / 10);
    const ImVec2 settings_size = ImGui::CalcTextSize(settings);
    label(ImVec2(panel.x + panel.width - settings_size.x - 6 * scale, panel.y + 4 * scale), settings);
    ImGui::PopFont();
    // the orientation marker: the probe's marker colour, ringed dark, clear of the ticks and labels
    const float r = 6 * scale;
    const ImVec2 dot(panel.x + 0.03f * panel.width + 28 * scale, panel.y + 12 * scale);
    const glm::vec3 c = scene::kMarkerColour;
    dl->AddCircleFilled(dot, r + 1.5f * scale, u32(shade));
    dl->AddCircleFilled(dot, r, u32(ImVec4(c.r, c.g, c.b, 1.0f)));
}

}  // namespace echosim::trainer
