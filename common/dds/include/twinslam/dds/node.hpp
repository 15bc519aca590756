#pragma once
// One DDS participant per service process, and the typed writers/readers it owns.
// A Node loads the QoS profile file before reading any QoS, creates every entity from a named profile of
// deploy/qos/twinslam.xml, and deletes everything in order in its destructor, which is what removes the process's
// shared-memory files from /dev/shm.
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "twinslam/dds/topics.hpp"
#include "twinslam/dds/types.hpp"

namespace eprosima::fastdds::dds {
class DomainParticipant;
class Publisher;
class Subscriber;
class Topic;
class DataWriter;
class DataReader;
}  // namespace eprosima::fastdds::dds

namespace twinslam::dds {

struct NodeConfig {
  std::string service;                                  // "ingest", "tracking", ... (participant name twinslam/<service>)
  std::string vehicle_id = "uav0";                      // vehicle this process belongs to; "" for shared services
  int domain = -1;                                      // -1: $TWINSLAM_DOMAIN, else 0
  std::string participant_profile = "twinslam.local";   // profile in the QoS file
  std::string qos_file;                                 // empty: $TWINSLAM_QOS_FILE, else the built-in default
  std::string security_dir;                             // secured profiles' files; empty: $TWINSLAM_SECURITY_DIR
  Replay replay = Replay::Lockstep;                     // QoS of sensor writers
  // DDS partitions of every writer and reader of this process, comma-separated, fnmatch patterns allowed ("uav[0-4]",
  // "*"); empty: $TWINSLAM_PARTITION, else the default partition. A fleet (issue 14) puts each vehicle's processes in
  // a partition of their own so its sensors never reach another vehicle's estimator, and the edge in "edge,*".
  std::string partition;
};

// Resolves the effective QoS file and domain as a Node would; exposed for tools and error messages.
std::string resolve_qos_file(const std::string& configured);
int resolve_domain(int configured);
// The partitions a Node with `configured` joins (as NodeConfig::partition says); empty: the default partition.
// UsageError for an empty name in the list (",uav0", "uav0,,uav1").
std::vector<std::string> resolve_partitions(const std::string& configured);

namespace detail {
using RawWriter = eprosima::fastdds::dds::DataWriter;
bool write(RawWriter* w, const void* sample);
int matched_readers(RawWriter* w);
bool wait_acknowledged(RawWriter* w, std::chrono::milliseconds timeout);
}  // namespace detail

// Non-owning handle; valid while its Node lives.
template <class T>
class Writer {
 public:
  Writer() = default;
  explicit Writer(detail::RawWriter* w) : w_(w) {}
  // False when the sample could not be written (e.g. a lockstep writer blocked past max_blocking_time).
  bool publish(const T& sample) const { return detail::write(w_, &sample); }
  int matched_readers() const { return detail::matched_readers(w_); }
  // Waits until every matched reliable reader has acknowledged every sample written so far.
  bool wait_acknowledged(std::chrono::milliseconds timeout) const { return detail::wait_acknowledged(w_, timeout); }
  bool valid() const { return w_ != nullptr; }

 private:
  detail::RawWriter* w_ = nullptr;
};

// Reader state shared with the application: how many writers are matched, and whether one was matched then lost.
struct ReaderStatus {
  std::atomic<int> matched_writers{0};
  std::atomic<bool> ever_matched{false};
  std::atomic<unsigned long long> received{0};
};

template <class T>
class CallbackListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  explicit CallbackListener(std::function<void(const T&)> cb) : cb_(std::move(cb)) {}
  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& s) override {
    status.matched_writers.store(s.current_count);
    if (s.current_count > 0) status.ever_matched.store(true);
  }
  ReaderStatus status;

 private:
  std::function<void(const T&)> cb_;
};

class Node {
 public:
  explicit Node(NodeConfig config);  // throws UsageError: unreadable QoS file, unknown profile, bad domain
  ~Node();
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  const NodeConfig& config() const { return config_; }
  // True when the participant profile enables DDS-Security (authentication, access control, encryption).
  bool secured() const { return secured_; }

  // Writer on `topic` with its family's profile (or `profile` if given).
  template <class T>
  Writer<T> writer(const TopicSpec& topic, std::string_view profile = {}) {
    return Writer<T>(make_writer(topic, type_support<T>(), profile.empty() ? writer_profile(topic.family, config_.replay)
                                                                           : profile));
  }

  // Calls `cb` for every sample received on `topic` (on a Fast DDS thread). The returned status lives as long as the Node.
  template <class T>
  const ReaderStatus& subscribe(const TopicSpec& topic, std::function<void(const T&)> cb, std::string_view profile = {}) {
    auto listener = std::make_unique<CallbackListener<T>>(std::move(cb));
    auto& status = listener->status;
    make_reader(topic, type_support<T>(), profile.empty() ? reader_profile(topic.family) : profile, std::move(listener));
    return status;
  }

  // Deletes every reader (waiting for running callbacks), so objects their callbacks use can be destroyed safely.
  // Writers stay usable. Idempotent.
  void close_readers();

  eprosima::fastdds::dds::DomainParticipant* participant() const { return participant_; }

 private:
  template <class T>
  eprosima::fastdds::dds::TypeSupport type_support() {
    return eprosima::fastdds::dds::TypeSupport(new typename PubSubTypeOf<T>::type());
  }
  eprosima::fastdds::dds::Topic* topic(const TopicSpec& spec, eprosima::fastdds::dds::TypeSupport type);
  detail::RawWriter* make_writer(const TopicSpec& spec, eprosima::fastdds::dds::TypeSupport type,
                                 std::string_view profile);
  void make_reader(const TopicSpec& spec, eprosima::fastdds::dds::TypeSupport type, std::string_view profile,
                   std::unique_ptr<eprosima::fastdds::dds::DataReaderListener> listener);

  NodeConfig config_;
  bool secured_ = false;
  std::mutex mutex_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::vector<eprosima::fastdds::dds::Topic*> topics_;
  // Listeners must outlive their readers: destroyed after delete_contained_entities().
  std::vector<std::unique_ptr<eprosima::fastdds::dds::DataReaderListener>> listeners_;
};

}  // namespace twinslam::dds

#include "twinslam/dds/node_impl.hpp"
