#!/bin/sh
# boards/client/client-test.sh DIR SCENE SERVER HOST_CLIENT CLIENT_ELF "QEMU_CMD"
#
# The board client (boards/client/client.c) end to end, bit for bit
# (docs/porting.md §7). lumo-server serves SCENE on loopback with its serial
# listener (a serial line carried over TCP, free ports via --port-file);
#  1. the host build streams it over LUMO_LINK and records the bytes;
#  2. the host build and QEMU (mps2-an385) replay the recording;
#  3. QEMU streams it live: its UART0 is a chardev socket to the serial
#     listener;
#  4. QEMU streams it live again through --loss 0.01 (a damaged frame must
#     be refused and the requests asked again), and the host build through
#     --loss 0.2 (silences too);
# Every run must exit 0; the HASH lines of 1-3 must be identical, and the
# full scene's (frame-100-*) in 4. Servers and QEMU are killed on exit
# (trap); every run is bounded in CPU time (ulimit -t) and wall time (timeout). QEMU_CMD is the board's QEMU
# invocation without -kernel; its "-serial none" is replaced by the link.
# Prints "RESULT: N passed, M failed". Logs: DIR/*.log.
dir=$1; scene=$2; server=$3; host=$4; elf=$5; qemu=$6
mkdir -p "$dir"
. "$(dirname "$0")/../../tests/lib/background.sh"

# serve NAME ARGS...: lumo-server in the background; sets $serial (its
# serial listener's port) once it listens (5 s at most).
serve() {
    name=$1; shift
    spawn "$name: lumo-server" "$dir/$name.port" "$dir/$name.server.log" "$server" "$scene" \
        --listen 127.0.0.1:0 --serial-listen 127.0.0.1:0 --port-file "$dir/$name.port" "$@" || return 1
    serial=$(cut -d' ' -f2 "$dir/$name.port")
}

# run LOG CMD...: in the background (so the trap can end it); its status in
# $st, its HASH lines in LOG.hash. Bounded by CPU time, 60 s (ulimit -t:
# SIGXCPU, exit 152), and by wall time, 600 s, for a process that hangs
# without computing. CPU, not wall time, because what a run needs is
# measured in CPU and the machine is shared: QEMU spends about 30 us of host
# CPU per byte moved through the CMSDK UART model (one byte per main-loop
# turn), so the live session costs 13-15 s of CPU against 4.8 s for the
# replay of the same bytes (4.39 G guest instructions either way); with 8
# builds on 2 cores that was 50-65 s of wall time, and a 60 s wall limit
# killed a healthy run (docs/porting.md §7).
run() {
    log=$1; shift
    timeout 600 sh -c 'ulimit -t 60; exec "$@"' run "$@" </dev/null >"$log" 2>&1 &
    p=$!
    pids="$pids $p"
    wait $p; st=$?
    grep '^HASH ' "$log" >"$log.hash"
}

board_live() {   # board_live LOG PORT
    run "$1" $(echo "$qemu" | sed 's/-serial none//') -chardev "socket,id=link,host=127.0.0.1,port=$2" \
        -serial chardev:link -kernel "$elf"
}

# same WHAT LOG REFERENCE [PATTERN]: exit 0 and the HASH lines (matching
# PATTERN) equal to the reference's.
same() {
    what=$1; log=$2; ref=$3; pat=${4:-.}
    if [ "$st" -eq 0 ] && [ -s "$log.hash" ] && cmp -s "$ref" "$log.hash" ||
       { [ "$pat" != . ] && [ "$st" -eq 0 ] && grep "$pat" "$log.hash" | cmp -s - "$ref"; }; then
        ok "$what: $(grep -c . "$ref") hashes equal; $(grep '^client: done' "$log" | sed 's/^client: done: //')"
    else
        bad "$what (exit $st) — $log"
        { diff "$ref" "$log.hash"; grep -E 'error|FAULT' "$log"; } | head -n 12 | sed 's/^/    /'
    fi
}

# A resynchronisation was seen (refused frames or silences) in LOG.
resynced() {
    if grep -Eq ' ([1-9][0-9]*) refused| ([1-9][0-9]*) silences' "$1"; then
        ok "$2: $(grep -o '[0-9]* refused, [0-9]* silences, [0-9]* times asked again' "$1")"
    else
        bad "$2: no frame was refused and no silence seen (the server's --seed damages none now: pick another)"
    fi
}

rec="$dir/session.rec"
if serve clean; then
    # A lossless line never makes the client ask again; on a loaded machine a
    # 250 ms stall could (a silence), and the recording would then hold
    # answers asked twice: record again (3 tries).
    for try in 1 2 3; do
        LUMO_LINK=127.0.0.1:$serial run "$dir/host-live.log" "$host" --record "$rec"
        grep -q ' 0 times asked again' "$dir/host-live.log" && break
    done
    if [ "$st" -eq 0 ] && [ "$(grep -c . "$dir/host-live.log.hash")" -eq 10 ]; then
        ok "host, live over the serial listener: 10 pictures, recorded $(wc -c <"$rec") bytes"
    else
        bad "host, live (exit $st) — $dir/host-live.log"; tail -n 5 "$dir/host-live.log" | sed 's/^/    /'
    fi
    ref="$dir/host-live.log.hash"
    run "$dir/host-replay.log" "$host" --replay "$rec"
    same "host, replay" "$dir/host-replay.log" "$ref"
    run "$dir/board-replay.log" $qemu -kernel "$elf" -append "--replay $rec"
    same "board (QEMU mps2-an385), replay" "$dir/board-replay.log" "$ref"
    board_live "$dir/board-live.log" "$serial"
    same "board, live over its UART" "$dir/board-live.log" "$ref"
fi
grep '^HASH frame-100' "$dir/host-live.log.hash" >"$dir/final.hash" 2>/dev/null
if serve loss --loss 0.01 --seed 1; then
    board_live "$dir/board-loss.log" "$serial"
    same "board, live through --loss 0.01: the full scene" "$dir/board-loss.log" "$dir/final.hash" '^HASH frame-100'
    resynced "$dir/board-loss.log" "board, --loss 0.01"
fi
if serve loss20 --loss 0.2 --seed 3; then
    LUMO_LINK=127.0.0.1:$serial run "$dir/host-loss.log" "$host"
    same "host, live through --loss 0.2: the full scene" "$dir/host-loss.log" "$dir/final.hash" '^HASH frame-100'
    resynced "$dir/host-loss.log" "host, --loss 0.2"
fi
grep -E '^(COST|MEM|stack)' "$dir/board-replay.log" | sed 's/^/    board replay: /'
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
