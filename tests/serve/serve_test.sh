#!/bin/sh
# tests/serve/serve_test.sh BIN TESTBIN WORKDIR MODELS — lumo-server over
# loopback, started and killed by this script (never left behind: trap),
# every server on free ports (--listen 127.0.0.1:0 --port-file). The
# clients are tests/serve/serve_client.c (the codec as a minimal client,
# checking every byte against the package); the servers are the sanitizer
# build (lumo-server-san) except for the 1000-client run, which measures the
# release build's memory. Prints "RESULT: N passed, M failed".
bin=$1; tbin=$2; dir=$3; models=$4
client=$tbin/serve_client
san=$tbin/lumo-server-san
mkdir -p "$dir"
. "$(dirname "$0")/../lib/background.sh"

# start NAME SERVER ARGS...: a server in the background on free ports; sets
# $pid and $ports ("TCP,SERIAL") once it listens (5 s at most).
start() {
    name=$1; shift
    spawn "$name" "$dir/$name.port" "$dir/$name.log" "$@" --listen 127.0.0.1:0 --port-file "$dir/$name.port" \
        || return 1
    ports=$(tr ' ' ',' <"$dir/$name.port")
}

# stop NAME: SIGTERM, the server must exit 0 within 5 s, its log clean of
# sanitizer reports.
stop() {
    kill -TERM "$pid" 2>/dev/null
    i=0
    while kill -0 "$pid" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
    if kill -0 "$pid" 2>/dev/null; then
        kill -9 "$pid"; wait "$pid" 2>/dev/null
        bad "$1: the server did not stop on SIGTERM within 5 s"; return
    fi
    wait "$pid"; st=$?
    if [ $st -ne 0 ] || grep -q "Sanitizer" "$dir/$1.log"; then
        bad "$1: server exit status $st"; grep -A12 "Sanitizer" "$dir/$1.log" | head -30 | sed 's/^/    /'
    else
        ok "$1: the server stopped on SIGTERM (exit 0, $(grep -c '^lumo-server: #' "$dir/$1.log") client lines)"
    fi
}

# run NAME CLIENT-ARGS...: a client run, its checks counted.
run() {
    name=$1; shift
    timeout 110 "$client" "$@" >"$dir/$name.out" 2>&1; st=$?
    p=$(sed -n 's/^RESULT: \([0-9]*\) passed.*/\1/p' "$dir/$name.out")
    f=$(sed -n 's/^RESULT: [0-9]* passed, \([0-9]*\) failed.*/\1/p' "$dir/$name.out")
    sed -n '/^ok\|^FAIL\|^    /p' "$dir/$name.out"
    if [ -z "$p" ]; then
        bad "$name: the client ended with status $st and no result"; tail -5 "$dir/$name.out" | sed 's/^/    /'
    else
        pass=$((pass + p)); fail=$((fail + f))
        [ "$st" -ne 0 ] && [ "$f" -eq 0 ] && bad "$name: client status $st"
    fi
}

# ---- packages ---------------------------------------------------------------------
dragon=$models/dragon_11k.ply
[ -f "$dragon" ] || { echo "RESULT: 0 passed, 1 failed ($dragon missing: run tools/setup.sh)"; exit 1; }
scene="$dir/scene.lumo"; split="$dir/split.lumo"; small="$dir/small.lumo"
"$bin/lumo-bake" --default --dragon "$dragon" --grid 12 --spp 8 --no-progress -o "$scene" 2>"$dir/bake.log" &&
"$bin/lumo-bake" --default --dragon "$dragon" --grid 32,8,8 --spp 4 --no-progress -o "$split" 2>>"$dir/bake.log" &&
"$bin/lumo-bake" --default --dragon sphere --grid 8 --spp 4 --no-progress -o "$small" 2>>"$dir/bake.log" ||
    { cat "$dir/bake.log"; echo "RESULT: 0 passed, 1 failed (lumo-bake)"; exit 1; }

# ---- the command line -------------------------------------------------------------
"$bin/lumo-server" --help | grep -q -- "--serial-listen" && ok "lumo-server --help" || bad "lumo-server --help"
expect_error() {   # expect_error NAME PATTERN ARGS...: exit 1, one "error:" line matching PATTERN
    name=$1; pat=$2; shift 2
    timeout 10 "$bin/lumo-server" "$@" >"$dir/out" 2>"$dir/err"; st=$?
    if [ $st -eq 1 ] && [ "$(wc -l <"$dir/err")" -eq 1 ] && grep -q "error:.*$pat" "$dir/err"; then
        ok "$name: $(cat "$dir/err")"
    else
        bad "$name (status $st)"; sed 's/^/    /' "$dir/err"
    fi
}
printf 'not a package at all, just text\n' >"$dir/text.lumo"
head -c 5000 "$scene" >"$dir/cut.lumo"
expect_error "no package"          "no package"
expect_error "missing file"        "No such file" "$dir/none.lumo"
expect_error "not a package"       "not a valid" "$dir/text.lumo"
expect_error "truncated package"   "not a valid" "$dir/cut.lumo"
if [ -f tests/server/data/v1_tiny.lumo ]; then
    expect_error "version-1 package" "re-bake" tests/server/data/v1_tiny.lumo
fi
expect_error "bad --rate"          "rate" "$scene" --rate fast
expect_error "bad --loss"          "loss" "$scene" --loss 2
expect_error "--loss without serial" "serial" "$scene" --loss 0.1
expect_error "bad address"         "address" "$scene" --listen nowhere
expect_error "unknown option"      "unknown" "$scene" --frobnicate

