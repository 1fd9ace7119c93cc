#!/bin/sh
# bench/stream.sh BUILD BIN — streaming through lumo-server's emulated link
# and the server's own costs (`make bench-stream`, bench/stream.mk). Writes
# BUILD/bench/sections/70-stream.md and docs/bench-stream-fig{5,6,7}.png.
#
#  a. first picture and full scene at 1 Mbit/s, 50 ms, the three orders
#     (lumo-client, and lumo-bench-stream: the same driver without drawing)
#  b. seed 000 Fig. 5: geometry download time against request size
#  c. Fig. 6: the IVG, quantized and binary32, against rounds per request
#  d. Fig. 7: push-pull with and without smoothing, over the protocol
#  e. server throughput, CPU per MB and memory per client, 10/100/1000
#     clients on loopback without link emulation
#
# Every server is started here on a free port and stopped here; every client
# has an alarm (lumo-bench-stream: 120 s) or a timeout.
set -eu
build=$1; bin=$2
dir="$build/bench/stream"; out="$build/bench/sections/70-stream.md"
bench="$bin/lumo-bench-stream"
models="$build/data/models"
mkdir -p "$dir" "$(dirname "$out")" docs
started=$(date +%s)
load0=$(cut -d' ' -f1-3 /proc/loadavg)

SRV_PID=
PORT=
stop() {
    if [ -n "$SRV_PID" ]; then
        kill "$SRV_PID" 2>/dev/null || true
        wait "$SRV_PID" 2>/dev/null || true
        SRV_PID=
    fi
}
trap stop EXIT INT TERM
start() {  # start NAME PACKAGE... [server options]: one lumo-server on a free port
    name=$1; shift
    rm -f "$dir/$name.port"
    "$bin/lumo-server" "$@" --listen 127.0.0.1:0 --port-file "$dir/$name.port" --quiet 2>"$dir/$name.log" &
    SRV_PID=$!
    n=0
    while [ ! -s "$dir/$name.port" ]; do
        n=$((n + 1))
        if [ $n -gt 200 ] || ! kill -0 "$SRV_PID" 2>/dev/null; then
            echo "bench-stream: lumo-server $name did not start (see $dir/$name.log)" >&2
            exit 1
        fi
        sleep 0.05
    done
    PORT=$(cut -d' ' -f1 "$dir/$name.port")
}
kv() {  # kv FILE KEY: the value of KEY=value in FILE's first line
    head -1 "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"
}
run() {  # run OUTFILE ARGS...: one lumo-bench-stream run against PORT
    f=$1; shift
    if ! "$bench" run "127.0.0.1:$PORT" "$@" >"$f" 2>"$f.err"; then
        echo "bench-stream: lumo-bench-stream run $* failed: $(cat "$f.err")" >&2
        exit 1
    fi
}
median3() { printf '%s\n%s\n%s\n' "$1" "$2" "$3" | sort -g | sed -n 2p; }

# ---- packages ------------------------------------------------------------------------
# default: lumo-bake --default (Cornell box + dragon 48k, 16^3 grid, 256 spp)
# d203:    the same scene with the 203k dragon (Fig. 5: a larger mesh; lighting unused)
# g32:     the default scene with a 32^3 grid, 16 spp (Figs. 6 and 7, the paper's grid)
"$bin/lumo-bake" --default --dragon "$models/dragon_48k.ply" --no-progress -o "$dir/default.lumo" >"$dir/bake.log" 2>&1
"$bin/lumo-bake" --default --dragon "$models/dragon_203k.ply" --spp 16 --no-progress -o "$dir/d203.lumo" >>"$dir/bake.log" 2>&1
"$bin/lumo-bake" --default --dragon "$models/dragon_48k.ply" --grid 32 --spp 16 --no-progress -o "$dir/g32.lumo" >>"$dir/bake.log" 2>&1

