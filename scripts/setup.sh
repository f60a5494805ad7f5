#!/bin/sh
# feint's set-up on a fresh Debian 12: install what is missing, build, then run.
#   sh scripts/setup.sh demo   build (Release) and run the main job on the shipped demo study
#   sh scripts/setup.sh test   build (Release, warnings as errors) and run the whole test suite
set -eu

mode=${1:-demo}
here=$(cd "$(dirname "$0")/.." && pwd)
build=${FEINT_BUILD_DIR:-$here/build}
jobs=$(nproc 2>/dev/null || echo 2)

# Debian packages feint needs to build and test (no others; nothing is downloaded from elsewhere).
packages="g++ make cmake pkg-config ca-certificates libfmt-dev libcli11-dev libboost-dev libeigen3-dev zlib1g-dev libgtest-dev libcairo2-dev"
# The test suite also checks the SVG figures (xmllint), report.html and the feint collect game in
# headless Chromium, and compiles the LaTeX tables and PDF figures in a paper (pdflatex, booktabs);
# feint collect is tested behind nginx with a self-signed TLS certificate (nginx, openssl).
if [ "$mode" = test ]; then
  packages="$packages libxml2-utils python3 chromium chromium-driver texlive-latex-base texlive-latex-recommended nginx openssl"
fi

missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "feint setup: installing$missing"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends $missing
fi

case "$mode" in
  demo)
    cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DFEINT_BUILD_TESTS=OFF
    cmake --build "$build" -j "$jobs"
    "$build/feint" analyze "$here/data/demo" -o "$here/out/demo"
    ;;
  test)
    cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DFEINT_BUILD_TESTS=ON -DFEINT_WERROR=ON
    cmake --build "$build" -j "$jobs"
    cd "$build" && ctest --output-on-failure -j "$jobs"
    ;;
  *)
    echo "usage: sh scripts/setup.sh demo|test" >&2
    exit 64
    ;;
esac
