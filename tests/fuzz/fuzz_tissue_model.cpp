// Fuzz target: the tissue model JSON (tissue::read_tissue_model).
#include <cstddef>
#include <cstdint>

#include "tissue/tissue_json.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::refusing<tissue::ModelFileError>([&] { tissue::read_tissue_model(fuzz::input_file(data, size, "model.json")); });
    return 0;
}
