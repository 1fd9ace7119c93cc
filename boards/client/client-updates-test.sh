#!/bin/sh
# boards/client/client-updates-test.sh DIR SERVER BAKE HOST_CLIENT CLIENT_ELF "QEMU_CMD"
#
# The board client's updates phase (boards/client/client.c --updates N,
# docs/dynamic.md §6): the demo's moving Cornell box baked small and served
# by lumo-server --dynamic (the engine running) with its serial listener;
#  1. the host build streams the scene, pulls updates until 3 pictures
#     after changes are drawn, and records every byte: their hashes differ
#     from the complete scene's (the lighting moved);
#  2. the host build and QEMU (mps2-an385) replay the recording: the same
#     hashes;
#  3. QEMU streams it live over its UART with --updates 2;
#  4. a recording damaged in its updates part: a one-line error, exit 1, the
#     scene's pictures drawn before it unchanged (the last good state kept).
# Every run is bounded (timeout, ulimit -t). Prints "RESULT: N passed, M failed".
dir=$1; server=$2; bake=$3; host=$4; elf=$5; qemu=$6
scene=tools/dynamic-demo/cornell_dynamic.txt
rm -rf "$dir"; mkdir -p "$dir"
. "$(dirname "$0")/../../tests/lib/background.sh"

"$bake" "$scene" -o "$dir/scene.lumo" --grid 8 --spp 16 --no-progress >"$dir/bake.log" 2>&1 ||
    { bad "bake $scene"; cat "$dir/bake.log"; echo "RESULT: $pass passed, $fail failed"; exit 1; }

run() {   # run LOG CMD...: status in $st, HASH lines in LOG.hash
    log=$1; shift
    timeout 300 sh -c 'ulimit -t 120; exec "$@"' run "$@" </dev/null >"$log" 2>&1 &
    p=$!; pids="$pids $p"
    wait $p; st=$?
    grep '^HASH ' "$log" >"$log.hash"
}

same() {   # same WHAT LOG REF
    if [ "$st" -eq 0 ] && cmp -s "$3" "$2.hash"; then
        ok "$1: $(grep -c . "$3") hashes equal; $(grep '^client: updates' "$2" | sed 's/^client: //')"
    else
        bad "$1 (exit $st) — $2"; { diff "$3" "$2.hash"; grep -E 'error|FAULT' "$2"; } | head -n 8 | sed 's/^/    /'
    fi
}

# changed WHAT LOG N: N update pictures, each unlike the complete scene's
changed() {
    full=$(sed -n 's/^HASH frame-100-320x240 //p' "$2.hash")
    n=$(grep -c '^HASH frame-update-[0-9]*-320x240' "$2.hash")
    same_as_full=$(grep '^HASH frame-update-[0-9]*-320x240' "$2.hash" | grep -c " $full\$")
    if [ "$st" -eq 0 ] && [ "$n" -eq "$3" ] && [ "$same_as_full" -eq 0 ]; then
        ok "$1: $n pictures after updates, none equal to the complete scene's ($(grep '^client: updates' "$2" | sed 's/^client: //'))"
    else
        bad "$1 (exit $st): $n update pictures, $same_as_full equal to the complete scene's"
        grep -E 'error|FAULT' "$2" | head -n 5 | sed 's/^/    /'
    fi
}

rec="$dir/updates.rec"
if spawn "dynamic server" "$dir/port" "$dir/server.log" timeout 300 "$server" "$dir/scene.lumo" \
    --listen 127.0.0.1:0 --serial-listen 127.0.0.1:0 --port-file "$dir/port" \
    --dynamic "$scene,vsl=150,pool=30000,batch=5000"; then
    serial=$(cut -d' ' -f2 "$dir/port")
    LUMO_LINK=127.0.0.1:$serial run "$dir/host-live.log" "$host" --updates 3 --record "$rec"
    changed "host, live with --updates 3" "$dir/host-live.log" 3
    ref="$dir/host-live.log.hash"
    run "$dir/host-replay.log" "$host" --replay "$rec" --updates 3
    same "host, replay of the updates" "$dir/host-replay.log" "$ref"
    run "$dir/board-replay.log" $qemu -kernel "$elf" -append "--replay $rec --updates 3"
    same "board (QEMU mps2-an385), replay of the updates" "$dir/board-replay.log" "$ref"
    run "$dir/board-live.log" $(echo "$qemu" | sed 's/-serial none//') \
        -chardev "socket,id=link,host=127.0.0.1,port=$serial" -serial chardev:link -kernel "$elf" -append "--updates 2"
    changed "board, live over its UART with --updates 2" "$dir/board-live.log" 2
    grep -E '^(COST updates|MEM|stack)' "$dir/board-replay.log" | sed 's/^/    board replay: /'

    # the last 200 bytes (updates frames) damaged: refused, the scene kept
    size=$(wc -c <"$rec")
    head -c $((size - 200)) "$rec" >"$dir/bad.rec"
    head -c 200 /dev/zero | tr '\0' '\125' >>"$dir/bad.rec"
    run "$dir/bad.log" "$host" --replay "$dir/bad.rec" --updates 3
    if [ "$st" -eq 1 ] && grep -q '^client: error: updates' "$dir/bad.log" &&
       grep '^HASH frame-100' "$dir/bad.log.hash" | cmp -s - "$(grep '^HASH frame-100' "$ref" >"$dir/full.hash"; echo "$dir/full.hash")"; then
        ok "damaged updates refused: $(grep '^client: error' "$dir/bad.log" | head -1)"
    else
        bad "damaged updates (exit $st)"; tail -n 4 "$dir/bad.log" | sed 's/^/    /'
    fi
fi
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
