#!/bin/sh
# bootstrap.sh - the README's first command: install the Debian packages svet
# needs when they are missing, build everything, and render the default
# scene (scenes/cbox.scn) to out/cbox.exr and out/cbox.png. The package
# list is .ci/run's: `parallel` is there because `make test` runs the split
# render under GNU parallel (tests/cmd/test_render_parallel.sh skips it
# when parallel is missing).
set -eu
cd "$(dirname "$0")/.."
pkgs="build-essential pkg-config check libpng-dev libopenexr-dev parallel"
missing=""
for p in $pkgs; do
    dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
    echo "installing:$missing"
    if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq $missing
fi
make -j"$(nproc)"
mkdir -p out
if [ -f scenes/cbox.scn ] && [ -x build/float/svet ]; then
    build/float/svet render scenes/cbox.scn -o out/cbox.exr
    echo "rendered out/cbox.exr and out/cbox.png"
else
    echo "built; no renderer yet to render scenes/cbox.scn"
fi
