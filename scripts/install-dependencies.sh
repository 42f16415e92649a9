#!/usr/bin/env bash
# Install what fdparticle needs from Debian 12 (bookworm) packages, if anything is missing.
set -euo pipefail
# libopenblas0-serial: an optimised BLAS for MUMPS's dense frontal matrices. Installed, it
# takes over libblas.so.3 (Debian alternatives); deal.II's dependencies pull in only the
# reference BLAS, with which the factorization of the 3D sediment scene runs ~5x slower
# (doc/performance.md). Serial, not pthread: MPI ranks already use the cores.
packages=(libdeal.ii-dev libmumps-dev libeigen3-dev cmake ninja-build g++ openmpi-bin numdiff python3 gnuplot-nox
          libopenblas0-serial python3-numpy python3-matplotlib)
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
