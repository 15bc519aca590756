#pragma once
// DDS-Security for a Node: the secured participant profiles of deploy/qos/twinslam.xml name their files relative to
// a security directory (made by scripts/security/make-pki.sh); this resolves them. Private to twinslam_dds.
#include <string>

namespace eprosima::fastdds::dds {
class DomainParticipantQos;
}

namespace twinslam::dds::detail {

// True when `qos` (read from `profile`) configures a DDS-Security plugin (a `dds.sec.*.plugin` property). Then each
// relative `file://PATH` property value is rewritten to `file://<dir>/PATH` with dir = `configured_dir`, else
// $TWINSLAM_SECURITY_DIR; UsageError when neither is set or a named file is missing (file and profile named).
bool resolve_security_files(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::string& profile,
                            const std::string& configured_dir);

}  // namespace twinslam::dds::detail
