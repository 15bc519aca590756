#include "registration_node.hpp"

namespace twinslam::registration {

void wire_registration_inputs(dds::Node& node, dds::Counters& counters) {
  node.subscribe<msg::LocalMap>(dds::topics::kLocalMap, [&counters](const msg::LocalMap&) { counters.add("local_maps_in"); });
  node.subscribe<msg::MapTile>(dds::topics::kMapTile, [&counters](const msg::MapTile&) { counters.add("tiles_in"); });
}

}  // namespace twinslam::registration
