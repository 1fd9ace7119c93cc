#!/bin/sh
# tools/demo.sh BUILD — the main job on the built-in default scene:
#   1. bake the Cornell box (+ dragon) lighting into a .lumo package (meshes
#      as progressive streams),
#   2. render the server's path-traced reference,
#   3. render the client's picture from the package (fixed-point soft
#      rasterizer: direct light + IVG indirect) and without indirect light,
#   4. levels of detail of the progressive meshes side by side (lod.png,
#      as the paper's Figure 3),
#   5. an orbit of client frames,
#   6. one side-by-side picture with the error against the reference.
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

step "1/6 bake the default scene (grid $GRID, $SPP paths per vertex)"
"$bin/lumo-bake" --default --grid "$GRID" --spp "$SPP" -o "$out/scene.lumo"
"$bin/lumo-inspect" "$out/scene.lumo"

step "2/6 path-traced reference ($SIZE, $REF_SPP spp)"
"$bin/lumo-bake" --default --reference "$SIZE" --spp "$REF_SPP" -o "$out/reference.png"

step "3/6 client pictures (soft rasterizer, fixed point)"
"$bin/lumo-render" "$out/scene.lumo" --size "$SIZE" --per-pixel -o "$out/client.png"
"$bin/lumo-render" "$out/scene.lumo" --size "$SIZE" --per-pixel --no-indirect -o "$out/client-direct.png"

step "4/6 levels of detail: ${LODS:=1% 10% 100%} of the vertices streamed after each base mesh"
set -- $LODS
[ $# -le 3 ] || { echo "demo: LODS holds at most 3 levels" >&2; exit 1; }
pics=""; labels=""
for lod in "$@"; do
    name="$out/lod-$(echo "$lod" | tr -d %).png"
    "$bin/lumo-render" "$out/scene.lumo" --size "$SIZE" --per-pixel --lod "$lod" -o "$name" | tee "$out/lod.log"
    tris=$(sed -n 's/.* vertices, \([0-9]*\) triangles$/\1/p' "$out/lod.log")
    pics="$pics $name"; labels="$labels${labels:+,}lod $lod: $tris triangles"
done
# shellcheck disable=SC2086 # pics is a list of paths without spaces
"$bin/lumo-compare" $pics --labels "$labels" -o "$out/lod.png"
rm -f "$out/lod.log"

step "5/6 orbit: $FRAMES frames"
"$bin/lumo-render" "$out/scene.lumo" --size "$SIZE" --per-pixel --frames "$FRAMES" --orbit -o "$out/orbit/frame.png"

step "6/6 side by side: client (direct + IVG) | client (direct only) | reference"
"$bin/lumo-compare" "$out/client.png" "$out/client-direct.png" "$out/reference.png" \
    --labels "client: direct + IVG,client: direct only,server: path traced" -o "$out/side-by-side.png"

printf '\ndemo: pictures in %s/ (side-by-side.png first, lod.png for the levels of detail)\n' "$out"
