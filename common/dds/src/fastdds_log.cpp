#include "twinslam/dds/fastdds_log.hpp"

#include <memory>
#include <mutex>

#include <fastdds/dds/log/Log.hpp>
#include <spdlog/spdlog.h>

namespace twinslam::dds {
namespace {
namespace fdds = eprosima::fastdds::dds;

class SpdlogConsumer : public fdds::LogConsumer {
 public:
  void Consume(const fdds::Log::Entry& entry) override {
    const auto level = entry.kind == fdds::Log::Kind::Error ? spdlog::level::err
                       : entry.kind == fdds::Log::Kind::Warning ? spdlog::level::warn
                                                                : spdlog::level::info;
    spdlog::log(level, "fastdds [{}] {}", entry.context.category == nullptr ? "" : entry.context.category,
                entry.message);
  }
};
}  // namespace

void route_fastdds_log() {
  static std::once_flag once;
  std::call_once(once, [] {
    fdds::Log::ClearConsumers();
    fdds::Log::RegisterConsumer(std::make_unique<SpdlogConsumer>());
    // Fast DDS warnings are mostly benign protocol chatter (e.g. DATA_FRAG from a writer not yet discovered, which
    // reliability repairs): shown only at --log-level debug or lower.
    fdds::Log::SetVerbosity(spdlog::get_level() <= spdlog::level::debug ? fdds::Log::Kind::Warning
                                                                        : fdds::Log::Kind::Error);
  });
}

}  // namespace twinslam::dds
