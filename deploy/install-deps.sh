#!/usr/bin/env bash
# Installs every Debian package the project needs to build, test and benchmark.
# Idempotent: when everything is present it prints nothing and exits 0.
# Runs as root (CI, fresh Debian 12 machine) or through sudo when available.
set -euo pipefail

packages=(
  # build
  cmake ninja-build ccache g++ pkg-config git
  # middleware and wire formats
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools default-jre-headless
  libprotobuf-dev protobuf-compiler
  # libraries
  libeigen3-dev libbullet-dev libspdlog-dev libcli11-dev libyaml-cpp-dev nlohmann-json3-dev
  libcpp-httplib-dev zlib1g-dev
  # systemd integration (sd_notify), unit checks and the Debian package
  libsystemd-dev systemd dpkg-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # fuzzing and sanitizers (clang build)
  clang libclang-rt-14-dev
  # process and network tests
  iproute2 procps python3
  # multi-host tests: network namespaces joined by a bridge, multicast filtered on it; a host's own systemd
  # (systemd-nspawn boots one in a namespace: the units restart a killed service)
  nftables systemd-container
  # browser tests of the console: Debian's chromium driven by playwright-core (tests/browser, from npm)
  chromium
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done
# Node.js and npm for the browser tests: any recent Node will do (machines often bring their own).
command -v node >/dev/null && command -v npm >/dev/null || missing+=(nodejs npm)
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
