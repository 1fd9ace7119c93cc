#!/bin/sh
# tools/board-demo/board-demo.sh DIR RECORDING HOST_CLIENT BOARD_ELF QEMU PPM2PNG
# Replays RECORDING on the board under QEMU and on the host build of the
# same client, both with --out, and writes every picture as PNG into
# DIR/board/ and DIR/host/; says whether each pair is byte for byte equal.
set -eu
dir=$1; rec=$2; host=$3; elf=$4; qemu=$5; topng=$6
[ -f "$rec" ] || { echo "demo-board: no recording at $rec (make board-client makes it)"; exit 1; }
rm -rf "$dir"; mkdir -p "$dir/board" "$dir/host" "$dir/ppm-board" "$dir/ppm-host"
timeout 600 $qemu -kernel "$elf" -append "--replay $rec --out $dir/ppm-board" >"$dir/board.log" 2>&1 ||
    { cat "$dir/board.log"; exit 1; }
"$host" --replay "$rec" --out "$dir/ppm-host" >"$dir/host.log" 2>&1 || { cat "$dir/host.log"; exit 1; }
same=0; differ=0
for p in "$dir"/ppm-board/*.ppm; do
    n=$(basename "$p" .ppm)
    "$topng" "$p" "$dir/board/$n.png"
    "$topng" "$dir/ppm-host/$n.ppm" "$dir/host/$n.png"
    if cmp -s "$p" "$dir/ppm-host/$n.ppm"; then same=$((same + 1)); else differ=$((differ + 1)); echo "demo-board: $n differs"; fi
done
rm -rf "$dir/ppm-board" "$dir/ppm-host"
echo "demo-board: $same pictures of the board (QEMU mps2-an385) in $dir/board, the host's in $dir/host; $same equal, $differ differ"
[ "$differ" -eq 0 ]
