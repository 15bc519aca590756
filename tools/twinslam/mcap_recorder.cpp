#include "mcap_recorder.hpp"

#include <twinslam/IdlText.h>

#include "twinslam/core/wall_clock.hpp"
#include "twinslam/mcap/writer.hpp"

namespace twinslam::cli {

McapRecorder::McapRecorder(const std::string& path) : path_(path), writer_(std::make_unique<mcap::Writer>(path)) {
  std::map<std::string_view, std::uint16_t> schemas;  // by type name: several topics may share a type
  for (const dds::TopicSpec& t : dds::topics::kAll) {
    auto it = schemas.find(t.type_name);
    if (it == schemas.end()) {
      it = schemas.emplace(t.type_name, writer_->add_schema(std::string(t.type_name), "omgidl",
                                                            std::string(msg::kIdlText)))
               .first;
    }
    channels_[t.name].id = writer_->add_channel(it->second, std::string(t.name), "cdr");
  }
}

McapRecorder::~McapRecorder() = default;  // the Writer closes the file if close() was not called

void McapRecorder::write(Channel& c, const std::uint8_t* data, std::size_t size) {
  const std::uint64_t log_time_ns = unix_time_ns();
  writer_->write(c.id, c.sequence++, log_time_ns, log_time_ns, data, size);
  ++c.count;
}

void McapRecorder::record(const dds::TopicSpec& topic, const std::vector<std::uint8_t>& cdr) {
  std::lock_guard lock(mutex_);
  if (closed_) return;
  const auto it = channels_.find(topic.name);
  if (it == channels_.end()) return;  // not a topic of the table: nothing to record it as
  write(it->second, cdr.data(), cdr.size());
}

void McapRecorder::record(const std::vector<foxglove::DerivedMessage>& well_known) {
  std::lock_guard lock(mutex_);
  if (closed_) return;
  for (const foxglove::DerivedMessage& d : well_known) {
    auto it = json_channels_.find(d.topic);
    if (it == json_channels_.end()) {
      auto schema = json_schemas_.find(d.schema->name);
      if (schema == json_schemas_.end()) {
        schema = json_schemas_.emplace(d.schema->name, writer_->add_schema(std::string(d.schema->name), "jsonschema",
                                                                           std::string(d.schema->jsonschema)))
                     .first;
      }
      it = json_channels_.emplace(d.topic, Channel{}).first;
      it->second.id = writer_->add_channel(schema->second, d.topic, "json");
    }
    write(it->second, reinterpret_cast<const std::uint8_t*>(d.json.data()), d.json.size());
  }
}

void McapRecorder::close() {
  std::lock_guard lock(mutex_);
  if (closed_) return;
  closed_ = true;
  writer_->close();
}

std::map<std::string, std::uint64_t> McapRecorder::counts() const {
  std::lock_guard lock(mutex_);
  std::map<std::string, std::uint64_t> out;
  for (const auto& [name, c] : channels_) out[std::string(name)] = c.count;
  for (const auto& [name, c] : json_channels_) out[name] = c.count;
  return out;
}

}  // namespace twinslam::cli
