#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine:
#   bash scripts/bootstrap.sh run    install what is missing, build Release, run the default job
#   bash scripts/bootstrap.sh test   install what is missing, build Release, run the whole test suite
# Extra arguments after `run` go to `grainshock run`.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
mode=${1:-run}
shift || true

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libosmesa6-dev libegl-dev libgl-dev libpng-dev zlib1g-dev libfreetype-dev fonts-dejavu-core
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev ffmpeg
  libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox
  python3-dev python3-numpy pybind11-dev python3-pybind11
)
# Optional for users, installed for the tests so that CI runs them: MPI ensembles; ASE, gsd
# and LAMMPS reading and writing snapshot files with ours (tests/io/test_interop.cpp); pytest,
# matplotlib and Jupyter for the Python module's tests and its notebook (tests/python).
if [ "$mode" = test ]; then
  packages+=(libopenmpi-dev openmpi-bin python3-ase python3-gsd lammps)
  packages+=(python3-pytest python3-matplotlib jupyter-nbconvert python3-ipykernel)
  # The pages of `grainshock view`, loaded in a real browser (tests/view).
  packages+=(chromium chromium-driver python3-selenium)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q "${missing[@]}"
fi

build="$here/build"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)"

case "$mode" in
  run)
    "$build/apps/grainshock" run "$@"
    ;;
  test)
    cd "$build" && ctest --output-on-failure -j "$(nproc)" "$@"
    ;;
  *)
    echo "bootstrap: unknown mode '$mode' (use run or test)" >&2
    exit 2
    ;;
esac
