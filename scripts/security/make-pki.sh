#!/usr/bin/env bash
# Makes the DDS-Security files of a twinslam deployment (OMG DDS-Security 1.1, Fast DDS builtin plugins):
#   DIR/ca.pem, DIR/ca.key        one CA (ECDSA P-256) that signs the identities and the governance/permissions
#   DIR/governance.p7s            every domain: authenticated participants only, discovery and liveliness encrypted,
#                                 every topic access-controlled, payload encrypted (AES-GCM), submessages signed
#   DIR/ROLE/{cert,key}.pem       one identity per role, CN=twinslam-ROLE
#   DIR/ROLE/permissions.p7s      what the role may publish and subscribe (below)
# Roles: drone (ingest, tracking, estimator: publishes everything but Registration and MapTile), edge (tiles,
# registration: publishes Registration, MapTile, Heartbeat), ops (monitors, recorders, the bridge: subscribes,
# publishes Heartbeat), and any EXTRA role named on the command line: Heartbeat only (e.g. `guest`, for access tests).
# Every role subscribes to every topic; the edge reads LocalMap and Odometry, the drone reads Registration and MapTile.
# Usage: make-pki.sh DIR [EXTRA_ROLE...]   (existing files are kept: delete DIR to make new keys)
set -euo pipefail
die() { echo "make-pki.sh: $*" >&2; exit 2; }
[[ $# -ge 1 ]] || die "usage: make-pki.sh DIR [EXTRA_ROLE...]"
command -v openssl >/dev/null || die "openssl not found (apt-get install openssl)"
dir=$1; shift
mkdir -p "$dir" || die "cannot create $dir"
cd "$dir"
umask 077
days=3650
domains='<domains><id_range><min>0</min><max>232</max></id_range></domains>'
validity='<validity><not_before>2020-01-01T00:00:00</not_before><not_after>2045-01-01T00:00:00</not_after></validity>'
topic() { local t; for t in "$@"; do printf '<topic>%s</topic>' "$t"; done; }
header='<?xml version="1.0" encoding="UTF-8"?>'

if [[ ! -f ca.pem ]]; then
  openssl ecparam -name prime256v1 -genkey -noout -out ca.key
  openssl req -x509 -new -key ca.key -sha256 -days "$days" -subj "/O=twinslam/CN=twinslam-ca" -out ca.pem
fi

sign() {  # sign XML FILE.xml into FILE.p7s (S/MIME, as the DDS-Security spec's documents are)
  openssl smime -sign -text -in "$1.xml" -out "$1.p7s" -signer ca.pem -inkey ca.key
}

if [[ ! -f governance.p7s ]]; then
  cat > governance.xml <<GOV
$header
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
  <domain_access_rules>
    <domain_rule>
      $domains
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>SIGN</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
GOV
  sign governance
fi

# The topics each role may publish (names: common/dds/include/twinslam/dds/topics.hpp).
publishes() {
  case $1 in
    drone) topic twinslam/v1/imu twinslam/v1/image twinslam/v1/gnss twinslam/v1/features twinslam/v2/odometry \
             twinslam/v2/local_map twinslam/v1/frame_ack twinslam/v1/tile_request twinslam/v1/heartbeat ;;
    edge) topic twinslam/v3/registration twinslam/v1/map_tile twinslam/v1/heartbeat ;;
    *) topic twinslam/v1/heartbeat ;;
  esac
}
subscribes() {
  case $1 in
    drone|edge|ops) topic '*' ;;
    *) topic twinslam/v1/heartbeat ;;
  esac
}

identity() {  # ROLE
  local role=$1
  mkdir -p "$role"
  if [[ ! -f $role/cert.pem ]]; then
    openssl ecparam -name prime256v1 -genkey -noout -out "$role/key.ec"
    openssl pkcs8 -topk8 -nocrypt -in "$role/key.ec" -out "$role/key.pem" && rm "$role/key.ec"
    openssl req -new -key "$role/key.pem" -subj "/O=twinslam/CN=twinslam-$role" -out "$role/cert.csr"
    openssl x509 -req -in "$role/cert.csr" -CA ca.pem -CAkey ca.key -CAcreateserial -days "$days" -sha256 \
      -out "$role/cert.pem" 2>/dev/null
    rm "$role/cert.csr"
  fi
  if [[ ! -f $role/permissions.p7s ]]; then
    cat > "$role/permissions.xml" <<PERM
$header
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
  <permissions>
    <grant name="twinslam-$role">
      <subject_name>CN=twinslam-$role,O=twinslam</subject_name>
      $validity
      <allow_rule>
        $domains
        <publish><topics>$(publishes "$role")</topics></publish>
        <subscribe><topics>$(subscribes "$role")</topics></subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
PERM
    sign "$role/permissions"
  fi
}

for role in drone edge ops "$@"; do
  [[ $role =~ ^[a-z][a-z0-9_-]*$ ]] || die "role '$role': lower-case letters, digits, - and _ only"
  identity "$role"
done
chmod 644 ca.pem governance.p7s ./*/cert.pem ./*/permissions.p7s
echo "make-pki.sh: $PWD: ca.pem, governance.p7s, roles: drone edge ops $*"
