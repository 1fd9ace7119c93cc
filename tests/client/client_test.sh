#!/bin/sh
# tests/client/client_test.sh BIN TESTBIN WORKDIR MODELS — lumo-client end to
# end against lumo-server on loopback (free ports: --listen 127.0.0.1:0
# --port-file). Every process it starts is bounded by `timeout` and killed by
# the trap. Prints "RESULT: N passed, M failed".
bin=$1; tbin=$2; dir=$3; models=$4
client=$bin/lumo-client
mkdir -p "$dir"
. "$(dirname "$0")/../lib/background.sh"

# start NAME ARGS...: lumo-server in the background on free ports; sets $pid,
# $port (TCP) and $sport (serial, when asked for) once it listens.
start() {
    name=$1; shift
    spawn "$name" "$dir/$name.port" "$dir/$name.log" \
        timeout 300 "$bin/lumo-server" "$@" --listen 127.0.0.1:0 --port-file "$dir/$name.port" || return 1
    port=$(cut -d' ' -f1 "$dir/$name.port"); sport=$(cut -d' ' -f2 "$dir/$name.port")
}
stop() { kill -TERM "$pid" 2>/dev/null; wait "$pid" 2>/dev/null; }

# proxy NAME UPSTREAM-PORT ARGS...: tests/client/cut_proxy in the background;
# sets $ppid and $pport once it listens. Its lines go to $dir/NAME.stats.
proxy() {
    name=$1; up=$2; shift 2
    server_pid=$pid   # spawn sets $pid: keep the server's for stop()
    spawn "$name proxy" "$dir/$name.pport" "$dir/$name.plog" timeout 150 "$tbin/cut_proxy" \
        --upstream "127.0.0.1:$up" --port-file "$dir/$name.pport" --stats "$dir/$name.stats" "$@"
    st_proxy=$?
    ppid=$pid; pid=$server_pid
    [ $st_proxy -eq 0 ] || return 1
    pport=$(cat "$dir/$name.pport")
}
# stat NAME FIELD: the sum of a field over the proxy's connections.
# stop_proxy NAME: the proxy logs a connection when it closes, a moment after
# the client has gone: wait (5 s at most) for the last, uncut connection's
# line, then stop it (stopping it first lost that line's bytes now and then).
stop_proxy() {
    i=0
    while ! grep -q ' cut 0$' "$dir/$1.stats" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
    kill "$ppid" 2>/dev/null; wait "$ppid" 2>/dev/null
}
stat() { awk -v k="$2" '{ for (i = 1; i < NF; i++) if ($i == k) s += $(i + 1) } END { print s + 0 }' "$dir/$1.stats"; }

