#!/bin/sh
# boards/lm3s6965evb/client-test.sh DIR SCENE SERVER HOST_CLIENT CLIENT_ELF "QEMU_CMD" OLED_COMPARE
#
# The 64 KiB thin client end to end (docs/porting.md §8). lumo-server serves
# SCENE on loopback with its serial listener;
#  1. the host build of the lm3s client (same pictures, same grey screen)
#     streams it and writes its pictures (--out DIR/host);
#  2. QEMU's lm3s6965evb streams it live over UART0, shows every 128x64
#     picture on the SSD0323 OLED and holds the last (--hold);
#  3. once it holds, QMP's screendump takes the OLED (DIR/oled.ppm) and QEMU
#     is quit; OLED_COMPARE checks it against the host's last grey picture,
#     pixel by pixel (all 8192 must be equal);
#  4. the board's HASH lines (every RGB565 picture and its grey reduction)
#     must equal the host's.
# QMP_SCREENDUMP is OLED_COMPARE's sibling (qmp-screendump). Runs are
# bounded in CPU time (ulimit -t) and wall time (timeout); the trap ends
# what is left. Prints "RESULT: N passed, M failed". Logs: DIR/*.log.
dir=$1; scene=$2; server=$3; host=$4; elf=$5; qemu=$6; compare=$7
qmp_dump=$(dirname "$compare")/qmp-screendump
mkdir -p "$dir/host"
. "$(dirname "$0")/../../tests/lib/background.sh"

if ! spawn "lumo-server" "$dir/server.port" "$dir/server.log" "$server" "$scene" \
        --listen 127.0.0.1:0 --serial-listen 127.0.0.1:0 --port-file "$dir/server.port"; then
    echo "RESULT: $pass passed, $fail failed"; exit 1
fi
serial=$(cut -d' ' -f2 "$dir/server.port")

# 1. the host: its pictures are the reference
rm -f "$dir"/host/*
LUMO_LINK=127.0.0.1:$serial timeout 120 "$host" --out "$dir/host" </dev/null >"$dir/host.log" 2>&1
st=$?
grep '^HASH ' "$dir/host.log" >"$dir/host.hash"
last=$(grep '^HASH grey-' "$dir/host.hash" | tail -n 1 | cut -d' ' -f2)
if [ "$st" -eq 0 ] && [ -n "$last" ] && [ -s "$dir/host/$last.pgm" ]; then
    ok "host, live: $(grep -c . "$dir/host.hash") hashes, the last grey picture $last"
else
    bad "host, live (exit $st) — $dir/host.log"; tail -n 5 "$dir/host.log" | sed 's/^/    /'
fi

# 2. the board, live over its UART, holding its last picture on the OLED
rm -f "$dir/qmp.sock" "$dir/oled.ppm"
timeout 600 sh -c 'ulimit -t 120; exec "$@"' run $qemu -qmp "unix:$dir/qmp.sock,server=on,wait=off" \
    -chardev "socket,id=link,host=127.0.0.1,port=$serial" -serial chardev:link -kernel "$elf" -append "--hold" \
    </dev/null >"$dir/board.log" 2>&1 &
qpid=$!
pids="$pids $qpid"
i=0
while ! grep -q 'holding the last picture' "$dir/board.log" && kill -0 $qpid 2>/dev/null && [ $i -lt 3000 ]; do
    sleep 0.2; i=$((i + 1))
done

# 3. the OLED through QMP, then QEMU quits
if grep -q 'holding the last picture' "$dir/board.log" && "$qmp_dump" "$dir/qmp.sock" "$dir/oled.ppm" >"$dir/qmp.log" 2>&1; then
    wait $qpid
    if "$compare" "$dir/oled.ppm" "$dir/host/$last.pgm" >"$dir/compare.log" 2>&1; then
        ok "board OLED (QMP screendump) = host's $last: $(cat "$dir/compare.log" | sed 's/^oled-compare: //')"
    else
        bad "board OLED differs from the host's $last: $(cat "$dir/compare.log")"
    fi
else
    kill $qpid 2>/dev/null; wait $qpid
    bad "board, live (no picture held) — $dir/board.log"
    { grep -E 'error|FAULT' "$dir/board.log"; tail -n 3 "$dir/board.log"; cat "$dir/qmp.log" 2>/dev/null; } \
        | head -n 12 | sed 's/^/    /'
fi

# 4. every picture's hash
grep '^HASH ' "$dir/board.log" >"$dir/board.hash"
if [ -s "$dir/host.hash" ] && cmp -s "$dir/host.hash" "$dir/board.hash"; then
    ok "board (QEMU lm3s6965evb), live over its UART: $(grep -c . "$dir/host.hash") hashes equal; $(grep '^client: done' "$dir/board.log" | sed 's/^client: done: //')"
else
    bad "board hashes differ from the host's — $dir/board.log"; diff "$dir/host.hash" "$dir/board.hash" | head -n 12 | sed 's/^/    /'
fi
grep -E '^(MEM|stack)' "$dir/board.log" | sed 's/^/    board: /'
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