# ---- a. first picture and full scene, 1 Mbit/s, 50 ms --------------------------------
RATE_A=1000; LAT_A=50
start a "$dir/default.lumo" --rate $RATE_A --latency $LAT_A
for order in interleaved geometry lighting; do
    for r in 1 2 3; do run "$dir/a-$order-$r.txt" --order $order; done
    # the run of median full-scene time stands for the order (adaptive sizes vary run to run)
    m=$(median3 $(for r in 1 2 3; do kv "$dir/a-$order-$r.txt" full_us; done))
    for r in 1 2 3; do
        if [ "$(kv "$dir/a-$order-$r.txt" full_us)" = "$m" ]; then cp "$dir/a-$order-$r.txt" "$dir/a-$order.txt"; fi
    done
    for r in 1 2 3; do kv "$dir/a-$order-$r.txt" full_us; done | sort -n | awk '{ v[NR] = $1 / 1e6 }
        END { printf "%.3f-%.3f", v[1], v[NR] }' >"$dir/a-$order.range"
    timeout 60 "$bin/lumo-client" --connect "127.0.0.1:$PORT" --order $order --quiet --out "$dir/client-$order" \
        >"$dir/a-client-$order.txt" 2>&1
done
run "$dir/a-fixed.txt" --vertices 100000 --rounds 1000
timeout 60 "$bin/lumo-client" --connect "127.0.0.1:$PORT" --vertices 100000 --rounds 1000 --quiet \
    --out "$dir/client-fixed" >"$dir/a-client-fixed.txt" 2>&1
stop
start a0 "$dir/default.lumo" --rate $RATE_A
run "$dir/a0-fixed.txt" --vertices 100000 --rounds 1000
stop

client_ms() {  # client_ms FILE: "TOTAL FIRST" from lumo-client's summary line
    sed -n 's/.* \([0-9]*\) ms; first picture after \([0-9]*\) ms.*/\1 \2/p' "$1"
}
arow() {  # arow LABEL FILE CLIENTFILE RANGE
    f=$2; c=$3; range=$4
    set -- $(client_ms "$c")
    awk -v label="$label" -v first="$(kv "$f" first_us)" -v full="$(kv "$f" full_us)" -v bytes="$(kv "$f" bytes_in)" \
        -v req="$(kv "$f" requests)" -v rate=$RATE_A -v lat=$LAT_A -v ctot="${1:-0}" -v cfirst="${2:--}" \
        -v range="$range" 'BEGIN {
        ideal = bytes * 8 / (rate * 1000); goal = 1.1 * ideal; floor = ideal + 2 * lat / 1000
        printf "| %s | %.0f | %s | %s | %.3f | %s | %.3f | %d | %d | %.3f | %.3f | %.3f | %+.1f %% | %s |\n", label,
            first / 1000, first <= 500000 ? "**yes**" : "no", cfirst, full / 1e6, range, ctot / 1000, bytes, req,
            ideal, floor, goal, 100 * (full / 1e6 / ideal - 1), full / 1e6 <= goal ? "**yes**" : "no" }'
}
{
    label="interleaved (default)"; arow "$label" "$dir/a-interleaved.txt" "$dir/a-client-interleaved.txt" "$(cat "$dir/a-interleaved.range")"
    label="geometry first"; arow "$label" "$dir/a-geometry.txt" "$dir/a-client-geometry.txt" "$(cat "$dir/a-geometry.range")"
    label="lighting first"; arow "$label" "$dir/a-lighting.txt" "$dir/a-client-lighting.txt" "$(cat "$dir/a-lighting.range")"
    label="interleaved, --vertices 100000 --rounds 1000"; arow "$label" "$dir/a-fixed.txt" "$dir/a-client-fixed.txt" "1 run"
} >"$dir/a-rows.md"
a0_full=$(kv "$dir/a0-fixed.txt" full_us)

# ---- b. Fig. 5: geometry against request size ----------------------------------------
# The 203k dragon's stream, lighting excluded (HELLO asks for no IVG), geometry
# first; the time from WELCOME to the last batch applied (the client's work
# included, as in the paper). 20 Mbit/s and 1 ms each way (802.11g-like, the
# link of the modelled Fig. 5 in bench-pm), stop-and-wait (--pipeline 1, the
# paper's client) and the default pipeline; median of 3. And 1 Mbit/s, 50 ms
# with the default pipeline (stop-and-wait there takes a round trip per batch).
RATE_B=20000; LAT_B=1
SIZES_B="250 500 1000 2500 5000 10000 100000"
start b "$dir/d203.lumo" --rate $RATE_B --latency $LAT_B
: >"$dir/fig5.dat"
for r in 1 2 3; do   # repetitions outermost: a burst of other load hits one run of a size, not all three
    for n in $SIZES_B; do
        run "$dir/b-$n-1-$r.txt" --no-ivg --order geometry --vertices $n --pipeline 1
        run "$dir/b-$n-auto-$r.txt" --no-ivg --order geometry --vertices $n
    done
