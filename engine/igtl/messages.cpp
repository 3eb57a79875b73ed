#include "igtl/messages.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <igtlImageMessage.h>
#include <igtlTimeStamp.h>
#include <igtlTransformMessage.h>

namespace echosim::igtl {
namespace {

// glm is column-major (m[column][row]); igtl::Matrix4x4 is float[row][column]
void to_igtl(const glm::dmat4& m, ::igtl::Matrix4x4& out)
{
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out[r][c] = float(m[c][r]);
}

void append(std::vector<std::byte>& out, ::igtl::MessageBase& message)
{
    const auto* bytes = static_cast<const std::byte*>(message.GetPackPointer());
    out.insert(out.end(), bytes, bytes + message.GetPackSize());
}

void append_transform(std::vector<std::byte>& out, const char* name, const glm::dmat4& to_reference, ::igtl::TimeStamp::Pointer& time)
{
    ::igtl::TransformMessage::Pointer message = ::igtl::TransformMessage::New();
    message->SetDeviceName(name);
    message->SetTimeStamp(time);
    ::igtl::Matrix4x4 m;
    to_igtl(to_reference, m);
    message->SetMatrix(m);
    message->Pack();
    append(out, *message);
}

}  // namespace

void check_frame(const LiveFrame& f)
{
    constexpr auto kMaxSide = std::uint32_t(std::numeric_limits<std::int16_t>::max());  // the IMAGE header's sizes are 16-bit
    if (f.columns == 0 || f.rows == 0 || f.columns > kMaxSide || f.rows > kMaxSide)
        throw std::invalid_argument("live frame: " + std::to_string(f.columns) + " x " + std::to_string(f.rows) + " pixels, outside 1..32767 a side");
    if (f.pixels.size() != std::size_t(f.columns) * f.rows)
        throw std::invalid_argument("live frame: " + std::to_string(f.pixels.size()) + " pixels for " + std::to_string(f.columns) + " x " +
                                    std::to_string(f.rows));
    for (int a = 0; a < 3; ++a) {
        const double length = glm::length(glm::dvec3(f.image_to_world[a]));
        if (!std::isfinite(length) || length <= 0)
            throw std::invalid_argument("live frame: image_to_world's axis " + std::to_string(a) + " has no length");
    }
}

std::vector<std::byte> pack_frame(const LiveFrame& f)
{
    check_frame(f);
    const glm::dmat4 image_to_reference = reference_from_world() * f.image_to_world;
    const glm::dmat4 probe_to_reference = reference_from_world() * f.probe_to_world;
    ::igtl::TimeStamp::Pointer time = ::igtl::TimeStamp::New();
    time->SetTime(f.timestamp_s);

    // IMAGE: unit pixel axes and the spacing apart, the translation at the centre of the pixel grid
    // (live_frame.hpp: what Slicer's OpenIGTLinkIF expects)
    float spacing[3];
    glm::dmat4 placement(1.0);
    for (int a = 0; a < 3; ++a) {
        const glm::dvec3 axis(image_to_reference[a]);
        spacing[a] = float(glm::length(axis));
        placement[a] = glm::dvec4(axis / glm::length(axis), 0.0);
    }
    placement[3] = image_to_reference * glm::dvec4(0.5 * (f.columns - 1.0), 0.5 * (f.rows - 1.0), 0.0, 1.0);
    ::igtl::ImageMessage::Pointer image = ::igtl::ImageMessage::New();
    image->SetDeviceName(kImageName);
    image->SetTimeStamp(time);
    image->SetDimensions(int(f.columns), int(f.rows), 1);
    image->SetSpacing(spacing);
    image->SetScalarTypeToUint8();
    image->SetCoordinateSystem(::igtl::ImageMessage::COORDINATE_RAS);
    ::igtl::Matrix4x4 m;
    to_igtl(placement, m);
    image->SetMatrix(m);
    image->AllocateScalars();
    std::memcpy(image->GetScalarPointer(), f.pixels.data(), f.pixels.size());
    image->Pack();

    std::vector<std::byte> out;
    out.reserve(std::size_t(image->GetPackSize()) + 2 * 128);
    append(out, *image);
    append_transform(out, kProbeToReferenceName, probe_to_reference, time);
    append_transform(out, kImageToReferenceName, image_to_reference, time);
    return out;
}

}  // namespace echosim::igtl
