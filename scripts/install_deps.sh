#!/usr/bin/env bash
# Installs the Debian bookworm packages top_sim needs; does nothing (no apt-get) when all are installed.
set -euo pipefail
source "$(dirname "$0")/lib.sh"

command -v dpkg-query >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1 \
  || top_sim_die "dpkg-query/apt-get not found: these scripts need Debian bookworm"

mapfile -t missing < <(top_sim_missing_packages)
if [ "${#missing[@]}" -eq 0 ]; then
  top_sim_log "all ${#TOP_SIM_PACKAGES[@]} Debian packages are installed"
  exit 0
fi

top_sim_log "installing ${#missing[@]} Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
top_sim_as_root env DEBIAN_FRONTEND=noninteractive apt-get update
top_sim_as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y "${missing[@]}"

mapfile -t missing < <(top_sim_missing_packages)
[ "${#missing[@]}" -eq 0 ] || top_sim_die "still not installed after apt-get: ${missing[*]}"
top_sim_log "all ${#TOP_SIM_PACKAGES[@]} Debian packages are installed"
