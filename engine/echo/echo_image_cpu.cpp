#include "echo/echo_image_cpu.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "echo/bmode.hpp"
#include "echo/deform_cpu.hpp"
#include "echo/kernel_params.hpp"
#include "echo/post_cpu.hpp"
#include "echo/slice_cpu.hpp"
#include "echo/tissue_mechanics.hpp"

namespace echosim::echo {

void check_volumes(const io::Volume& volume, const io::Volume* labels)
{
    if (volume.type != io::VoxelType::uint8)
        throw std::invalid_argument(std::string("volume: voxels are ") + io::to_string(volume.type) + ", the image pipeline reads unsigned char");
    if (volume.voxel_count() == 0) throw std::invalid_argument("volume: no voxels");
    if (!labels) return;
    if (labels->type != io::VoxelType::uint8)
        throw std::invalid_argument(std::string("labels: voxels are ") + io::to_string(labels->type) + ", tissue codes are unsigned char");
    bool same = labels->size == volume.size;
    for (int a = 0; a < 3 && same; ++a)
        for (int b = 0; b < 3; ++b) same = same && std::abs(labels->directions[a][b] - volume.directions[a][b]) < 1e-6;
    for (int a = 0; a < 3 && same; ++a) same = std::abs(labels->origin[a] - volume.origin[a]) < 1e-6;
    if (!same) throw std::invalid_argument("labels: not on the volume's grid (sizes, space directions and space origin must match)");
}

EchoImage render_echo_cpu(const io::Volume& volume, const io::Volume* labels, const ImagePlane& plane, const EchoFrame& frame,
                          const ScannerSettings& scanner, const PatientCase& patient, bool want_labels, Imaging imaging)
{
    check_volumes(volume, labels);
    if (imaging == Imaging::generative && !labels)
        throw std::invalid_argument("generative imaging needs the case's tissue labels, and this volume has none");
    KernelParams k = make_kernel_params(volume, plane, frame, scanner, patient, labels != nullptr);
    if (want_labels && labels) k.slice.flags |= SLICE_LABELS;
    EchoImage out;
    out.columns = plane.columns;
    out.rows = plane.rows;
    out.map_columns = k.deform.columns;
    if (!frame.columns.empty()) {
        const TissueTable tissues = labels ? tissue_mechanics(patient) : paper_linear_mechanics();
        const std::vector<glm::vec2> map = deform_cpu(labels, deform_profiles(frame, plane, k.deform.columns), tissues, k.deform);
        out.map.resize(2 * map.size());
        for (std::size_t i = 0; i < map.size(); ++i) out.map[2 * i] = map[i].x, out.map[2 * i + 1] = map[i].y;
    }
    SliceOutput sliced = slice_stage_cpu(volume, labels, out.map, k.slice);
    if (imaging == Imaging::generative) {
        // the live image in the slice's place, through the same post stage (the GPU's SLICE_GENERATED)
        const BModeImage live = synthesize_live(*labels, bmode_live_params(plane), k.slice, frame.face, out.map);
        for (std::size_t i = 0; i < sliced.grey.size(); ++i) sliced.grey[i] = float(live.pixels[i]);
        std::fill(sliced.gain.begin(), sliced.gain.end(), 0.0f);
    }
    out.rgba = post_cpu(sliced.grey, sliced.gain, k.post);
    out.grey = std::move(sliced.grey);
    out.labels = std::move(sliced.labels);
    return out;
}

}  // namespace echosim::echo