done
for n in $SIZES_B; do
    t1=$(median3 $(for r in 1 2 3; do f="$dir/b-$n-1-$r.txt"; echo $(( $(kv $f geometry_us) - $(kv $f welcome_us) )); done))
    ta=$(median3 $(for r in 1 2 3; do f="$dir/b-$n-auto-$r.txt"; echo $(( $(kv $f geometry_us) - $(kv $f welcome_us) )); done))
    ap=$(median3 $(for r in 1 2 3; do kv "$dir/b-$n-auto-$r.txt" geometry_apply_cpu_us; done))
    f="$dir/b-$n-auto-1.txt"
    echo "$n $t1 $ta $ap $(kv $f requests) $(kv $f geometry_bytes) $(kv $f data_frames)" >>"$dir/fig5.dat"
done
stop
SIZES_BS="250 1000 5000 100000"
start bs "$dir/d203.lumo" --rate $RATE_A --latency $LAT_A
: >"$dir/fig5s.dat"
for n in $SIZES_BS; do
    run "$dir/bs-$n.txt" --no-ivg --order geometry --vertices $n
    f="$dir/bs-$n.txt"
    echo "$n $(( $(kv $f geometry_us) - $(kv $f welcome_us) )) $(kv $f geometry_apply_cpu_us) $(kv $f requests) $(kv $f geometry_bytes)" >>"$dir/fig5s.dat"
done
stop
geo_bytes=$(awk 'NR == 1 { print $6 }' "$dir/fig5.dat")

# ---- c, d. Figs. 6 and 7: the 32^3 IVG against rounds per request -------------------
# Lighting first, geometry fixed (one request per mesh, after the lighting);
# the time from WELCOME to the last round applied. A round is one record per
# slice of the grid's longest axis (32 slices): K rounds per request = the
# paper's "K samples per slice". Client work = CPU time inside the driver for
# lighting DATA (records applied: dequantized or copied, and push-pull).
SIZES_C="4 8 16 32 64 128 256 1024"
start c "$dir/g32.lumo" --rate $RATE_B --latency $LAT_B
: >"$dir/fig6.dat"
for k in $SIZES_C; do
    run "$dir/c-q-$k.txt" --order lighting --vertices 100000000 --rounds $k
    run "$dir/c-f-$k.txt" --order lighting --vertices 100000000 --rounds $k --float
    run "$dir/c-n-$k.txt" --order lighting --vertices 100000000 --rounds $k --no-smoothing
    line="$k"
    for m in q f n; do
        f="$dir/c-$m-$k.txt"
        line="$line $(( $(kv $f lighting_us) - $(kv $f welcome_us) )) $(kv $f lighting_apply_cpu_us) $(kv $f pushpull_cpu_us) $(kv $f pushpull_calls) $(kv $f lighting_bytes)"
    done
    # columns 17-19: the median push-pull call in CPU µs of q, f, n
    for m in q f n; do line="$line $(kv "$dir/c-$m-$k.txt" pushpull_cpu_median_us)"; done
    echo "$line" >>"$dir/fig6.dat"
done
stop
rounds_c=$(kv "$dir/c-q-4.txt" rounds)

