// twinslam-registration: aligns each vehicle's local map to the digital twin (point-to-plane ICP, paper eqs. 2-10).
#include "registration_node.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/dds/service_main.hpp"

int main(int argc, char** argv) {
  namespace dds = twinslam::dds;
  namespace reg = twinslam::registration;
  CLI::App app{"twinslam registration service: aligns each vehicle's local map to the digital twin"};
  dds::ServiceOptions service;
  dds::add_service_options(app, service);
  std::string config_file, weights;
  reg::RegistrationNodeOptions options;
  app.add_option("--config", config_file, "Registration config YAML (deploy/config/registration.yaml lists every key)");
  app.add_option("--weights", weights, "Information weighting: paper | adaptive | fixed (wins over --config)")
      ->check(CLI::IsMember({"paper", "adaptive", "fixed"}));
  app.add_option("--tile-size", options.tile_size_m, "Side of the twin store's tiles [m]")->capture_default_str();
  app.add_option("--window", options.window_m, "Square window of twin around each vehicle [m]")->capture_default_str();
  app.add_option("--prefetch", options.prefetch_m, "Ring around the window whose tiles are indexed ahead [m]")
      ->capture_default_str();
  app.add_option("--keep", options.keep_m, "Indexed tiles are dropped only this far beyond the ring [m]")
      ->capture_default_str();
  return dds::service_main("registration", app, service, argc, argv, [&] {
    if (!config_file.empty()) options.registration = reg::load_registration_config(config_file);
    if (weights == "paper") options.registration.weights = reg::WeightMode::kPaper;
    if (weights == "adaptive") options.registration.weights = reg::WeightMode::kAdaptive;
    if (weights == "fixed") options.registration.weights = reg::WeightMode::kFixed;
    options.registration.validate(config_file.empty() ? "command line" : config_file);
    if (!(options.tile_size_m > 0.0) || !(options.window_m > 0.0) || !(options.prefetch_m >= 0.0) ||
        !(options.keep_m >= 0.0)) {
      throw twinslam::UsageError("--tile-size and --window must be > 0, --prefetch and --keep >= 0");
    }
    dds::Node node(service.node);
    dds::Counters counters;
    dds::HeartbeatPublisher heartbeat(node, counters);
    reg::RegistrationNode registration(node, counters, options);
    return dds::serve_until_shutdown(heartbeat, node);
  });
}
