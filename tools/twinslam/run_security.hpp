#pragma once
// DDS-Security for `twinslam run --secure` (issue 14 item 5): the role, and so the participant profile, of each
// process of a run, and the security files, made on first use by scripts/security/make-pki.sh.
#include <filesystem>
#include <string>

namespace twinslam::cli {

// drone (ingest, tracking, estimator), edge (tiles, registration) or ops (the run's recorder, the bridge): what the
// role may publish is in make-pki.sh's permissions. Throws UsageError for a process without a role.
std::string security_role(const std::string& service);

// "twinslam.secure.<role>" (deploy/qos/twinslam.xml).
std::string secure_profile(const std::string& service);

// The security directory: `configured`, else $TWINSLAM_SECURITY_DIR, else $XDG_STATE_HOME/twinslam/pki (default
// ~/.local/state). Makes the CA, identities and signed documents there when its CA is absent; UsageError naming the
// directory when that fails.
std::filesystem::path ensure_security_files(const std::string& configured, bool quiet);

}  // namespace twinslam::cli
