#!/bin/sh
# tools/demo.sh BUILD — the main job on the built-in default scene:
#   1. bake the Cornell box (+ dragon) lighting into a .lumo package,
#   2. render the server's path-traced reference,
#   3. render the client's picture from the package (fixed-point soft
#      rasterizer: direct light + IVG indirect) and without indirect light,
#   4. an orbit of client frames,
#   5. one side-by-side picture with the error against the reference.
# Output in BUILD/demo/. Settings can be overridden from the environment.
set -eu
build=${1:-build}
bin="$build/bin"
out="$build/demo"
GRID=${GRID:-16}
SPP=${SPP:-256}
REF_SPP=${REF_SPP:-256}
SIZE=${SIZE:-320x240}
FRAMES=${FRAMES:-12}
mkdir -p "$out/orbit"

step() { printf '\n== %s\n' "$*"; }

step "1/5 bake the default scene (grid $GRID, $SPP paths per vertex)"
"$bin/lumo-bake" --default --grid "$GRID" --spp "$SPP" -o "$out/scene.lumo"
"$bin/lumo-inspect" "$out/scene.lumo"

step "2/5 path-traced reference ($SIZE, $REF_SPP spp)"
"$bin/lumo-bake" --default --reference "$SIZE" --spp "$REF_SPP" -o "$out/reference.png"

step "3/5 client pictures (soft rasterizer, fixed point)"
"$bin/lumo-render" "$out/scene.lumo" --size "$SIZE" --per-pixel -o "$out/client.png"
"$bin/lumo-render" "$out/scene.lumo" --size "$SIZE" --per-pixel --no-indirect -o "$out/client-direct.png"

step "4/5 orbit: $FRAMES frames"
"$bin/lumo-render" "$out/scene.lumo" --size "$SIZE" --per-pixel --frames "$FRAMES" --orbit -o "$out/orbit/frame.png"

step "5/5 side by side: client (direct + IVG) | client (direct only) | reference"
"$bin/lumo-compare" "$out/client.png" "$out/client-direct.png" "$out/reference.png" \
    --labels "client: direct + IVG,client: direct only,server: path traced" -o "$out/side-by-side.png"

printf '\ndemo: pictures in %s/ (side-by-side.png first)\n' "$out"
