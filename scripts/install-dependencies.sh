#!/usr/bin/env bash
# Install what fdparticle needs from Debian 12 (bookworm) packages, if anything is missing.
set -euo pipefail
packages=(libdeal.ii-dev libeigen3-dev cmake ninja-build g++ openmpi-bin numdiff python3 gnuplot-nox)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "Installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
