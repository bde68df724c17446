# Shared by the set-up scripts: install the Debian packages ddafrac needs (only those missing)
# and build it. Sourced, not run.
set -euo pipefail

DDAFRAC_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DDAFRAC_BUILD="${DDAFRAC_BUILD:-$DDAFRAC_ROOT/build}"

# Every dependency is a Debian 12 package (see README "Dependencies" for why each is there).
DDAFRAC_PACKAGES=(
  cmake g++ make pkg-config
  libeigen3-dev libgmsh-dev libboost-test-dev libboost-serialization-dev
  libtomlplusplus-dev libcli11-dev nlohmann-json3-dev libfmt-dev libcairo2-dev
  libdeal.ii-dev libsuitesparse-dev openmpi-bin
  python3-matplotlib
)

ddafrac_install_dependencies() {
  local missing=()
  for package in "${DDAFRAC_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$package")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    echo "ddafrac: all ${#DDAFRAC_PACKAGES[@]} Debian packages are installed"
    return
  fi
  if [ "$(id -u)" -ne 0 ]; then
    echo "ddafrac: missing packages: ${missing[*]}; run as root (or install them with apt-get)" >&2
    exit 1
  fi
  echo "ddafrac: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# Configures the Release build and builds the named targets (every target when none is named:
# the tests need them all, a run only the ddafrac executable).
ddafrac_build() {
  cmake -S "$DDAFRAC_ROOT" -B "$DDAFRAC_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
  if [ $# -gt 0 ]; then
    cmake --build "$DDAFRAC_BUILD" -j "$(nproc)" --target "$@"
  else
    cmake --build "$DDAFRAC_BUILD" -j "$(nproc)"
  fi
}
