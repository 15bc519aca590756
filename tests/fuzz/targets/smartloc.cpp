// smartLoc urban GNSS text (pseudorange3 / point3 lines); the first byte picks pseudoranges or ground truth.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "twinslam/gnss/smartloc.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  if (size == 0) return 0;
  const auto path = fuzz::write_scratch("smartloc.txt", data + 1, size - 1).string();
  return fuzz::expect_input_error_only([&] {
    if (data[0] % 2 == 0) gnss::read_smartloc_pseudoranges(path);
    else gnss::read_smartloc_ground_truth(path);
  });
}
