#!/bin/sh
# tests/usb/kernel.sh DIR — Debian's own x86-64 kernel for the USB guest
# (tests/usb/usb-test.sh), cached under DIR: the package linux-image-amd64
# depends on (apt-cache), fetched with apt-get download and unpacked with
# dpkg-deb -x. Prints the unpacked tree (DIR/<package>/root, with boot/
# and lib/modules/) on stdout; a failure is one line on stderr, status 1.
set -eu
dir=$1
name=$(apt-cache depends linux-image-amd64 2>/dev/null |
       sed -n 's/^ *Depends: \(linux-image-[0-9][^ ]*-amd64\)$/\1/p' | head -n 1)
[ -n "$name" ] || { echo "kernel.sh: apt-cache names no linux-image-*-amd64 (apt-get update?)" >&2; exit 1; }
out="$dir/$name"
if [ ! -f "$out/done" ]; then
    rm -rf "$out"
    mkdir -p "$out"
    (cd "$out" && apt-get download "$name" >download.log 2>&1) ||
        { echo "kernel.sh: apt-get download $name failed ($out/download.log)" >&2; exit 1; }
    dpkg-deb -x "$out"/*.deb "$out/root"
    rm -f "$out"/*.deb
    touch "$out/done"
fi
echo "$out/root"
