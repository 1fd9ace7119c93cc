#!/bin/sh
# boards/client/client-bench.sh DIR SCENE SERVER HOST_CLIENT CLIENT_ELF "QEMU_CMD" OUT.md
#
# The board client's costs on the Cortex-M3 (docs/porting.md §7): SCENE is
# streamed once by the host build through lumo-server's serial listener and
# recorded; QEMU (mps2-an385, -icount shift=0: board ticks count
# instructions) replays the recording, so nothing waits for bytes; its
# COST, MEM and stack lines become the section OUT.md of docs/benchmarks.md,
# with the session's time on a 100 MHz Cortex-M3 at 115200 baud and
# 1 Mbit/s. The server is killed on exit (trap); runs are bounded by timeout.
dir=$1; scene=$2; server=$3; host=$4; elf=$5; qemu=$6; out=$7
mkdir -p "$dir"
pid=""
trap '[ -n "$pid" ] && kill -9 $pid 2>/dev/null' EXIT
trap 'exit 1' INT TERM

rm -f "$dir/bench.port"
"$server" "$scene" --listen 127.0.0.1:0 --serial-listen 127.0.0.1:0 --port-file "$dir/bench.port" \
    2>"$dir/bench.server.log" &
pid=$!
i=0
while [ ! -s "$dir/bench.port" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
serial=$(cut -d' ' -f2 "$dir/bench.port" 2>/dev/null)
rec="$dir/bench.rec"; log="$dir/bench-replay.log"
LUMO_LINK=127.0.0.1:$serial timeout 60 "$host" --record "$rec" </dev/null >"$dir/bench-host.log" 2>&1 ||
    { echo "client-bench: the host run failed"; cat "$dir/bench-host.log"; exit 1; }
timeout 60 $qemu -kernel "$elf" -append "--replay $rec" </dev/null >"$log" 2>&1 ||
    { echo "client-bench: the board replay failed"; cat "$log"; exit 1; }
kill -TERM $pid; wait $pid; pid=""   # its line for the client is complete now
sent=$(sed -n 's/.*HELLO.*, \([0-9]*\) requests,.*/\1/p' "$dir/bench.server.log")

{
echo "## The thin client on the Cortex-M3 (QEMU mps2-an385, instruction counts)"
echo
echo "Command: \`make bench-client\` (boards/client/client-bench.sh) — lumo-bake's default scene"
echo "(\`lumo-bake --default\`: the Cornell box with the 48k dragon, a 16³ grid) streamed by the host"
echo "build of the board client (boards/client/client.c) through lumo-server's serial listener and"
echo "recorded, then the recording replayed by the same program under"
echo "\`$qemu\`, so no instruction waits for a byte. Requests of 250 vertices and 4 lighting"
echo "rounds, 4 in flight, quantized IVG, push-pull with smoothing after every lighting DATA; each"
echo "picture per pixel, RGB565 in 16-row bands with 32-bit depth, the first picture and 10, 25, 50"
echo "and 100 % of the scene at 320×240 and 160×128. Guest instructions (the 25 MHz board timer"
echo "ticks every 40), not cycles; arm-none-eabi-gcc -Os, Thumb-2, soft float."
echo
awk '
/^client: done:/ { done = $0; sub(/^client: done: /, "", done) }
{ gsub(/[(),]/, "") }
/^COST frame-/ { pics = pics sprintf("| %s | %.1f M |\n", $2, $3 / 1e6) }
/^COST geometry.batch/ { g = $3; gn = $5; gt = $7 }
/^COST lighting.data/ { l = $3; ln = $5; lt = $10 }
/^COST lighting.pushpull/ { p = $3; pn = $5; pt = $7 }
/^COST frame.decode/ { d = $3; dn = $5; dt = $10 }
/^COST picture/ { pc = $3; pcn = $5; pct = $7 }
/^COST session.total/ { total = $3 }
/^MEM/ { scene = $5; pic = $12 }
/^stack peak/ { stack = $3 }
END {
    printf "Session: %s.\n\n", done
    print "| work | count | instructions each | in all |"
    print "|---|---:|---:|---:|"
    printf "| geometry batch (Draco decode, progressive mesh applied) | %d | %.2f M | %.0f M |\n", gn, g / 1e6, gt / 1e6
    printf "| lighting DATA (IVG records applied + push-pull) | %d | %.2f M | %.0f M |\n", ln, l / 1e6, lt / 1e6
    printf "| — of which push-pull (16³, smoothing) | %d | %.2f M | %.0f M |\n", pn, p / 1e6, pt / 1e6
    printf "| frame received (CRC, header and payload checks) | %d | %.1f k | %.1f M |\n", dn, d / 1e3, dt / 1e6
    printf "| picture | %d | %.0f M | %.0f M |\n", pcn, pc / 1e6, pct / 1e6
    printf "| **the whole session** | | | **%.0f M** |\n\n", total / 1e6
    print "| picture | instructions |"
    print "|---|---:|"
    printf "%s\n", pics
    printf "Memory: scene arena peak %d bytes (the session: meshes, decoders, IVG), picture arena peak %d bytes\n", scene, pic
    printf "(vertex caches of 64 bytes per vertex, one band, no frame buffer), stack peak %d bytes.\n\n", stack
}' "$log"
bytes=$(wc -c <"$rec")
total=$(sed -n 's/^COST session.total \([0-9]*\).*/\1/p' "$log")
pictures=$(sed -n 's/^COST picture .*, \([0-9]*\) in all.*/\1/p' "$log")
awk -v b="$bytes" -v t="$total" -v p="$pictures" -v r="$sent" 'BEGIN {
    up = 40 + 28 * r + 12
    printf "The session'\''s time on a 100 MHz Cortex-M3 at one instruction per cycle (a lower bound:\n"
    printf "flash wait states and 64-bit multiplies cost more) with the line at 10 bits per byte (8N1):\n"
    printf "the transfer is the %d bytes received (frames with their headers); the %d sent (HELLO, %d\n", b, up, r
    printf "requests, BYE) travel the other way at the same time. \"One after the other\" is this\n"
    printf "client (polled UART, one byte of buffer: the line waits while it\n"
    printf "computes, as QEMU'\''s UART does); \"overlapped\" is a client receiving into a buffer under\n"
    printf "an interrupt while it computes (the longer of the two). Streaming alone leaves out the\n"
    printf "10 pictures (%.2f s of them).\n\n", p / 1e8
    print "| link | transfer | compute (streaming alone) | one after the other | overlapped |"
    print "|---|---:|---:|---:|---:|"
    n = split("115200 1000000", rate, " ")
    for (i = 1; i <= n; i++) {
        x = b * 10 / rate[i]; c = t / 1e8; s = (t - p) / 1e8
        name = rate[i] == 115200 ? "115 200 baud" : "1 Mbit/s"; over = x > c ? x : c
        printf "| %s | %.2f s | %.2f s (%.2f s) | %.2f s | %.2f s |\n", name, x, c, s, x + c, over
    }
}'
} >"$out"
cat "$out"
