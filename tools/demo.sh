#!/bin/sh
# tools/demo.sh BUILD — the main job on the built-in default scene:
#   1. bake the Cornell box (+ dragon): progressive meshes and the IVG into a
#      .lumo package (format 2: the streaming order fixed at write time),
#   2. render the server's path-traced reference,
#   3. serve the package with lumo-server on loopback behind an emulated
#      slow link (RATE kbit/s, LATENCY ms),
#   4. stream it to lumo-client three times — interleaved, geometry first,
#      lighting first (seed 000 §5.1) — writing a frame at growing shares
#      of the scene (with shadow maps of SHADOWS^2 texels per face),
#   5. progress.png: what the client shows after growing amounts of bytes
#      (seed 000 Fig. 1), each picture labelled with bytes, triangles, IVG %,
#   6. error-vs-bytes.png: the client's image error against the path-traced
#      reference as bytes arrive, for the three orders (gnuplot),
# and a summary (time to the first picture, to the full scene).
# Output in BUILD/demo/. Settings can be overridden from the environment.
set -eu
build=${1:-build}
bin="$build/bin"
out="$build/demo"
GRID=${GRID:-16}
# 2048 paths per grid vertex: at 256 the IVG's noise shows as blotches on the
# walls (docs/rasterizer.md "Error against truth"); 1024-spp reference
SPP=${SPP:-2048}
REF_SPP=${REF_SPP:-1024}
SIZE=${SIZE:-320x240}
RATE=${RATE:-1000}
LATENCY=${LATENCY:-50}
FRAMES_AT=${FRAMES_AT:-1,2,3,5,7,10,15,20,30,40,50,60,70,80,90,100}
# the client's shadow maps, texels per side (0: none; docs/rasterizer.md "Shadows")
SHADOWS=${SHADOWS:-1024}
rm -rf "$out"
mkdir -p "$out"

step() { printf '\n== %s\n' "$*"; }
server_pid=""
cleanup() { [ -z "$server_pid" ] || kill "$server_pid" 2>/dev/null || true; }
trap cleanup EXIT INT TERM

step "1/6 bake the default scene (grid $GRID, $SPP paths per vertex)"
"$bin/lumo-bake" --default --grid "$GRID" --spp "$SPP" -o "$out/scene.lumo"
"$bin/lumo-inspect" "$out/scene.lumo" | head -n 12

step "2/6 path-traced reference ($SIZE, $REF_SPP spp)"
"$bin/lumo-bake" --default --reference "$SIZE" --spp "$REF_SPP" -o "$out/reference.png"

step "3/6 lumo-server on loopback, link $RATE kbit/s, $LATENCY ms"
"$bin/lumo-server" "$out/scene.lumo" --listen 127.0.0.1:0 --port-file "$out/port" \
    --rate "$RATE" --latency "$LATENCY" >"$out/server.log" 2>&1 &
server_pid=$!
i=0
while [ ! -s "$out/port" ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
[ -s "$out/port" ] || { cat "$out/server.log"; echo "demo: lumo-server did not start" >&2; exit 1; }
port=$(cut -d' ' -f1 "$out/port")
head -n 3 "$out/server.log"

step "4/6 lumo-client: stream the scene three ways, frames at $FRAMES_AT % of it"
for order in interleaved geometry lighting; do
    "$bin/lumo-client" --connect "127.0.0.1:$port" --order "$order" --size "$SIZE" \
        --frames-at "$FRAMES_AT" --shadows "$SHADOWS" --out "$out/$order" --quiet | tee "$out/$order.log"
done
kill "$server_pid" 2>/dev/null || true
wait "$server_pid" 2>/dev/null || true
server_pid=""

# One row of a progress.csv by frame path: bytes, triangles, IVG %.
label_of() {
    awk -F, -v f="$1" '$10 == f { printf "%.0f KB %s TRIS IVG %.0f%%", $2 / 1024, $6, $8 ? 100 * $7 / $8 : 0 }' \
        "$(dirname "$1")/progress.csv"
}

step "5/6 progress.png: the interleaved stream after growing amounts of bytes"
set --; labels=""; last=""
for f in first 002.00 005.00 010.00 020.00 030.00 050.00 070.00 100.00; do
    p="$out/interleaved/frame-$f.png"
    [ -f "$p" ] || continue
    l=$(label_of "$p")
    # one picture per state: a large answer can cross several shares at once
    [ "$l" != "$last" ] && [ $# -lt 7 ] || continue
    set -- "$@" "$p"; labels="$labels$l,"; last=$l
done
"$bin/lumo-compare" "$@" "$out/reference.png" --labels "${labels}PATH TRACED" -o "$out/progress.png" \
    >"$out/progress.txt"

step "6/6 error-vs-bytes.png: mean Delta E against the reference as bytes arrive"
for order in interleaved geometry lighting; do
    tail -n +2 "$out/$order/progress.csv" | while IFS=, read -r pct bytes _ _ _ _ _ _ _ frame; do
        de=$("$bin/lumo-compare" "$frame" "$out/reference.png" | sed -n 's/.*mean dE76 \([0-9.]*\),.*/\1/p')
        echo "$bytes $de $pct"
    done | sort -n >"$out/error-$order.dat"
done
gnuplot <<EOF
set terminal png size 800,480
set output "$out/error-vs-bytes.png"
set title "lumo-client vs the path-traced reference, streamed at $RATE kbit/s, $LATENCY ms"
set xlabel "bytes received (KB)"
set ylabel "mean Delta E (CIE76)"
set key top right
set grid
plot "$out/error-interleaved.dat" using (\$1/1024):2 with linespoints title "interleaved", \
     "$out/error-geometry.dat" using (\$1/1024):2 with linespoints title "geometry first", \
     "$out/error-lighting.dat" using (\$1/1024):2 with linespoints title "lighting first"
EOF

"$bin/lumo-compare" "$out/interleaved/frame-100.00.png" "$out/reference.png" \
    --labels "CLIENT: STREAMED,SERVER: PATH TRACED" -o "$out/side-by-side.png" >"$out/side-by-side.txt"

step "summary"
pkg=$(wc -c <"$out/scene.lumo")
for order in interleaved geometry lighting; do
    sed -n "s/^lumo-client: [^:]*:[0-9]*: \(.*\)/$order: \1/p" "$out/$order.log"
done
echo "package: $pkg bytes on disk (both IVG forms); a client streams only the form it asked for"
cat "$out/side-by-side.txt"
printf '\ndemo: pictures in %s/ (progress.png, error-vs-bytes.png, side-by-side.png; frames per order in interleaved/, geometry/, lighting/)\n' "$out"
