// OSM XML through libosmium: nodes with valid locations, every way's node list, building multipolygon relations.
#include "osm_read.hpp"

#include <osmium/handler.hpp>
#include <osmium/io/xml_input.hpp>
#include <osmium/visitor.hpp>

#include "twinslam/core/error.hpp"

namespace twinslam::twin {
namespace {

std::map<std::string, std::string> tags_of(const osmium::TagList& tags) {
  std::map<std::string, std::string> out;
  for (const osmium::Tag& t : tags) out.emplace(t.key(), t.value());
  return out;
}

class Collector : public osmium::handler::Handler {
 public:
  explicit Collector(OsmData& data) : data_(data) {}
  void node(const osmium::Node& n) {
    if (n.location().valid()) data_.nodes[n.id()] = {n.location().lat(), n.location().lon()};
  }
  void way(const osmium::Way& w) {
    OsmWay way;
    way.id = w.id();
    for (const osmium::NodeRef& r : w.nodes()) way.refs.push_back(r.ref());
    if (w.tags().has_key("building")) way.tags = tags_of(w.tags());
    data_.ways.push_back(std::move(way));
  }
  void relation(const osmium::Relation& r) {
    if (!r.tags().has_tag("type", "multipolygon") || !r.tags().has_key("building")) return;
    OsmRelation rel;
    rel.id = r.id();
    rel.tags = tags_of(r.tags());
    for (const osmium::RelationMember& m : r.members())
      if (m.type() == osmium::item_type::way) rel.ways.push_back({m.ref(), m.role()});
    data_.building_relations.push_back(std::move(rel));
  }

 private:
  OsmData& data_;
};

}  // namespace

OsmData read_osm_xml(const std::string& path) {
  OsmData data;
  try {
    osmium::io::Reader reader{osmium::io::File{path, "osm"}};
    Collector collector(data);
    osmium::apply(reader, collector);
    reader.close();
  } catch (const osmium::xml_error& e) {
    throw InputError(where(path, e.line, "OSM XML error: " + e.error_string));
  } catch (const std::exception& e) {  // io_error, format_version_error, system errors: all one-line messages
    std::string what = e.what();
    for (char& c : what)
      if (c == '\n') c = ' ';
    throw InputError(where(path, 0, "cannot read OSM XML: " + what));
  }
  return data;
}

}  // namespace twinslam::twin
