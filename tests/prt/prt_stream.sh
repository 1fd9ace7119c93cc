#!/bin/sh
# tests/prt/prt_stream.sh BIN TESTBIN WORKDIR — PRT carried by the protocol
# (docs/protocol.md §10) end to end: lumo-server streams each mesh's PRTV
# after the WELCOME's PRTV header and PRTL, lumo-client --prt asks for it in
# step with the geometry and relights from its session. The streamed
# picture must equal lumo-render --prt of the package byte for byte: plain,
# with frames of 4 KiB (the clusters split over frames), through a proxy
# that cuts the connection at random points (resumed from the PRT cursor
# held), recorded and replayed, and with the lighting turned per frame.
# A client without --prt gets the plain WELCOME; --prt on a package without
# PRT is one clear error. Every process is bounded by `timeout` and killed
# by the trap. Prints "RESULT: N passed, M failed".
bin=$1; tbin=$2; dir=$3
mkdir -p "$dir"
. "$(dirname "$0")/../lib/background.sh"

start() {
    spawn "$1" "$dir/$1.port" "$dir/$1.log" \
        timeout 120 "$bin/lumo-server" "$2" --listen 127.0.0.1:0 --port-file "$dir/$1.port" || return 1
    port=$(cut -d' ' -f1 "$dir/$1.port")
}
# lc NAME ARGS...: lumo-client into $dir/NAME (60 s at most); $st its status.
lc() {
    name=$1; shift
    rm -rf "${dir:?}/$name"; mkdir -p "$dir/$name"
    timeout 60 "$bin/lumo-client" --out "$dir/$name" --quiet --per-vertex "$@" >"$dir/$name.out" 2>"$dir/$name.err"
    st=$?
}
show() { sed 's/^/    /' "$dir/$1.out" "$dir/$1.err" | tail -n 6; }
# same NAME WHAT PNG: the run ended 0 and its last frame is PNG byte for byte
same() {
    if [ "$st" -eq 0 ] && cmp -s "$dir/$1/frame-100.00.png" "$3"; then ok "$2"
    else bad "$2 (status $st)"; show "$1"; fi
}

"$bin/prt-demo" env "$dir/sky.png" 64 32 || bad "prt-demo env"
bake="$bin/lumo-bake build/data/models/bunny.obj --light directional:0.3,-1,0.2:2,2,2 --grid 3 --spp 2 --threads 2 --no-progress"
$bake --prt 6,clusters=64,components=8,strata=8 --prt-env "$dir/sky.png" -o "$dir/prt.lumo" 2>"$dir/bake.log" \
    || { bad "bake"; cat "$dir/bake.log"; }
$bake -o "$dir/plain.lumo" 2>/dev/null || bad "plain bake"
"$bin/lumo-render" "$dir/prt.lumo" --prt --per-vertex -o "$dir/render.png" >/dev/null 2>&1 || bad "lumo-render --prt"
"$bin/lumo-render" "$dir/prt.lumo" --prt --per-vertex --frames 3 --rotate 40 -o "$dir/turn.png" >/dev/null 2>&1 \
    || bad "lumo-render --prt --rotate"

if start srv "$dir/prt.lumo"; then
    lc plain --connect "127.0.0.1:$port" --prt
    same plain "streamed PRT = the package's PRT picture: $(cat "$dir/plain.out")" "$dir/render.png"
    lc small --connect "127.0.0.1:$port" --prt --max-payload 4096
    same small "frames of 4 KiB (clusters split over frames)" "$dir/render.png"
    lc rec --connect "127.0.0.1:$port" --prt --record "$dir/prt.rec"
    lc rep --replay "$dir/prt.rec" --prt
    same rep "recorded and replayed" "$dir/render.png"
    lc turn --connect "127.0.0.1:$port" --prt --rotate 40 --frames-at 50,100
    same turn "the lighting turned 40 degrees a frame drawn (frame 2 = lumo-render's third)" "$dir/turn_002.png"
    cmp -s "$dir/turn/frame-050.00.png" "$dir/turn/frame-100.00.png" && bad "a turned sky changes nothing" \
        || ok "a turned sky changes the frame"
    lc noprt --connect "127.0.0.1:$port"
    if [ "$st" -eq 0 ] && ! cmp -s "$dir/noprt/frame-100.00.png" "$dir/render.png"; then
        ok "without --prt: the plain scene ($(cat "$dir/noprt.out"))"
    else bad "without --prt"; show noprt; fi
    # cuts: the proxy drops the connection 6 times at random points; the
    # client resumes from the cursors it holds, the PRT's among them
    pid_srv=$pid
    spawn "cut proxy" "$dir/cut.pport" "$dir/cut.plog" timeout 100 "$tbin/cut_proxy" --upstream "127.0.0.1:$port" \
        --port-file "$dir/cut.pport" --stats "$dir/cut.stats" --cuts 6 --span 40000 --seed 7
    pport=$(cat "$dir/cut.pport" 2>/dev/null)
    lc cut --connect "127.0.0.1:$pport" --prt --retries 10 --max-payload 8192
    same cut "cut $(grep -c ' cut 1$' "$dir/cut.stats" 2>/dev/null) times and resumed" "$dir/render.png"
    pid=$pid_srv
else bad "lumo-server did not start"; fi

if start plainsrv "$dir/plain.lumo"; then
    lc noprt_pkg --connect "127.0.0.1:$port" --prt
    if [ "$st" -ne 0 ] && grep -q "has no PRT" "$dir/noprt_pkg.err"; then ok "--prt, package without: $(cat "$dir/noprt_pkg.err")"
    else bad "--prt on a package without PRT"; show noprt_pkg; fi
fi
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