# lumo_client NAME PORTS ARGS...: the real client (the protocol driver and
# the session, tools/lumo-client) streams the first package to the end.
lumo_client() {
    name=$1; port=${2%%,*}; shift 2
    rm -rf "$dir/client"; mkdir -p "$dir/client"
    timeout 60 "$bin/lumo-client" --connect "127.0.0.1:$port" --out "$dir/client" --quiet --frames-at 100 "$@" \
        >"$dir/client.out" 2>&1; st=$?
    last=$(tail -n 1 "$dir/client/progress.csv" 2>/dev/null)
    if [ $st -eq 0 ] && echo "$last" | awk -F, '{ exit !($1 == 100 && $4 == $5 && $7 == $8 && $8 > 0) }'; then
        ok "$name: to the end through the session: $(tail -n 1 "$dir/client.out" | sed 's/^lumo-client: //')"
    else
        bad "$name (status $st): $last"; sed 's/^/    /' "$dir/client.out"
    fi
}

# ---- one server, several packages: whole fetches, resume, hostile frames ------------
if start main "$san" "$scene" "$split" "$small"; then
    run full         full "$ports" "$scene" --seed 1
    run full-small   full "$ports" "$scene" --seed 2 --max-payload 4096 --pipeline 4 --form f
    run full-split   full "$ports" "$split" --package 1 --seed 3 --max-payload 4096 --form f
    run full-one     full "$ports" "$small" --package 2 --seed 4 --pipeline 1 --form q
    run resume       resume "$ports" "$scene" --seed 5 --cuts 40
    run resume-split resume "$ports" "$split" --package 1 --seed 6 --cuts 25 --max-payload 4096 --form f
    run hostile      hostile "$ports" "$scene" --seed 7
    lumo_client "lumo-client" "$ports" --order interleaved
    lumo_client "lumo-client --float --order geometry" "$ports" --float --order geometry --size 64x48
    stop main
fi

# ---- idle and slow clients (a short --idle-timeout) --------------------------------
if start idle "$san" "$scene" --idle-timeout 2; then
    run idle idle "$ports" "$scene" --idle 2 --seed 8
    stop idle
fi

# ---- the serial listener: garbage, lost and damaged frames -------------------------
if start serial "$san" "$scene" --serial-listen 127.0.0.1:0 --loss 0.1 --seed 9; then
    run serial serial "$ports" "$scene" --seed 10 --expect-loss 1
    grep -q "serial: HELLO.*resyncs" "$dir/serial.log" && ok "serial: the server resynchronised on the client's garbage" ||
        bad "serial: no resynchronisation in the server's log"
    stop serial
fi

# ---- --max-clients, link emulation ------------------------------------------------
if start limit "$san" "$small" --max-clients 3; then
    run full-limit full-limit "$ports" "$small" 3
    stop limit
fi
if start link "$bin/lumo-server" "$scene" --rate 400 --latency 30; then
    run timing timing "$ports" "$scene" 400 30 --seed 11
    stop link
fi
if start link2 "$bin/lumo-server" "$scene" --rate 2000 --latency 20; then
    lumo_client "lumo-client over 2 Mbit/s, 20 ms (adaptive request sizes)" "$ports"
    stop link2
fi

# ---- 1000 clients at once: all finish, memory per client --------------------------
if start many "$bin/lumo-server" "$scene" --max-clients 2000 --quiet; then
    rss0=$(sed -n 's/^VmRSS:[^0-9]*\([0-9]*\).*/\1/p' /proc/$pid/status)
    run many many "$ports" "$scene" 1000 --max-payload 16384 --seed 12
    hwm=$(sed -n 's/^VmHWM:[^0-9]*\([0-9]*\).*/\1/p' /proc/$pid/status)
    per=$(( (hwm - rss0) * 1024 / 1000 ))
    if [ "$per" -le 16384 ]; then
        ok "many: server memory $rss0 KiB idle, $hwm KiB at its peak with 1000 clients: $per bytes per client (bound 16 KiB)"
    else
        bad "many: $per bytes per client (idle $rss0 KiB, peak $hwm KiB), more than 16 KiB"
    fi
    stop many
fi

# ---- SIGTERM while output is queued: drained by the deadline, then closed ------------
if start drain "$bin/lumo-server" "$scene" --rate 20; then
    timeout 20 "$client" full "$ports" "$scene" --seed 13 --pipeline 4 >"$dir/drain-client.out" 2>&1 &
    cpid=$!; pids="$pids $cpid"
    sleep 1
    t0=$(date +%s%N)
    kill -TERM "$pid"
    i=0
    while kill -0 "$pid" 2>/dev/null && [ $i -lt 60 ]; do sleep 0.1; i=$((i + 1)); done
    t1=$(date +%s%N)
    ms=$(( (t1 - t0) / 1000000 ))
    if kill -0 "$pid" 2>/dev/null; then
        kill -9 "$pid"; bad "drain: still running 6 s after SIGTERM"
    elif wait "$pid" && grep -q "shutting down: 1 clients" "$dir/drain.log" && [ "$ms" -lt 4000 ]; then
        ok "drain: SIGTERM with a slow client's output queued: exit 0 after $ms ms; $(grep '^lumo-server: #' "$dir/drain.log" | sed 's/.*: //')"
    else
        bad "drain: exit after $ms ms"; sed 's/^/    /' "$dir/drain.log"
    fi
    wait "$cpid" 2>/dev/null
fi

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
