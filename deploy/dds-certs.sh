#!/usr/bin/env bash
# Makes the DDS Security files of one trust domain with openssl only: a CA, the governance document and,
# per identity, a certificate, its private key and its permissions document (both documents S/MIME-signed
# by the CA, as Fast DDS's builtin Access-Permissions plugin requires). `./ssl certs` runs it; installed
# as ssl-dds-certs. Layout of DIR (libs/dds/security.h reads it):
#
#   ca.pem, ca.key             the CA (identities and permissions); ca.key only signs: keep it off match PCs
#   governance.xml/.p7s        join access control, encrypted discovery and liveliness, read/write access
#                              control on every topic; team topics encrypted, shared ones signed
#   <identity>/cert.pem, key.pem, permissions.xml/.p7s
#
# Identities (who runs them: libs/dds/security.h):
#   shared          vision_gateway, referee_gateway, simulator: shared topics only
#   <team>          world_model, planner, robot_link of a team: its team partition and the shared topics
#                   it needs; its e-stop only in its own partition (robot_link's button)
#   <team>-operator console or sslctl of one team: reads its team, writes system.params and its team's
#                   system.estop
#   operator        console or sslctl of every team (the sim host, or a team's coach box): both team
#                   partitions, also in a one-team CA, where nobody of the other team can authenticate
#
# Threat model: at a competition each team makes its own trust domain (--teams blue), so the other team
# cannot even authenticate. An AI-vs-AI simulation shares one trust domain (--teams blue,yellow): there a
# participant holding the other team's identity authenticates, and its permissions (partitions) stop it.
#
# Usage: dds-certs.sh --dir DIR [--teams blue,yellow] [--days N] [--force]
#   Existing files are kept (the CA, and identities already made by it), missing ones are made: running
#   it twice changes nothing. --force deletes DIR's files first and makes a new CA (every host needs the
#   new files then).
set -euo pipefail

dir=""
teams="blue,yellow"
days=3650
force=0
usage() { awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "${BASH_SOURCE[0]}"; }
fail() { echo "dds-certs: $*" >&2; exit 2; }
# quietly COMMAND...: runs an openssl step, showing its output only when it fails.
quietly() {
  local output
  output="$("$@" 2>&1)" || { echo "$output" >&2; fail "failed: $*"; }
}
while [ $# -gt 0 ]; do
  case "$1" in
    --dir) [ $# -ge 2 ] || fail "--dir needs a directory"; dir="$2"; shift 2 ;;
    --teams) [ $# -ge 2 ] || fail "--teams needs blue, yellow or blue,yellow"; teams="$2"; shift 2 ;;
    --days) [ $# -ge 2 ] || fail "--days needs a number"; days="$2"; shift 2 ;;
    --force) force=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) fail "unknown option '$1' (--dir DIR, --teams blue,yellow, --days N, --force)" ;;
  esac
done
[ -n "$dir" ] || fail "--dir DIR is required"
command -v openssl >/dev/null || fail "openssl is not installed (apt-get install openssl)"
case "$days" in ''|*[!0-9]*) fail "--days must be a positive number of days" ;; esac
[ "$days" -gt 0 ] || fail "--days must be a positive number of days"
team_list=()
IFS=',' read -r -a requested <<<"$teams"
for team in "${requested[@]}"; do
  case "$team" in
    blue|yellow) team_list+=("$team") ;;
    *) fail "--teams: '$team' is not a team (blue, yellow)" ;;
  esac