# ---- e. server throughput, CPU and memory per client --------------------------------
# lumo-bench-stream load: N clients at once, each fetching the whole default
# scene R times (one request per mesh and one for the lighting, two fetches in
# flight, 64 KiB frames), payloads skipped unchecked. Server CPU: utime +
# stime from /proc/PID/stat; memory: VmHWM at the end minus VmRSS before the
# clients came, per client (kernel socket buffers not included).
tck=$(getconf CLK_TCK)
cpu_ticks() { awk '{ print $14 + $15 }' "/proc/$1/stat"; }
vm() { sed -n "s/^$2:[^0-9]*\([0-9]*\).*/\1/p" "/proc/$1/status"; }
: >"$dir/load.dat"
for nr in "10 50" "100 5" "1000 1"; do
    set -- $nr
    start "e$1" "$dir/default.lumo" --max-clients 2000
    rss0=$(vm $SRV_PID VmRSS); c0=$(cpu_ticks $SRV_PID)
    if ! "$bench" load "127.0.0.1:$PORT" "$1" "$2" >"$dir/e-$1.txt" 2>"$dir/e-$1.err"; then
        echo "bench-stream: load $1 $2 failed: $(cat "$dir/e-$1.txt" "$dir/e-$1.err")" >&2
        exit 1
    fi
    c1=$(cpu_ticks $SRV_PID); hwm=$(vm $SRV_PID VmHWM)
    stop
    echo "$1 $2 $(kv "$dir/e-$1.txt" bytes) $(kv "$dir/e-$1.txt" seconds) $((c1 - c0)) $rss0 $hwm" >>"$dir/load.dat"
done
# Where the server's CPU goes: a separate 100-client run under `perf record`
# (when perf is there and may attach), top symbols by self time.
: >"$dir/perf.txt"
if command -v perf >/dev/null 2>&1; then
    start eperf "$dir/default.lumo" --max-clients 2000
    perf record -q -o "$dir/perf.data" -p "$SRV_PID" >/dev/null 2>&1 &
    PERF_PID=$!
    sleep 0.5
    if kill -0 $PERF_PID 2>/dev/null; then
        "$bench" load "127.0.0.1:$PORT" 100 5 >/dev/null 2>&1 || true
        kill -INT $PERF_PID 2>/dev/null || true
        wait $PERF_PID 2>/dev/null || true
        timeout 30 perf report -i "$dir/perf.data" --no-children --sort symbol --stdio 2>/dev/null |
            sed -n 's/^ *\([0-9.]*%\) *\[\(.\)\] \([^ ]*\).*/\1 \2 \3/p' | head -5 >"$dir/perf.txt" || true
    fi
    stop
fi

# ---- plots ------------------------------------------------------------------------
raw_b=$(awk -v b="$geo_bytes" -v r=$RATE_B -v l=$LAT_B 'BEGIN { printf "%.6f", b * 8 / (r * 1000) + 2 * l / 1000 }')
raw_bs=$(awk -v b="$geo_bytes" -v r=$RATE_A -v l=$LAT_A 'BEGIN { printf "%.6f", b * 8 / (r * 1000) + 2 * l / 1000 }')
qb=$(awk 'NR == 1 { print $6 }' "$dir/fig6.dat"); fb=$(awk 'NR == 1 { print $11 }' "$dir/fig6.dat")
raw_q=$(awk -v b="$qb" -v r=$RATE_B -v l=$LAT_B 'BEGIN { printf "%.6f", b * 8 / (r * 1000) + 2 * l / 1000 }')
raw_f=$(awk -v b="$fb" -v r=$RATE_B -v l=$LAT_B 'BEGIN { printf "%.6f", b * 8 / (r * 1000) + 2 * l / 1000 }')
gnuplot <<EOF
set terminal pngcairo size 1100,440 font "sans,10"
set output "docs/bench-stream-fig5.png"
set multiplot layout 1,2 title "Seed 000 Fig. 5 over lumo-server: dragon 203k geometry (${geo_bytes} record bytes), download time against request size"
set logscale x; set grid; set key top right; set xlabel "request size (vertices; batches hold 250)"; set ylabel "seconds"
set xrange [200:150000]
set yrange [0:*]
set title "20 Mbit/s, 1 ms each way"
plot "$dir/fig5.dat" u 1:(\$2/1e6) w lp pt 7 lw 2 t "stop-and-wait (--pipeline 1)", \
     "$dir/fig5.dat" u 1:(\$3/1e6) w lp pt 5 lw 2 t "default pipeline", \
     "$dir/fig5.dat" u 1:(\$4/1e6) w lp pt 4 dt 2 t "client CPU time (default pipeline)", \
     $raw_b w l lw 2 lc rgb "cyan" t "no streaming: one transfer of the same bytes"
