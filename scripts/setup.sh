#!/usr/bin/env bash
# Shared by scripts/demo and scripts/test: install the Debian packages dynmesh needs (only
# those missing; `apt-get update` once, only when something is missing), then configure and
# build the Release preset. Usage: source scripts/setup.sh
set -euo pipefail

DYNMESH_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DYNMESH_PACKAGES=(g++ cmake ninja-build libgtest-dev libbenchmark-dev libcgal-dev libgmp-dev
                  libmpfr-dev libcli11-dev nlohmann-json3-dev python3-matplotlib
                  python3-vtk9 python3-meshio gemmi-dev tao-pegtl-dev python3-dev pybind11-dev
                  python3-numpy python3-pytest)

dynmesh_install_packages() {
    local missing=()
    for p in "${DYNMESH_PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if [ ${#missing[@]} -eq 0 ]; then
        echo "setup: all Debian packages present"
        return
    fi
    echo "setup: installing ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

dynmesh_build() {
    cd "$DYNMESH_ROOT"
    cmake --preset release >/dev/null
    cmake --build --preset release -j "$(nproc)"
    ln -sf build/release/compile_commands.json compile_commands.json 2>/dev/null || true
}

dynmesh_install_packages
dynmesh_build
# `/usr/bin/python3 -c "import dynmesh"` finds this build's module from anywhere.
bash "$DYNMESH_ROOT/scripts/python_path.sh" "$DYNMESH_ROOT/build/release/python"
DYNMESH_BIN="$DYNMESH_ROOT/build/release/bin/dynmesh"
export DYNMESH_ROOT DYNMESH_BIN