done
[ ${#team_list[@]} -gt 0 ] || fail "--teams names no team"

if [ "$force" -eq 1 ] && [ -d "$dir" ]; then
  rm -f "$dir"/ca.pem "$dir"/ca.key "$dir"/ca.srl "$dir"/governance.xml "$dir"/governance.p7s
  for identity in shared operator blue blue-operator yellow yellow-operator; do
    rm -rf "${dir:?}/$identity"
  done
fi
mkdir -p "$dir"
dir="$(cd "$dir" && pwd)"
umask 077

# --- the CA ------------------------------------------------------------------------------------------
if [ -f "$dir/ca.pem" ] && [ -f "$dir/ca.key" ]; then
  echo "dds-certs: keeping the CA in $dir (--force makes a new one)"
elif [ -f "$dir/ca.pem" ] || [ -f "$dir/ca.key" ]; then
  fail "$dir has only one of ca.pem and ca.key: restore it or start over with --force"
else
  # A unique subject: two trust domains never look alike, even in logs. digitalSignature: the CA also
  # signs the governance and permissions (S/MIME), which Fast DDS verifies for that purpose.
  ca_subject="/O=SSL stack/OU=$(IFS=+; echo "${team_list[*]}")/CN=SSL stack CA $(hostname) $(date -u +%Y%m%dT%H%M%SZ) $RANDOM"
  quietly openssl req -x509 -new -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -sha256 -days "$days" \
    -subj "$ca_subject" -addext "basicConstraints=critical,CA:TRUE" -addext "keyUsage=critical,digitalSignature,keyCertSign,cRLSign" \
    -keyout "$dir/ca.key" -out "$dir/ca.pem"
  echo "dds-certs: made a new CA in $dir"
fi
# Names the trust domain in every identity's subject (the first 16 hex digits of the CA's fingerprint).
ca_id="$(openssl x509 -in "$dir/ca.pem" -noout -fingerprint -sha256 | cut -d= -f2 | tr -d : | cut -c1-16)"

sign() {  # sign XML FILE.p7s
  quietly openssl smime -sign -text -in "$1" -out "$2" -signer "$dir/ca.pem" -inkey "$dir/ca.key"
}

not_before="$(date -u +%Y-%m-%dT%H:%M:%S)"
not_after="$(date -u -d "+$days days" +%Y-%m-%dT%H:%M:%S)"
domains="<domains><id_range><min>0</min><max>232</max></id_range></domains>"

# --- governance (one per trust domain) ---------------------------------------------------------------
# Topic rules: the first that matches a topic applies. Team topics are secret (plans, our world view):
# encrypted. Shared topics (vision, referee, system) are what every team may see anyway: signed, so that
# nobody outside the trust domain can forge them, at a lower cost. Read and write access control
# everywhere: a participant reads and writes only what its permissions grant.
topic_rule() {  # topic_rule EXPRESSION METADATA_PROTECTION DATA_PROTECTION
  cat <<EOF
        <topic_rule>
          <topic_expression>$1</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>$2</metadata_protection_kind>
          <data_protection_kind>$3</data_protection_kind>
        </topic_rule>
EOF
}
if [ ! -f "$dir/governance.p7s" ]; then
  cat >"$dir/governance.xml" <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      $domains
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
$(topic_rule 'world.*' ENCRYPT ENCRYPT)
$(topic_rule 'robot.*' ENCRYPT ENCRYPT)
$(topic_rule 'planner.*' ENCRYPT ENCRYPT)
$(topic_rule '*' SIGN NONE)
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
EOF
  sign "$dir/governance.xml" "$dir/governance.p7s"
  echo "dds-certs: signed governance.p7s"
fi

# --- permissions -------------------------------------------------------------------------------------
# Fast DDS applies, per topic, the first allow_rule that lists it, and pools the partitions of that rule's
# criteria: so team topics (in team partitions) and shared topics (default partition) get separate rules.
team_topics="<topic>world.state</topic><topic>robot.commands</topic><topic>robot.sent</topic><topic>robot.feedback</topic><topic>planner.debug</topic>"
shared_topics="<topic>vision.*</topic><topic>referee.*</topic><topic>system.params</topic><topic>system.param_state</topic><topic>system.health</topic>"

partitions() {  # partitions TEAM...
  local xml="<partitions>" team
  for team in "$@"; do xml+="<partition>$team</partition>"; done
  echo "$xml</partitions>"
}

# grant IDENTITY SUBJECT RULE...: the permissions document, one allow_rule per RULE body.
grant() {
  local identity="$1" subject="$2" rule rules=""
  shift 2
  for rule in "$@"; do rules+="
      <allow_rule>$domains
        $rule
      </allow_rule>"; done
  cat <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$identity">
      <subject_name>$subject</subject_name>
      <validity><not_before>$not_before</not_before><not_after>$not_after</not_after></validity>$rules
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
EOF
}

# rules_of IDENTITY: the allow_rule bodies of one identity, one per line.
rules_of() {
  local identity="$1" team
  case "$identity" in
    shared)
      echo "<publish><topics>$shared_topics</topics></publish><subscribe><topics>$shared_topics</topics></subscribe>" ;;
    operator)
      echo "<publish><topics>$team_topics<topic>system.estop</topic></topics>$(partitions blue yellow)</publish><subscribe><topics>$team_topics<topic>system.estop</topic></topics>$(partitions blue yellow)</subscribe>"
      echo "<publish><topics>$shared_topics</topics></publish><subscribe><topics>$shared_topics</topics></subscribe>" ;;
    *-operator)
      # One team's operator sets parameters but never forges vision or the referee for both teams.
      team="${identity%-operator}"
      echo "<publish><topics>$team_topics<topic>system.estop</topic></topics>$(partitions "$team")</publish><subscribe><topics>$team_topics<topic>system.estop</topic></topics>$(partitions "$team")</subscribe>"
      echo "<publish><topics><topic>system.params</topic><topic>system.health</topic><topic>system.param_state</topic></topics></publish><subscribe><topics>$shared_topics</topics></subscribe>" ;;
    *)
      team="$identity"
      echo "<publish><topics>$team_topics<topic>system.estop</topic></topics>$(partitions "$team")</publish><subscribe><topics>$team_topics<topic>system.estop</topic></topics>$(partitions "$team")</subscribe>"
      # A team's services publish health and run-time parameter state; they never forge vision or the referee.
      echo "<publish><topics><topic>system.health</topic><topic>system.param_state</topic></topics></publish><subscribe><topics>$shared_topics</topics></subscribe>" ;;
  esac
}

