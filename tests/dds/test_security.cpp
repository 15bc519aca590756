// DDS-Security (issue 14 item 5) with the files of scripts/security/make-pki.sh, participants of one process on a
// private domain: the drone and the edge (their profiles twinslam.secure.drone / .edge) exchange Odometry, LocalMap
// and Registration; a participant without a certificate, one with a certificate whose permissions grant only
// Heartbeat, and one that forged its own "allow everything" permissions (signed by a CA of its own) neither read
// Odometry / LocalMap nor get a Registration to the drone for 10 s.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <thread>

#include "subprocess.hpp"
#include "text_file.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/dds/node.hpp"
#include "wait_for.hpp"

namespace twinslam::dds {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
  return s;
}

// A participant profile with absolute paths: the guest (a real identity, Heartbeat-only permissions) and the forger
// (the same identity, permissions and governance signed by its own CA, which it names as permissions CA).
std::string test_profile(const std::string& name, const fs::path& pki, const std::string& permissions_dir) {
  auto prop = [](const std::string& n, const std::string& v) {
    return "<property><name>" + n + "</name><value>" + v + "</value></property>\n";
  };
  const fs::path perm = pki / permissions_dir;
  return "<participant profile_name=\"" + name + "\"><rtps><propertiesPolicy><properties>\n" +
         prop("dds.sec.auth.plugin", "builtin.PKI-DH") +
         prop("dds.sec.auth.builtin.PKI-DH.identity_ca", "file://" + (pki / "ca.pem").string()) +
         prop("dds.sec.auth.builtin.PKI-DH.identity_certificate", "file://" + (pki / "guest/cert.pem").string()) +
         prop("dds.sec.auth.builtin.PKI-DH.private_key", "file://" + (pki / "guest/key.pem").string()) +
         prop("dds.sec.access.plugin", "builtin.Access-Permissions") +
         prop("dds.sec.access.builtin.Access-Permissions.permissions_ca", "file://" + (perm / "ca.pem").string()) +
         prop("dds.sec.access.builtin.Access-Permissions.governance", "file://" + (perm / "governance.p7s").string()) +
         prop("dds.sec.access.builtin.Access-Permissions.permissions",
              "file://" + (perm / "permissions.p7s").string()) +
         prop("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC") + "</properties></propertiesPolicy></rtps></participant>\n";
}

class DdsSecurity : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    pki_ = fs::temp_directory_path() / ("twinslam_pki_" + std::to_string(::getpid()));
    fs::remove_all(pki_);
    const auto made = test::run_process(
        {"/bin/bash", std::string(TWINSLAM_SOURCE_DIR) + "/scripts/security/make-pki.sh", pki_.string(), "guest"});
    ASSERT_EQ(made.exit_code, 0) << made.err;
    // The forger: its own CA signs a copy of the guest's grant that allows every topic, and the governance.
    fs::create_directories(pki_ / "forged");
    write_text(pki_ / "forged/permissions.xml",
               replace_all(test::read_text(pki_ / "guest/permissions.xml"), "twinslam/v1/heartbeat", "*"));
    const std::string forge =
        "cd '" + (pki_ / "forged").string() +
        "' && openssl ecparam -name prime256v1 -genkey -noout -out ca.key && openssl req -x509 -new -key ca.key "
        "-subj /CN=rogue -days 30 -out ca.pem && openssl smime -sign -text -in permissions.xml -out permissions.p7s "
        "-signer ca.pem -inkey ca.key && openssl smime -sign -text -in ../governance.xml -out governance.p7s "
        "-signer ca.pem -inkey ca.key";
    const auto forged = test::run_process({"/bin/bash", "-c", forge});
    ASSERT_EQ(forged.exit_code, 0) << forged.err;
    // One profile file for every participant of the process: the project's, plus the guest and the forger.
    std::string xml = test::read_text(std::string(TWINSLAM_SOURCE_DIR) + "/deploy/qos/twinslam.xml");
    const auto end = xml.find("</profiles>");
    ASSERT_NE(end, std::string::npos);
    xml.insert(end, test_profile("test.secure.guest", pki_, "") + test_profile("test.secure.forger", pki_, "forged"));
    // The guest's own permissions live in guest/, its CA and governance at the top.
    xml = replace_all(xml, "file://" + pki_.string() + "/permissions.p7s",
                      "file://" + pki_.string() + "/guest/permissions.p7s");
    qos_ = pki_ / "qos.xml";
    write_text(qos_, xml);
  }
  static void TearDownTestSuite() { fs::remove_all(pki_); }

  static NodeConfig config(const std::string& service, const std::string& profile, int domain) {
    NodeConfig c;
    c.service = service;
    c.domain = domain;
    c.participant_profile = profile;
    c.qos_file = qos_.string();
    c.security_dir = pki_.string();
    return c;
  }

  static inline fs::path pki_, qos_;
};