# lc NAME ARGS...: lumo-client into $dir/NAME (60 s at most); $st its status.
lc() {
    name=$1; shift
    rm -rf "${dir:?}/$name"; mkdir -p "$dir/$name"
    timeout 60 "$client" --out "$dir/$name" --quiet "$@" >"$dir/$name.out" 2>"$dir/$name.err"; st=$?
}
# complete NAME: the run ended 0 with the whole scene in its last progress row.
complete() {
    last=$(tail -n 1 "$dir/$1/progress.csv" 2>/dev/null)
    [ "$st" -eq 0 ] && echo "$last" | awk -F, '{ exit !($1 == 100 && $4 == $5 && $7 == $8 && $8 > 0) }'
}
show() { sed 's/^/    /' "$dir/$1.out" "$dir/$1.err" | tail -n 8; }
# same_frames A B: every PNG of A is in B, byte for byte (and B has no other).
same_frames() {
    [ "$(cd "$dir/$1" && ls ./*.png)" = "$(cd "$dir/$2" && ls ./*.png)" ] || return 1
    for f in "$dir/$1"/*.png; do cmp -s "$f" "$dir/$2/$(basename "$f")" || return 1; done
}
# progress NAME: progress.csv without its timing column (ms) and frame directory.
progress() { awk -F, 'BEGIN { OFS = "," } { $9 = ""; sub(".*/", "", $10); print }' "$dir/$1/progress.csv"; }
# flip FILE OFFSET: one byte changed (xor 0x55) in place.
flip() {
    b=$(od -An -tu1 -j "$2" -N1 "$1" | tr -d ' ')
    printf "\\$(printf %o $((b ^ 85)))" | dd of="$1" bs=1 seek="$2" conv=notrunc 2>/dev/null
}
summary_field() { sed -n "s/.* \([0-9]*\) $1.*/\1/p" "$dir/$2.out"; }

# listening PORT: something listens on 127.0.0.1:PORT (Linux: /proc/net/tcp).
listening() { grep -qi "0100007F:$(printf %04X "$1") 00000000:0000 0A" /proc/net/tcp; }

# nginx_start DIR FILES...: Debian's nginx serving FILES from DIR/www on a free
# loopback port (a generated minimal nginx.conf, daemon off, in the
# background, killed by the trap); sets $npid and $hport.
nginx_start() {
    command -v nginx >/dev/null || { bad "nginx missing (nginx-light: run tools/setup.sh)"; return 1; }
    rm -rf "$1"; mkdir -p "$1/www" "$1/tmp"
    ng=$(cd "$1" && pwd); shift   # nginx wants absolute paths
    cp "$@" "$ng/www/"
    for try in 1 2 3 4 5 6; do
        hport=$(( 20000 + ($(date +%N | sed 's/^0*//;s/^$/0/') / 1000 + try * 7919) % 40000 ))
        listening "$hport" && continue
        cat >"$ng/nginx.conf" <<EOF
daemon off;
master_process off;
worker_processes 1;
pid $ng/nginx.pid;
error_log $ng/error.log;
events { worker_connections 64; }
http {
    access_log $ng/access.log;
    client_body_temp_path $ng/tmp/body;
    proxy_temp_path $ng/tmp/proxy;
    fastcgi_temp_path $ng/tmp/fastcgi;
    uwsgi_temp_path $ng/tmp/uwsgi;
    scgi_temp_path $ng/tmp/scgi;
    types { application/octet-stream lumo; }
    server {
        listen 127.0.0.1:$hport;
        root $ng/www;
    }
}
EOF
        timeout 300 nginx -c "$ng/nginx.conf" -p "$ng/" >"$ng/stderr" 2>&1 &
        npid=$!
        pids="$pids $npid"
        i=0
        while kill -0 "$npid" 2>/dev/null && ! listening "$hport" && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
        listening "$hport" && kill -0 "$npid" 2>/dev/null && return 0
        kill "$npid" 2>/dev/null; wait "$npid" 2>/dev/null
    done
    bad "nginx did not start"; sed 's/^/    /' "$ng/stderr" "$ng/error.log" 2>/dev/null | tail -5
    return 1
}

# ---- the packages -----------------------------------------------------------------
dragon=$models/dragon_11k.ply
[ -f "$dragon" ] || { echo "RESULT: 0 passed, 1 failed ($dragon missing: run tools/setup.sh)"; exit 1; }
scene="$dir/scene.lumo"; split="$dir/split.lumo"
timeout 120 "$bin/lumo-bake" --default --dragon "$dragon" --grid 12 --spp 8 --no-progress -o "$scene" 2>"$dir/bake.log" &&
timeout 120 "$bin/lumo-bake" --default --dragon "$dragon" --grid 32,8,8 --spp 4 --no-progress -o "$split" 2>>"$dir/bake.log" ||
    { cat "$dir/bake.log"; echo "RESULT: 0 passed, 1 failed (lumo-bake)"; exit 1; }
AT=5,10,25,50,75,100

# ---- the command line ---------------------------------------------------------------
if timeout 10 "$client" --help >"$dir/help.out" 2>&1 && grep -q -- "--record FILE" "$dir/help.out"; then
    ok "lumo-client --help"
else
    bad "lumo-client --help"
fi
timeout 10 "$client" --connect 127.0.0.1:1 --replay x >/dev/null 2>&1
[ $? -eq 2 ] && ok "two sources: usage, status 2" || bad "two sources"

if start main "$scene" "$split"; then
    # ---- record / replay ----------------------------------------------------------
    lc live --connect "127.0.0.1:$port" --frames-at $AT --record "$dir/live.rec"
    if complete live; then ok "live run with --record: $(sed 's/^lumo-client: //' "$dir/live.out")"; else bad "live run"; show live; fi
    lc replay --replay "$dir/live.rec" --frames-at $AT
    if complete replay && same_frames live replay; then
        ok "--replay: the same $(ls "$dir/live"/*.png | wc -l) PNG frames, byte for byte"
    else
        bad "--replay frames"; show replay
    fi
    if progress live >"$dir/a.csv" && progress replay >"$dir/b.csv" && cmp -s "$dir/a.csv" "$dir/b.csv"; then
        ok "--replay: progress.csv the same but for its ms column"
    else
        bad "--replay progress.csv"; diff "$dir/a.csv" "$dir/b.csv" | head -5 | sed 's/^/    /'
    fi
    inb=$(summary_field "bytes in" live)
    if [ "$(wc -c <"$dir/live.rec")" -eq "$inb" ]; then
        ok "the recording of an uncut TCP run is the received byte stream ($inb bytes)"
    else
        bad "recording $(wc -c <"$dir/live.rec") bytes, $inb received"
    fi

    # a damaged recording: a byte flipped half-way, then cut short
    size=$(wc -c <"$dir/live.rec")
    cp "$dir/live.rec" "$dir/damaged.rec"
    flip "$dir/damaged.rec" $((size / 2))
    lc damaged --replay "$dir/damaged.rec" --frames-at $AT
    n=$(ls "$dir/damaged"/*.png 2>/dev/null | wc -l)
    kept=1
    for f in "$dir/damaged"/*.png; do cmp -s "$f" "$dir/live/$(basename "$f")" || kept=0; done
    if [ "$st" -eq 1 ] && [ "$(wc -l <"$dir/damaged.err")" -eq 1 ] && grep -q "error: .*damaged frame at byte" "$dir/damaged.err" &&
        [ "$n" -ge 1 ] && [ "$n" -lt "$(ls "$dir/live"/*.png | wc -l)" ] && [ $kept -eq 1 ]; then
        ok "damaged recording: status 1, $n frames kept (equal to the live run's): $(sed 's/^lumo-client: //' "$dir/damaged.err")"
    else
        bad "damaged recording (status $st, $n frames, kept $kept)"; show damaged
    fi
    head -c $((size - 5)) "$dir/live.rec" >"$dir/short.rec"
    lc short --replay "$dir/short.rec" --frames-at $AT
    if [ "$st" -eq 1 ] && grep -q "error: .*ends inside a frame" "$dir/short.err"; then
        ok "truncated recording: $(sed 's/^lumo-client: //' "$dir/short.err")"
    else
        bad "truncated recording (status $st)"; show short
    fi

    # ---- resume after cuts -------------------------------------------------------------
    # Fixed request sizes: the answers are the same frames however the run is
    # cut (each request starts at a cursor of the uncut run), so the bytes
    # received twice are exactly the frames cut mid-way and the WELCOMEs of
    # the new connections.
    FIXED="--vertices 300 --rounds 5 --pipeline 4"
    if proxy uncut "$port" --cuts 0; then
        lc uncut --connect "127.0.0.1:$pport" --frames-at $AT $FIXED --record "$dir/uncut.rec"
        stop_proxy uncut
        if complete uncut; then ok "uncut run through the proxy: $(sed 's/^lumo-client: //' "$dir/uncut.out")"; else bad "uncut run"; show uncut; fi
    fi
    total=$(summary_field "bytes in" uncut)
    for seed in 1 2 3; do
        r=cut$seed
        proxy "$r" "$port" --cuts 8 --span $((total / 6)) --seed $seed || continue
        lc "$r" --connect "127.0.0.1:$pport" --frames-at $AT $FIXED --retries 5 --record "$dir/$r.rec"
        stop_proxy "$r"
        cuts=$(stat "$r" cut); partial=$(stat "$r" partial)
        extra=$(( $(summary_field "bytes in" "$r") - total ))
        welcomes=$(( $(stat "$r" welcome) - $(stat uncut welcome) ))
        said=$(sed -n 's/.*; \([0-9]*\) cuts resumed, \([0-9]*\) bytes of frames cut mid-way.*/\1 \2/p' "$dir/$r.out")
        if ! complete "$r"; then
            bad "$r: did not finish"; show "$r"
        elif ! same_frames uncut "$r"; then
            bad "$r: frames differ from the uncut run's"
        elif [ "$(stat "$r" data)" -ne "$(stat uncut data)" ] || [ "$extra" -ne $((welcomes + partial)) ] ||
             [ "$said" != "$cuts $partial" ]; then
            bad "$r: $cuts cuts, $extra bytes more than uncut, $welcomes of WELCOMEs, $partial of cut frames (client: $said); DATA bytes $(stat "$r" data) vs $(stat uncut data)"
        else
            ok "$r: $cuts cuts resumed, the same $(ls "$dir/$r"/*.png | wc -l) frames as uncut; $extra bytes more = $welcomes of new WELCOMEs + $partial of frames cut mid-way; the same $(stat uncut data) DATA bytes"
        fi
        [ "$cuts" -ge 3 ] || bad "$r: only $cuts cuts made"
        lc "$r-replay" --replay "$dir/$r.rec" --frames-at $AT
        if complete "$r-replay" && same_frames uncut "$r-replay" && [ "$(wc -c <"$dir/$r.rec")" -eq "$total" ]; then
            ok "$r: its recording ($(wc -c <"$dir/$r.rec") bytes, as many as the uncut run received) replays to the same frames"
        else
            bad "$r: replay of a cut run's recording"; show "$r-replay"
        fi
    done
    # retries run out: the proxy serves one connection, cuts it and goes away
    if proxy gone "$port" --cuts 1 --span 3000 --max-conns 1; then
        t0=$(date +%s)
        lc gone --connect "127.0.0.1:$pport" $FIXED --retries 3
        t1=$(date +%s)
        if [ "$st" -eq 1 ] && [ "$(wc -l <"$dir/gone.err")" -eq 1 ] && grep -q "connection lost after frame .*3 reconnections" "$dir/gone.err" &&
           [ $((t1 - t0)) -lt 10 ]; then
            ok "retries bounded: $(sed 's/^lumo-client: //' "$dir/gone.err")"
        else
            bad "retries (status $st, $((t1 - t0)) s)"; show gone
        fi
        wait "$ppid" 2>/dev/null
    fi

    # ---- HTTP: the same package from nginx with Range requests -----------------------
    printf 'this is a text file, not a package at all; %0200d\n' 0 >"$dir/junk.lumo"
    if nginx_start "$dir/nginx" "$scene" "$split" "$dir/junk.lumo" tests/server/data/v1_tiny.lumo; then
        url="http://127.0.0.1:$hport"
        for v in "scene.lumo 0 --vertices 300 --rounds 5" "split.lumo 1 --vertices 150 --rounds 3 --float --max-payload 4096 --pipeline 8"; do
            file=${v%% *}; rest=${v#* }; pkg=${rest%% *}; args=${rest#* }
            lc "http-$file" --http "$url/$file" --frames-at $AT $args --record "$dir/http-$file.rec"
            lc "tcp-$file" --connect "127.0.0.1:$port" --package "$pkg" --frames-at $AT $args --record "$dir/tcp-$file.rec"
            fetched=$(sed -n 's/.*; \([0-9]*\) range requests, \([0-9]*\) bytes fetched.*/\1 \2/p' "$dir/http-$file.out")
            if complete "http-$file" && complete "tcp-$file" && same_frames "tcp-$file" "http-$file" &&
               cmp -s "$dir/http-$file.rec" "$dir/tcp-$file.rec"; then
                ok "http $file $args: the TCP run's $(ls "$dir/http-$file"/*.png | wc -l) frames and its $(wc -c <"$dir/tcp-$file.rec") received bytes, byte for byte, from ${fetched% *} range requests of ${fetched#* } bytes (the package: $(wc -c <"$dir/nginx/www/$file"))"
            else
                bad "http $file $args"; show "http-$file"; show "tcp-$file"
            fi
        done
        lc http-adaptive --http "$url/scene.lumo" --frames-at 50,100
        if complete http-adaptive && cmp -s "$dir/http-adaptive/frame-100.00.png" "$dir/live/frame-100.00.png"; then
            ok "http, adaptive sizes: the full scene, the TCP run's last frame: $(sed 's/.*bytes; //' "$dir/http-adaptive.out")"
        else
            bad "http adaptive"; show http-adaptive
        fi
        for v in "none.lumo:HTTP 404" "junk.lumo:not a valid package" "v1_tiny.lumo:re-bake"; do
            lc http-err --http "$url/${v%%:*}"
            if [ "$st" -eq 1 ] && [ "$(wc -l <"$dir/http-err.err")" -eq 1 ] && grep -q "error: .*${v#*:}" "$dir/http-err.err"; then
                ok "http ${v%%:*}: $(sed 's/^lumo-client: //' "$dir/http-err.err")"
            else
                bad "http ${v%%:*} (status $st)"; show http-err
            fi
        done
        kill "$npid" 2>/dev/null; wait "$npid" 2>/dev/null
    fi

    stop
fi

# ---- the serial line: --serial against --serial-listen --loss 0.05 ---------------------
if start serial "$scene" --serial-listen 127.0.0.1:0 --loss 0.05 --seed 9; then
    damaged=0
    for args in "--pipeline 1" "--pipeline 4" "--pipeline 8 --order lighting" "--vertices 300 --rounds 5 --order geometry" \
                "--float --pipeline 2"; do
        r=serial$(echo "$args" | tr -cd '0-9a-z')
        lc "$r" --serial "127.0.0.1:$sport" --frames-at 50,100 $args --record "$dir/$r.rec"
        refused=$(sed -n 's/.*; \([0-9]*\) frames refused, \([0-9]*\) silences.*/\1 \2/p' "$dir/$r.out")
        damaged=$((damaged + ${refused% *} + ${refused#* }))
        if complete "$r" && { [ -n "$args" ] && [ "${args#*float}" != "$args" ] || cmp -s "$dir/$r/frame-100.00.png" "$dir/live/frame-100.00.png"; }; then
            ok "serial $args: the full scene$( [ "${args#*float}" = "$args" ] && echo ", the TCP run's last frame byte for byte"): $(sed 's/.*bytes; //' "$dir/$r.out")"
        else
            bad "serial $args"; show "$r"
        fi
    done
    [ "$damaged" -gt 0 ] && ok "serial: the client saw $damaged damaged or lost frames" || bad "serial: no damage seen (--loss 0.05)"
    lc serial-replay --replay "$dir/serialpipeline4.rec" --frames-at 50,100
    if complete serial-replay && same_frames serialpipeline4 serial-replay; then
        ok "serial: the recording (only the frames taken) replays to the same frames"
    else
        bad "serial: replay"; show serial-replay
    fi
    stop
fi

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