identities=(shared operator)
for team in "${team_list[@]}"; do identities+=("$team" "$team-operator"); done

for identity in "${identities[@]}"; do
  id_dir="$dir/$identity"
  if [ -f "$id_dir/cert.pem" ] && [ -f "$id_dir/key.pem" ] && [ -f "$id_dir/permissions.p7s" ] &&
     openssl verify -CAfile "$dir/ca.pem" "$id_dir/cert.pem" >/dev/null 2>&1; then
    continue
  fi
  mkdir -p "$id_dir"
  quietly openssl req -new -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -sha256 \
    -subj "/O=SSL stack/OU=$ca_id/CN=$identity" -keyout "$id_dir/key.pem" -out "$id_dir/cert.csr"
  quietly openssl x509 -req -in "$id_dir/cert.csr" -CA "$dir/ca.pem" -CAkey "$dir/ca.key" -CAcreateserial \
    -CAserial "$dir/ca.srl" -days "$days" -sha256 -out "$id_dir/cert.pem"
  rm -f "$id_dir/cert.csr"
  subject="$(openssl x509 -in "$id_dir/cert.pem" -noout -subject -nameopt RFC2253 | sed 's/^subject=//')"
  mapfile -t rules < <(rules_of "$identity")
  grant "$identity" "$subject" "${rules[@]}" >"$id_dir/permissions.xml"
  sign "$id_dir/permissions.xml" "$id_dir/permissions.p7s"
  echo "dds-certs: made identity $identity"
done

# Everything readable by the services' group, private keys included (they run as one user; keep DIR's
# own mode as tight as that user needs); the CA key only by its owner.
chmod 0750 "$dir"
find "$dir" -mindepth 1 -type d -exec chmod 0750 {} +
find "$dir" -mindepth 1 -type f -exec chmod 0640 {} +
chmod 0600 "$dir/ca.key"
echo "dds-certs: $dir holds the CA, governance and identities: ${identities[*]}"