set title "1 Mbit/s, 50 ms each way"
plot "$dir/fig5s.dat" u 1:(\$2/1e6) w lp pt 5 lw 2 lc 2 t "default pipeline", \
     "$dir/fig5s.dat" u 1:(\$3/1e6) w lp pt 4 dt 2 lc 3 t "client CPU time", \
     $raw_bs w l lw 2 lc rgb "cyan" t "no streaming"
unset multiplot
set output "docs/bench-stream-fig6.png"
set terminal pngcairo size 800,480 font "sans,10"
set title "Seed 000 Fig. 6 over lumo-server: 32^3 IVG at 20 Mbit/s, 1 ms each way"
set xlabel "rounds per request (= samples per slice, 32 slices)"; set ylabel "seconds"; set key at graph 0.98, 0.85
set xrange [3:1500]
plot "$dir/fig6.dat" u 1:(\$7/1e6) w lp pt 7 lw 2 lc 1 t "binary32 (${fb} bytes): download", \
     "$dir/fig6.dat" u 1:(\$8/1e6) w lp pt 6 dt 2 lc 1 t "binary32: client CPU (records + push-pull)", \
     $raw_f w l lc 1 dt 3 lw 2 t "binary32: one transfer", \
     "$dir/fig6.dat" u 1:(\$2/1e6) w lp pt 5 lw 2 lc 2 t "quantized (${qb} bytes): download", \
     "$dir/fig6.dat" u 1:(\$3/1e6) w lp pt 4 dt 2 lc 2 t "quantized: client CPU", \
     $raw_q w l lc 2 dt 3 lw 2 t "quantized: one transfer"
set output "docs/bench-stream-fig7.png"
set title "Seed 000 Fig. 7 over lumo-server: quantized 32^3 IVG, push-pull with and without smoothing"
plot "$dir/fig6.dat" u 1:(\$2/1e6) w lp pt 7 lw 2 lc 1 t "download, smoothing", \
     "$dir/fig6.dat" u 1:(\$12/1e6) w lp pt 5 lw 2 lc 2 t "download, no smoothing", \
     "$dir/fig6.dat" u 1:(\$4/1e6) w lp pt 6 dt 2 lc 1 t "push-pull CPU time, smoothing", \
     "$dir/fig6.dat" u 1:(\$14/1e6) w lp pt 4 dt 2 lc 2 t "push-pull CPU time, no smoothing", \
     $raw_q w l lc rgb "cyan" lw 2 t "one transfer of the same bytes"
EOF

