#include "twinslam/dds/node.hpp"

#include <cstdlib>
#include <filesystem>
#include <set>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/PublisherQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/SubscriberQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include "twinslam/core/error.hpp"
#include "twinslam/dds/fastdds_log.hpp"

#include "security.hpp"

namespace twinslam::dds {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

std::string resolve_qos_file(const std::string& configured) {
  if (!configured.empty()) return configured;
  if (const char* env = std::getenv("TWINSLAM_QOS_FILE"); env != nullptr && *env != '\0') return env;
  return TWINSLAM_DEFAULT_QOS_FILE;
}

int resolve_domain(int configured) {
  int domain = configured;
  if (domain < 0) {
    const char* env = std::getenv("TWINSLAM_DOMAIN");
    domain = 0;
    if (env != nullptr && *env != '\0') {
      char* end = nullptr;
      const long v = std::strtol(env, &end, 10);
      if (end == env || *end != '\0') throw UsageError(std::string("TWINSLAM_DOMAIN is not an integer: '") + env + "'");
      domain = static_cast<int>(v);
    }
  }
  // Fast DDS maps the domain to UDP ports 7400 + 250 * domain; above 232 the ports overflow 65535.
  if (domain < 0 || domain > 232) throw UsageError("DDS domain " + std::to_string(domain) + " is outside 0..232");
  return domain;
}

std::vector<std::string> resolve_partitions(const std::string& configured) {
  std::string text = configured;
  const char* source = "partition";
  if (text.empty()) {
    const char* env = std::getenv("TWINSLAM_PARTITION");
    if (env == nullptr || *env == '\0') return {};
    text = env;
    source = "TWINSLAM_PARTITION";
  }
  std::vector<std::string> names;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = text.find(',', begin);
    std::string name = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    if (name.empty()) throw UsageError(std::string(source) + " '" + text + "': an empty partition name in the list");
    names.push_back(std::move(name));
    if (comma == std::string::npos) return names;
    begin = comma + 1;
  }
}

namespace {
// Each file is loaded once per process: several nodes may share a process (tests, `twinslam run`).
void load_profiles_once(const std::string& file) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::lock_guard lock(mutex);
  if (loaded.count(file) != 0) return;
  if (!std::filesystem::is_regular_file(file)) throw UsageError(file + ": QoS profile file not found");
  route_fastdds_log();
  if (fdds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(file) != ReturnCode_t::RETCODE_OK) {
    throw UsageError(file + ": not a valid Fast DDS XML profile file");
  }
  loaded.insert(file);
}
}  // namespace

namespace detail {
bool write(RawWriter* w, const void* sample) { return w->write(const_cast<void*>(sample)); }

int matched_readers(RawWriter* w) {
  fdds::PublicationMatchedStatus status;
  w->get_publication_matched_status(status);
  return status.current_count;
}

bool wait_acknowledged(RawWriter* w, std::chrono::milliseconds timeout) {
  const auto ms = timeout.count();
  return w->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(static_cast<int32_t>(ms / 1000),
                                                                    static_cast<uint32_t>((ms % 1000) * 1000000))) ==
         ReturnCode_t::RETCODE_OK;
}
}  // namespace detail

Node::Node(NodeConfig config) : config_(std::move(config)) {
  const std::string qos_file = resolve_qos_file(config_.qos_file);
  load_profiles_once(qos_file);
  const int domain = resolve_domain(config_.domain);
  const std::vector<std::string> partitions = resolve_partitions(config_.partition);  // refused before any entity
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile(config_.participant_profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw UsageError(qos_file + ": no participant profile named '" + config_.participant_profile + "'");
  }
  secured_ = detail::resolve_security_files(qos, config_.participant_profile, config_.security_dir);
  qos.name("twinslam/" + config_.service);
  participant_ = factory->create_participant(domain, qos);
  if (participant_ == nullptr) {
    // A secured participant fails here when its certificate, key or signed documents do not verify (Fast DDS logs
    // the reason at error level, which route_fastdds_log shows).
    throw std::runtime_error("cannot create DDS participant in domain " + std::to_string(domain) +
                             (secured_ ? " with the DDS-Security files of profile '" + config_.participant_profile +
                                             "' (see the Fast DDS error above)"
                                       : std::string()));
  }
  // Partitions are a publisher / subscriber QoS: one of each per process, so every topic of it shares them.
  fdds::PublisherQos pub_qos = fdds::PUBLISHER_QOS_DEFAULT;
  fdds::SubscriberQos sub_qos = fdds::SUBSCRIBER_QOS_DEFAULT;
  for (const std::string& name : partitions) {
    pub_qos.partition().push_back(name.c_str());
    sub_qos.partition().push_back(name.c_str());
  }
  publisher_ = participant_->create_publisher(pub_qos);
  subscriber_ = participant_->create_subscriber(sub_qos);
  if (publisher_ == nullptr || subscriber_ == nullptr) throw std::runtime_error("cannot create DDS publisher/subscriber");
}

Node::~Node() {
  if (participant_ != nullptr) {
    // Readers first (their listeners stop), then everything else; deleting the participant releases its
    // shared-memory segments and ports.
    participant_->delete_contained_entities();
    fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  listeners_.clear();
}

void Node::close_readers() {
  std::lock_guard lock(mutex_);
  if (subscriber_ != nullptr) subscriber_->delete_contained_entities();
}

fdds::Topic* Node::topic(const TopicSpec& spec, fdds::TypeSupport type) {
  for (auto* t : topics_) {
    if (t->get_name() == spec.name) return t;
  }
  if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("cannot register DDS type " + std::string(spec.type_name));
  }
  auto* t = participant_->create_topic(std::string(spec.name), type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (t == nullptr) throw std::runtime_error("cannot create DDS topic " + std::string(spec.name));
  topics_.push_back(t);
  return t;
}

detail::RawWriter* Node::make_writer(const TopicSpec& spec, fdds::TypeSupport type, std::string_view profile) {
  std::lock_guard lock(mutex_);
  auto* t = topic(spec, type);
  fdds::DataWriterQos qos;
  if (publisher_->get_datawriter_qos_from_profile(std::string(profile), qos) != ReturnCode_t::RETCODE_OK) {
    throw UsageError("no data_writer QoS profile named '" + std::string(profile) + "'");
  }
  auto* w = publisher_->create_datawriter(t, qos);
  if (w == nullptr) throw std::runtime_error("cannot create DDS writer on " + std::string(spec.name));
  return w;
}

void Node::make_reader(const TopicSpec& spec, fdds::TypeSupport type, std::string_view profile,
                       std::unique_ptr<fdds::DataReaderListener> listener) {
  std::lock_guard lock(mutex_);
  auto* t = topic(spec, type);
  fdds::DataReaderQos qos;
  if (subscriber_->get_datareader_qos_from_profile(std::string(profile), qos) != ReturnCode_t::RETCODE_OK) {
    throw UsageError("no data_reader QoS profile named '" + std::string(profile) + "'");
  }
  auto* r = subscriber_->create_datareader(t, qos, listener.get());
  if (r == nullptr) throw std::runtime_error("cannot create DDS reader on " + std::string(spec.name));
  listeners_.push_back(std::move(listener));
}

}  // namespace twinslam::dds
