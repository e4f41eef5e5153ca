#!/usr/bin/env bash
# Installs the Debian 12 packages meshtopo needs to build, test, fuzz and
# benchmark (the one package list). Run as root:
#   sudo scripts/install-deps.sh           # build, run, the test suite but archive.paraview
#   sudo scripts/install-deps.sh --tests   # also ParaView for archive.paraview (.ci/run)
# Debian 12's python3-paraview conflicts with python3-vtk9: with --tests it
# replaces it, and its VTK modules (VTK 9.2) serve meshtopo render too.
set -euo pipefail

with_tests=false
case "${1:-}" in
    "") ;;
    --tests) with_tests=true ;;
    *)
        echo "usage: install-deps.sh [--tests]" >&2
        exit 2
        ;;
esac

packages=(
    build-essential cmake ninja-build pkg-config   # compiler and build
    zlib1g-dev                                     # meshtopo::io reads .gz meshes
    libcjson-dev python3                           # tests: JSON reference answers
    time                                           # tests/io: peak RSS of meshtopo inspect
    clang libclang-rt-14-dev clang-format          # fuzzers (libFuzzer), format check
    libopenmesh-dev libcgal-dev                    # benchmark peers (optional)
    # LCM: library, lcm-gen, lcm.jar; a JDK builds meshtopo-msgs.jar for lcm-spy
    # (jchart2d draws its charts, default-jre has the window toolkit the
    # headless JDK lacks); lcm.pc names glib-2.0, which liblcm-dev does not
    # pull in
    liblcm-dev liblcm-bin liblcm-java default-jdk-headless default-jre libjchart2d-java
    libglib2.0-dev
    libxxhash-dev                                  # content hash of submitted meshes (XXH3)
    libhdf5-dev hdf5-tools                         # meshtopo::archive (HDF5 1.10), h5dump/h5ls
    hdf5-filter-plugin-blosc-serial                # LZ4 archives (--archive-compression lz4)
    python3-vtk9                                   # meshtopo render, archive export to .vtu; tests/archive:
    python3-h5py                                   # VTK's vtkHDFReader and h5py read archives
    python3-numpy python3-pytest                   # the Python package (lib/python) and its tests
    nftables iproute2                              # tests/netns: private network, packet loss
    xvfb xauth                                     # meshtopo render (VTK 9.1 draws through X: its own
                                                   # Xvfb without a display); tests/cli: meshtopo spy
    help2man man-db lintian                        # man pages from --help; tests/install: man -w,
                                                   # the Debian packages' policy check
)
# --tests: archive.paraview opens every archived corpus mesh in ParaView's
# pvbatch (large; meshtopo itself never needs ParaView).
test_packages=(paraview python3-paraview)

if [ "$(id -u)" -ne 0 ]; then
    echo "install-deps.sh: run as root (sudo scripts/install-deps.sh)" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update
# python3-vtk9 (asked for above) and python3-paraview conflict. With
# --tests, ask for the list without it, and apt replaces an installed
# python3-vtk9; without, keep an installed python3-paraview (its VTK serves
# meshtopo render), so running this again never takes ParaView away.
if $with_tests || dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null |
    grep -q 'ok installed'; then
    mapfile -t packages < <(printf '%s\n' "${packages[@]}" | grep -vx python3-vtk9)
fi
if $with_tests; then
    packages+=("${test_packages[@]}")
fi
apt-get install -y --no-install-recommends "${packages[@]}"