# ---- the section ------------------------------------------------------------------
elapsed=$(( $(date +%s) - started ))
{
    echo "## Streaming over the emulated link (seed 000 §5.2, Figs. 5-7) and the server's costs"
    echo
    echo "Command: \`make bench-stream\` (runs \`bench/stream.sh\`; ${elapsed} s on this machine, load average"
    echo "$load0 at the start). Servers: \`lumo-server PKG --rate KBIT --latency MS\` on loopback (the link"
    echo "emulation of docs/server.md: token bucket, one-way latency on requests and answers). Clients:"
    echo "\`lumo-client\` and \`build/bin/lumo-bench-stream run\` (bench/stream_client.c: the same protocol driver"
    echo "and session as lumo-client, no renderer, microsecond times from just before connect(), push-pull"
    echo "timed inside the driver through \`-Wl,--wrap=lumo_session_update\`). Packages: \`lumo-bake --default\`"
    echo "(Cornell box + dragon 48k, 16^3 grid), the same scene with \`--dragon dragon_203k.ply --spp 16\`, and"
    echo "with \`--grid 32 --spp 16\`. Raw files and per-run outputs: \`$dir/\`."
    echo
    echo "### a. First picture and full scene at 1 Mbit/s, 50 ms (the issue's goals)"
    echo
    echo "\`lumo-server default.lumo --rate 1000 --latency 50\`; \`lumo-bench-stream run --order O\` and"
    echo "\`lumo-client --order O\` (adaptive request sizes, default pipeline) one after the other. First"
    echo "picture = every base mesh and the grid's corners applied (lumo-client's frame-first.png), from"
    echo "connect(). Full = everything applied (lumo-bench-stream); lumo-client's total also includes"
    echo "drawing and writing its last frame. Goals: first picture ≤ 0.5 s; full scene ≤ 1.1 × streamed"
    echo "bytes (all bytes received, framing and WELCOME included) / link rate. Floor = bytes/rate + 1 round"
    echo "trip (HELLO, answered by WELCOME and the first picture: HELLO flag bit 1 of docs/protocol.md §2):"
    echo "no client can do better on this link."
    echo
    echo "lumo-bench-stream ran each order 3 times (adaptive sizes follow the measured link, so runs differ):"
    echo "the row is the run of median full-scene time, with the range of the 3."
    echo
    echo "| order | first picture ms | ≤ 0.5 s | lumo-client first ms | full scene s | range of 3 | lumo-client total s | bytes | requests | bytes/rate s | floor s | goal s | over bytes/rate | within goal |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    cat "$dir/a-rows.md"
    echo
    awk -v b="$(kv "$dir/a-interleaved.txt" bytes_in)" -v r=$RATE_A -v l=$LAT_A 'BEGIN { ideal = b * 8 / (r * 1000)
        printf "The floor alone is %.1f %% over bytes/rate here (one round trip of %d ms on %.2f s of bytes), so the\n", 200 * l / 1000 / ideal, 2 * l, ideal
        printf "10 %% goal leaves %.1f %% for everything else. What remains above the floor: the requests after the\n", 10 - 200 * l / 1000 / ideal
        printf "first picture are sized from its answers (a second round trip before the bulk flows), and adaptive\n"
        printf "requests that are small against the link'"'"'s bytes per round trip. lumo-client'"'"'s total adds drawing and\n"
        printf "writing frame-first.png (during the stream) and its last frame.\n" }'
    echo
    awk -v t="$a0_full" -v b="$(kv "$dir/a0-fixed.txt" bytes_in)" -v r=$RATE_A 'BEGIN {
        printf "Without latency (`--rate 1000` alone, `--vertices 100000 --rounds 1000`): full scene %.3f s for %d bytes (bytes/rate %.3f s).\n", t / 1e6, b, b * 8 / (r * 1000) }'
    echo
    echo "### b. Geometry download time against request size (Fig. 5)"
    echo
    echo "Default scene with the 203k dragon, \`lumo-bench-stream run --no-ivg --order geometry --vertices N\`"
    echo "(HELLO asks for no lighting): time from WELCOME to the last batch applied, median of 3 runs;"
    echo "client work = CPU time applying batches (Draco decode, vertex splits, normals) inside that time"
    echo "(this thread's CPU time: other jobs share the 2 cores)."
    echo "No streaming = one request and one transfer of the same ${geo_bytes} record bytes at the link rate"
    echo "(plus its round trip). Plot: [docs/bench-stream-fig5.png](bench-stream-fig5.png)."
    echo
    echo "20 Mbit/s, 1 ms each way:"
    echo
    echo "| vertices per request | requests | stop-and-wait s | over no streaming | default pipeline s | over no streaming | client CPU s |"
    echo "|---|---|---|---|---|---|---|"
    awk -v raw="$raw_b" '{ printf "| %d | %d | %.3f | %+.0f %% | %.3f | %+.0f %% | %.3f |\n", $1, $5, $2 / 1e6,
        100 * ($2 / 1e6 / raw - 1), $3 / 1e6, 100 * ($3 / 1e6 / raw - 1), $4 / 1e6 }' "$dir/fig5.dat"
    echo "| no streaming | 1 | $raw_b | | | | |"
    echo
    echo "1 Mbit/s, 50 ms each way, default pipeline (one run each):"
    echo
    echo "| vertices per request | requests | download s | over no streaming | client CPU s |"
    echo "|---|---|---|---|---|"
    awk -v raw="$raw_bs" '{ printf "| %d | %d | %.3f | %+.1f %% | %.3f |\n", $1, $4, $2 / 1e6, 100 * ($2 / 1e6 / raw - 1), $3 / 1e6 }' "$dir/fig5s.dat"
    echo "| no streaming | 1 | $raw_bs | | |"
    echo
    echo "### c. The 32^3 IVG, binary32 against quantized, against request size (Fig. 6)"
    echo
    echo "\`lumo-bench-stream run --order lighting --vertices 100000000 --rounds K [--float]\` at 20 Mbit/s,"
    echo "1 ms: time from WELCOME to the last of the $rounds_c rounds applied. A round is one record per slice"
    echo "(32 slices), so K is the paper's samples per slice. Client work = CPU time feeding records to the session"
    echo "(dequantized, or copied) + push-pull after each answer. Plot: [docs/bench-stream-fig6.png](bench-stream-fig6.png)."
    echo
    echo "| K | push-pulls (answers) | quantized s | client CPU s | of which push-pull | binary32 s | client CPU s | of which push-pull | binary32 / quantized |"
    echo "|---|---|---|---|---|---|---|---|---|"
    awk '{ printf "| %d | %d | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.2f |\n", $1, $5, $2 / 1e6, $3 / 1e6, $4 / 1e6,
        $7 / 1e6, $8 / 1e6, $9 / 1e6, $7 / $2 }' "$dir/fig6.dat"
    echo "| one transfer | 1 | $raw_q | | | $raw_f | | | |"
    echo
    awk -v rq="$raw_q" -v rf="$raw_f" -v qb="$qb" -v fb="$fb" '
        function cross(k0, w0, k1, w1, raw) {   # log-linear in K where work meets the transfer time
            return exp(log(k0) + (log(k1) - log(k0)) * (w0 - raw) / (w0 - w1)) }
        { k[NR] = $1; wq[NR] = $3 / 1e6; wf[NR] = $8 / 1e6; tq[NR] = $2 / 1e6; tf[NR] = $7 / 1e6
          rec_q[NR] = ($3 - $4) / 1e6; rec_f[NR] = ($8 - $9) / 1e6; n = NR }
        END {
            cq = "none in 4..1024"; cf = cq
            for (i = 1; i < n; i++) {
                if (wq[i] > rq && wq[i + 1] <= rq && cq ~ /none/) cq = sprintf("K ≈ %.0f", cross(k[i], wq[i], k[i + 1], wq[i + 1], rq))
                if (wf[i] > rf && wf[i + 1] <= rf && cf ~ /none/) cf = sprintf("K ≈ %.0f", cross(k[i], wf[i], k[i + 1], wf[i + 1], rf))
            }
            if (wq[1] <= rq) cq = "below K = 4 (work under the transfer time at every K measured)"
            if (wf[1] <= rf) cf = "below K = 4 (work under the transfer time at every K measured)"
            fq = 0; for (i = 1; i <= n; i++) if (tf[i] < tq[i]) fq++
            printf "Sizes: binary32 %d bytes, quantized %d bytes (%.2f x smaller; the paper: 3 MB and 1.3 MB, 2.3 x).\n", fb, qb, fb / qb
            printf "Crossing (the paper reads the right request size where the client-work curve meets the transfer-time\n"
            printf "line, ~100 samples per slice on its client): quantized %s; binary32 %s.\n", cq, cf
            printf "Binary32 faster than quantized at %d of %d request sizes (the download curves %s).\n", fq, n, fq ? "cross" : "do not cross"
            printf "Records fed to the session (client work minus push-pull; dequantized, or copied as binary32): quantized\n"
            printf "%.3f s (%.1f %% of its client work) at K = %d and %.3f s (%.1f %%) at K = %d; binary32 %.3f s and %.3f s\n",
                rec_q[1], 100 * rec_q[1] / wq[1], k[1], rec_q[n], 100 * rec_q[n] / wq[n], k[n], rec_f[1], rec_f[n]
            printf "(the paper: dequantization ~4 %% of the processing).\n"
        }' "$dir/fig6.dat"
    echo
    echo "### d. Push-pull with and without smoothing over the protocol (Fig. 7)"
    echo
    echo "Quantized 32^3 grid as in c, \`--no-smoothing\` against the default (smoothing); push-pull time ="
    echo "this thread's CPU time in the driver's \`lumo_session_update\` calls (one per lighting answer), summed"
    echo "(other jobs share the 2 cores: wall times move with them, CPU time much less). Smoothing share ="
    echo "(smooth − plain) / smooth of the median call, shown where the runs made 30 calls or more; the paper"
    echo "reports 80 % (bench-ivg above: 13-22 % at 32^3)."
    echo "Plot: [docs/bench-stream-fig7.png](bench-stream-fig7.png)."
    echo
    echo "| K | push-pulls | download s, smoothing | download s, none | push-pull CPU s, smoothing | push-pull CPU s, none | median ms per push-pull, smoothing | median ms, none | smoothing share |"
    echo "|---|---|---|---|---|---|---|---|---|"
    awk '{ printf "| %d | %d | %.3f | %.3f | %.3f | %.3f | %.2f | %.2f | %s |\n", $1, $5, $2 / 1e6, $12 / 1e6, $4 / 1e6,
        $14 / 1e6, $17 / 1e3, $19 / 1e3, $5 < 30 ? "-" : sprintf("%.0f %%", 100 * ($17 - $19) / $17) }' "$dir/fig6.dat"
    echo
    awk '{ s += $4; p += $14; n += $5; m += $15 } END {
        printf "Over all K, CPU time in push-pull: %.3f s with smoothing (%d calls), %.3f s without (%d calls): smoothing\n", s / 1e6, n, p / 1e6, m
        printf "is %.0f %% of the push-pull time. Only where the client is the bottleneck (small K) does it show in the\n", 100 * (s - p) / s
        printf "download time.\n" }' "$dir/fig6.dat"
    echo
    echo "### e. Server throughput, CPU per MB and memory per client (loopback, no link emulation)"
    echo
    echo "\`lumo-server default.lumo --max-clients 2000\`, a fresh one per row; \`lumo-bench-stream load PORT N R\`:"
    echo "N clients at once, each fetching the whole default scene R times (one request per mesh and one for"
    echo "the lighting, two fetches in flight, 64 KiB frames), payloads skipped unchecked. Client and server"
    echo "share the 2 cores. Server CPU = utime + stime of /proc/PID/stat ($tck ticks/s); memory = VmHWM after"
    echo "the run − VmRSS before the clients, per client (the 256 KiB kernel send buffer per client is not"
    echo "in RSS)."
    echo
    echo "| clients | fetches each | MB sent | wall s | MB/s | server CPU s | server CPU ms per MB | server CPU busy | RSS idle KiB | peak KiB | bytes per client |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|"
    awk -v tck="$tck" '{ mb = $3 / 1e6; cpu = $5 / tck
        printf "| %d | %d | %.1f | %.3f | %.0f | %.2f | %.2f | %.0f %% | %d | %d | %.0f |\n", $1, $2, mb, $4, mb / $4, cpu,
            1000 * cpu / mb, 100 * cpu / $4, $6, $7, ($7 - $6) * 1024 / $1 }' "$dir/load.dat"
    echo
    awk -v tck="$tck" '{ c += $5 / tck; m += $3 / 1e6; b = ($7 - $6) * 1024 / $1; if (b > mx) mx = b } END {
        printf "Over all rows: %.2f ms of server CPU per MB, one core of this machine for ~%.0f MB/s; memory at most\n", 1000 * c / m, m / c
        printf "%.0f bytes per client beside the fixed kernel buffers.\n", mx }' "$dir/load.dat"
    if [ -s "$dir/perf.txt" ]; then
        echo
        echo "Server CPU by symbol (self time; \`perf record -p PID\` over a separate 100-client run; [k] kernel, [.] lumo-server):"
        echo
        echo "| share | where | symbol |"
        echo "|---|---|---|"
        awk '{ printf "| %s | %s | `%s` |\n", $1, $2 == "k" ? "kernel" : "user", $3 }' "$dir/perf.txt"
        if grep -q lumo_wire_crc32 "$dir/perf.txt"; then
            echo
            echo "\`lumo_wire_crc32\` is the CRC-32 trailer of each DATA frame, computed over the package bytes as"
            echo "the frame is made (conn.c push_data; the SDK's half-byte table, chosen for client memory)."
        fi
    fi
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "bench-stream: wrote $out and docs/bench-stream-fig5.png, fig6.png, fig7.png ($elapsed s)" >&2