TEST_F(DdsSecurity, ASecuredProfileWithoutItsFilesIsRefusedNamingWhatIsMissing) {
  NodeConfig c = config("drone", "twinslam.secure.drone", test::test_domain());
  c.security_dir.clear();
  ::unsetenv("TWINSLAM_SECURITY_DIR");
  try {
    Node node(c);
    FAIL() << "a secured profile without a security directory was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("twinslam.secure.drone"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("TWINSLAM_SECURITY_DIR"), std::string::npos) << e.what();
  }
  c.security_dir = (pki_ / "nowhere").string();
  try {
    Node node(c);
    FAIL() << "a security directory without the files was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find((pki_ / "nowhere/ca.pem").string()), std::string::npos) << e.what();
  }
}

TEST_F(DdsSecurity, OnlyTheDroneAndTheEdgeReadEachOthersTopicsAndNoIntruderInjectsARegistration) {
  const int domain = test::test_domain();
  Node drone(config("estimator", "twinslam.secure.drone", domain));
  Node edge(config("registration", "twinslam.secure.edge", domain));
  Node plain(config("intruder", "twinslam.local", domain));
  Node guest(config("guest", "test.secure.guest", domain));
  Node forger(config("forger", "test.secure.forger", domain));
  EXPECT_TRUE(drone.secured() && edge.secured() && guest.secured() && forger.secured());
  EXPECT_FALSE(plain.secured());

  std::atomic<int> edge_odometry{0}, edge_maps{0}, stolen{0};
  std::mutex mutex;
  std::multiset<std::string> registration_senders;
  edge.subscribe<msg::Odometry>(topics::kOdometry, [&](const msg::Odometry&) { ++edge_odometry; });
  edge.subscribe<msg::LocalMap>(topics::kLocalMap, [&](const msg::LocalMap&) { ++edge_maps; });
  drone.subscribe<msg::Registration>(topics::kRegistration, [&](const msg::Registration& r) {
    std::lock_guard lock(mutex);
    registration_senders.insert(r.vehicle_id());
  });
  for (Node* intruder : {&plain, &forger}) {
    intruder->subscribe<msg::Odometry>(topics::kOdometry, [&](const msg::Odometry&) { ++stolen; });
    intruder->subscribe<msg::LocalMap>(topics::kLocalMap, [&](const msg::LocalMap&) { ++stolen; });
  }
  // The guest's own participant refuses what its permissions do not grant.
  EXPECT_ANY_THROW(guest.subscribe<msg::Odometry>(topics::kOdometry, [&](const msg::Odometry&) { ++stolen; }));
  EXPECT_ANY_THROW(guest.writer<msg::Registration>(topics::kRegistration));

  const auto odometry = drone.writer<msg::Odometry>(topics::kOdometry);
  const auto local_map = drone.writer<msg::LocalMap>(topics::kLocalMap);
  const auto from_edge = edge.writer<msg::Registration>(topics::kRegistration);
  const auto from_plain = plain.writer<msg::Registration>(topics::kRegistration);
  const auto from_forger = forger.writer<msg::Registration>(topics::kRegistration);
  const auto until = std::chrono::steady_clock::now() + 10s;
  for (long long seq = 0; std::chrono::steady_clock::now() < until; ++seq) {
    msg::Odometry o;
    o.vehicle_id("uav0");
    o.seq(seq);
    odometry.publish(o);
    msg::LocalMap m;
    m.vehicle_id("uav0");
    m.seq(seq);
    m.landmarks().resize(50);
    local_map.publish(m);
    for (auto [w, who] : {std::pair{&from_edge, "edge"}, {&from_plain, "plain"}, {&from_forger, "forger"}}) {
      msg::Registration r;
      r.vehicle_id(who);
      r.seq(seq);
      w->publish(r);
    }
    std::this_thread::sleep_for(100ms);
  }
  std::this_thread::sleep_for(300ms);
  EXPECT_GT(edge_odometry.load(), 20) << "the edge must read the drone's Odometry (security must not stop it)";
  EXPECT_GT(edge_maps.load(), 20);
  std::lock_guard lock(mutex);
  EXPECT_GT(registration_senders.count("edge"), 20u);
  EXPECT_EQ(registration_senders.count("plain"), 0u) << "a participant without a certificate injected a Registration";
  EXPECT_EQ(registration_senders.count("forger"), 0u) << "forged permissions injected a Registration";
  EXPECT_EQ(stolen.load(), 0) << "an intruder read Odometry or LocalMap";
  EXPECT_EQ(from_plain.matched_readers(), 0);
  EXPECT_EQ(from_forger.matched_readers(), 0);
}

}  // namespace
}  // namespace twinslam::dds
