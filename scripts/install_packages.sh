#!/usr/bin/env bash
# Installs the given Debian/Ubuntu packages with apt-get when one of them is
# missing (`sudo` only when not root; nothing happens when `dpkg -s` finds them
# all, or when DEM_SKIP_DEPS=1). Used by setup.sh (build dependencies) and
# build_docs.sh (documentation tools).
#   bash scripts/install_packages.sh PACKAGE...
set -euo pipefail
if [[ "${DEM_SKIP_DEPS:-0}" == 1 ]]; then exit 0; fi
if ! command -v dpkg >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
  echo "install_packages: not a Debian/Ubuntu system; install these yourself: $*" >&2
  exit 0
fi
missing=()
for p in "$@"; do
  # "install ok installed" is the only state where the package is usable
  if ! dpkg -s "$p" 2>/dev/null | grep -q '^Status: install ok installed'; then
    missing+=("$p")
  fi
done
if (( ${#missing[@]} == 0 )); then exit 0; fi
echo "install_packages: installing ${missing[*]}"
sudo=()
if [[ "$(id -u)" != 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then sudo=(sudo); else
    echo "install_packages: not root and no sudo; install these yourself: ${missing[*]}" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
