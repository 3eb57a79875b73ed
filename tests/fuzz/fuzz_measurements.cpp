// Fuzz target: the measurements CSV (fit::read_measurements).
#include <cstddef>
#include <cstdint>

#include "fit/measurements.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::refusing<fit::MeasurementError>([&] { fit::read_measurements(fuzz::input_file(data, size, "measurements.csv")); });
    return 0;
}
