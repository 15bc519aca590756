#include "twinslam/core/log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "twinslam/core/error.hpp"

namespace twinslam {

void init_logging(const std::string& level) {
  const auto lvl = spdlog::level::from_str(level);
  if (lvl == spdlog::level::off && level != "off") throw UsageError("unknown log level '" + level + "'");
  auto logger = spdlog::stderr_color_mt("twinslam");
  spdlog::set_default_logger(logger);
  spdlog::set_level(lvl);
  spdlog::set_pattern("%H:%M:%S.%e %^%l%$ %v");
}

}  // namespace twinslam
