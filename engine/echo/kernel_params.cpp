#include "echo/kernel_params.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/matrix.hpp>

#include "echo/bmode.hpp"

namespace echosim::echo {

void check_plane(const ImagePlane& p)
{
    const auto bad = [](const char* field, const std::string& why) { throw std::invalid_argument(std::string("image ") + field + " " + why); };
    if (!(p.width_mm > 0 && p.width_mm <= 200)) bad("width", std::to_string(p.width_mm) + " mm: must be in (0, 200]");
    if (!(p.depth_mm > 0 && p.depth_mm <= 300)) bad("depth", std::to_string(p.depth_mm) + " mm: must be in (0, 300]");
    if (p.columns < 2 || p.columns > kMaxImageSide) bad("columns", std::to_string(p.columns) + ": must be in 2.." + std::to_string(kMaxImageSide));
    if (p.rows < 2 || p.rows > kMaxImageSide) bad("rows", std::to_string(p.rows) + ": must be in 2.." + std::to_string(kMaxImageSide));
    if (p.pixels() > kMaxImagePixels)
        bad("size", std::to_string(p.columns) + "x" + std::to_string(p.rows) + ": more than 7680x4320 pixels");
}

const char* imaging_name(Imaging imaging) { return imaging == Imaging::generative ? "generative" : "interpolative"; }

Imaging parse_imaging(const std::string& name)
{
    if (name == "interpolative") return Imaging::interpolative;
    if (name == "generative") return Imaging::generative;
    throw std::invalid_argument("imaging \"" + name + "\": must be interpolative or generative");
}

ImagePlane plane_with_pixel(double width_mm, double depth_mm, double pixel_mm)
{
    if (!(pixel_mm > 0)) throw std::invalid_argument("image pixel " + std::to_string(pixel_mm) + " mm: must be > 0");
    const double c = std::round(width_mm / pixel_mm), r = std::round(depth_mm / pixel_mm);
    if (!(c <= kMaxImageSide && r <= kMaxImageSide))
        throw std::invalid_argument("image pixel " + std::to_string(pixel_mm) + " mm: too many pixels for " + std::to_string(width_mm) + " x " +
                                    std::to_string(depth_mm) + " mm");
    ImagePlane p{width_mm, depth_mm, std::uint32_t(std::max(c, 2.0)), std::uint32_t(std::max(r, 2.0))};
    check_plane(p);
    return p;
}

glm::dmat4 pixel_to_world(const ImagePlane& plane, const Pose& face)
{
    const glm::dvec3 ax(face.axis_x()), ay(face.axis_y()), az(face.axis_z());
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(ax * plane.pixel_x_mm(), 0.0);
    m[1] = glm::dvec4(ay * plane.pixel_y_mm(), 0.0);
    m[2] = glm::dvec4(az, 0.0);
    m[3] = glm::dvec4(glm::dvec3(face.position) + ax * (0.5 * plane.pixel_x_mm() - 0.5 * plane.width_mm) + ay * (0.5 * plane.pixel_y_mm()), 1.0);
    return m;
}

double pulse_at(double time_s, double heart_rate_bpm)
{
    if (!(heart_rate_bpm > 0)) return 0;
    const double phase = time_s * heart_rate_bpm / 60.0;
    const double f = phase - std::floor(phase);
    constexpr double systole = 0.35;
    if (f >= systole) return 0;
    const double s = std::sin(std::numbers::pi * f / systole);
    return s * s;
}

double deform_step_mm(const io::Volume& grid, const ImagePlane& plane)
{
    return std::max({plane.pixel_y_mm(), grid.finest_spacing_mm(), kDeformResolutionMm});
}

float map_step(std::uint32_t map_columns, const ImagePlane& plane)
{
    return float(double(map_columns) / double(plane.columns));  // 1 exactly when the map is as fine
}

std::uint32_t deform_columns(const io::Volume& grid, const ImagePlane& plane)
{
    const double across = std::ceil(plane.width_mm / std::max(grid.finest_spacing_mm(), kDeformResolutionMm));
    return std::max(1u, std::uint32_t(std::min(double(plane.columns), across)));
}

std::vector<ColumnProfile> deform_profiles(const EchoFrame& frame, const ImagePlane& plane, std::uint32_t columns)
{
    if (frame.columns.empty()) return {};
    if (frame.columns.size() != plane.columns)
        throw std::invalid_argument("echographic image: " + std::to_string(frame.columns.size()) + " column profiles for " +
                                    std::to_string(plane.columns) + " columns");
    if (columns == plane.columns) return frame.columns;
    std::vector<ColumnProfile> out(columns);
    const double last = double(plane.columns - 1);
    for (std::uint32_t j = 0; j < columns; ++j) {
        // deform column j's centre in image columns (both span the same width)
        const double u = std::clamp((j + 0.5) * double(plane.columns) / columns - 0.5, 0.0, last);
        const auto left = std::size_t(u);
        const std::size_t right = std::min(left + 1, std::size_t(plane.columns - 1));
        const double f = u - double(left);
        const ColumnProfile& a = frame.columns[left];
        const ColumnProfile& b = frame.columns[right];
        out[j].skin_y_mm = float((1 - f) * a.skin_y_mm + f * b.skin_y_mm);
        out[j].skin_shift_mm = float((1 - f) * a.skin_shift_mm + f * b.skin_shift_mm);
    }
    return out;
}

std::uint32_t deform_max_steps(const io::Volume& grid, const ImagePlane& plane)
{
    return std::uint32_t(std::ceil((plane.depth_mm + kMaxSkinAboveFaceMm) / deform_step_mm(grid, plane)));
}

KernelParams make_kernel_params(const io::Volume& grid, const ImagePlane& plane, const EchoFrame& frame, const ScannerSettings& scanner,
                                const PatientCase& patient, bool labelled)
{
    check_plane(plane);
    glm::dmat4 index_to_world(grid.directions);
    index_to_world[3] = glm::dvec4(grid.origin, 1.0);
    const glm::mat4 probe_to_index(glm::inverse(index_to_world) * glm::dmat4(frame.face.matrix()));
    const bool warped = !frame.columns.empty();
    const auto px = float(plane.pixel_x_mm()), py = float(plane.pixel_y_mm());
    const std::uint32_t map_columns = deform_columns(grid, plane);
    const auto map_px = float(plane.width_mm / map_columns);
    const float step = map_step(map_columns, plane);

    KernelParams k{};
    k.deform = {probe_to_index,
                map_columns,
                plane.rows,
                map_px,
                py,
                float(plane.width_mm),
                float(plane.depth_mm),
                float(frame.skin_pressure_kpa),
                float(pulse_at(frame.time_s, patient.heart_rate_bpm)),
                float(kLinearProbe.face_width_mm),
                float(kLinearProbe.face_thickness_mm),
                float(deform_step_mm(grid, plane)),
                deform_max_steps(grid, plane),
                float(ScanSpec{}.tgc_db_per_cm_mhz),  // the time-gain compensation the volume was made with
                float(kLinearProbe.frequency_mhz),
                labelled ? 0u : DEFORM_PAPER_LINEAR};
    k.slice = {probe_to_index,
               plane.columns,
               plane.rows,
               px,
               py,
               float(plane.width_mm),
               warped ? kernels::slice_warped_flags(step) : 0u,
               map_columns,
               step,
               std::uint32_t(grid.size[0]),
               std::uint32_t(grid.size[1]),
               std::uint32_t(grid.size[2]),
               kernels::packed_fold_bits(std::uint32_t(grid.size[0]))};
    k.post.columns = plane.columns;
    k.post.rows = plane.rows;
    k.post.pixel_x_mm = px;
    k.post.pixel_y_mm = py;
    k.post.depth_mm = float(plane.depth_mm);
    k.post.volume_dynamic_range_db = float(scanner.volume_dynamic_range_db);
    k.post.gain_db = float(scanner.gain_db);
    k.post.dynamic_range_db = float(scanner.dynamic_range_db);
    k.post.focus_mm = float(scanner.focus_mm);
    k.post.flags = (warped ? POST_WARPED : 0u) | (scanner.markers ? POST_MARKERS : 0u);
    k.post.tgc_near = {scanner.tgc_db[0], scanner.tgc_db[1], scanner.tgc_db[2], scanner.tgc_db[3]};
    k.post.tgc_far = {scanner.tgc_db[4], scanner.tgc_db[5], scanner.tgc_db[6], scanner.tgc_db[7]};
    return k;
}

}  // namespace echosim::echo
