#!/bin/sh
# Installs the Debian packages pmech builds and tests with, when they are missing.
# Runs apt-get only as root; otherwise it says what to install and lets the build try.
set -e
PKGS="build-essential cmake pkg-config time clang libclang-rt-dev libomp-dev libjansson-dev libsuitesparse-dev libcairo2-dev libexpat1-dev libhdf5-dev hdf5-tools libcmocka-dev python3 python3-vtk9 python3-numpy python3-matplotlib python3-setuptools python3-venv python3-pip ffmpeg"
missing=""
for p in $PKGS; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
[ -z "$missing" ] && exit 0
if [ "$(id -u)" -ne 0 ]; then
  echo "pmech: missing Debian packages:$missing" >&2
  echo "pmech: run 'sudo apt-get install$missing' (or run make as root)" >&2
  exit 0
fi
echo "pmech: installing$missing"
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q --no-install-recommends $missing
