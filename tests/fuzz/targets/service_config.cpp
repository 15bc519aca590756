// The services' --config YAML files (the whole file: the node section and the library's) (ingest, tracking, estimator, tiles, registration) and the GNSS receiver's;
// the first byte picks the module.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include <string>
#include "estimator_config.hpp"
#include "twinslam/gnss/receiver_config.hpp"
#include "twinslam/ingest/ingest_config.hpp"
#include "twinslam/registration/registration_config.hpp"
#include "twinslam/tiles/tiles_config.hpp"
#include "tracking_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  return fuzz::expect_input_error_only([&] {
    switch (data[0] % 6) {
      case 0: ingest::parse_ingest_config(text, "ingest.yaml"); break;
      case 1: tracking::parse_tracking_config(text, "tracking.yaml"); break;
      case 2: estimator::parse_estimator_service_config(text, "estimator.yaml"); break;
      case 3: tiles::parse_tiles_config(text, "tiles.yaml"); break;
      case 4: registration::parse_registration_config(text, "registration.yaml"); break;
      default: gnss::load_receiver_config(fuzz::write_scratch("receiver.yaml", text).string()); break;
    }
  });
}
