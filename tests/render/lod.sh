#!/bin/sh
# tests/render/lod.sh BUILD — lumo-render on progressive meshes (issue 5):
# the default scene from a `--mesh pm` package (decoded through the SDK's
# lumo_pmesh) looks the same as from a `--mesh raw` package (mean Delta E
# <= 1, lumo-compare); --lod levels give the vertex counts they promise and
# fewer triangles the lower they go; a damaged stream is refused with one
# line naming the mesh and the batch, while a level below the damage still
# renders; bad --lod values are usage errors.
set -u
build=$1
bin=$build/bin
out=$build/render/lod
mkdir -p "$out"
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "ok   $*"; }
bad() { fail=$((fail + 1)); echo "FAIL $*"; }
render() { "$bin/lumo-render" "$@" --size 160x120 >"$out/log.txt" 2>&1; }
field() { sed -n "s/.* \([0-9]*\) $1.*/\1/p" "$out/log.txt" | head -1; }   # the number before WORD

bake="$bin/lumo-bake --default --grid 8 --spp 32 --no-progress"
$bake --mesh raw -o "$out/raw.lumo" 2>/dev/null || { echo "RESULT: 0 passed, 1 failed (bake raw)"; exit 1; }
$bake --mesh pm -o "$out/pm.lumo" 2>/dev/null || { echo "RESULT: 0 passed, 1 failed (bake pm)"; exit 1; }

# The full level against the raw mesh, both lighting modes.
for mode in per-vertex per-pixel; do
    if render "$out/raw.lumo" --$mode -o "$out/raw-$mode.png" && grep -q "raw meshes" "$out/log.txt" \
       && render "$out/pm.lumo" --$mode -o "$out/pm-$mode.png" && grep -q "progressive meshes" "$out/log.txt" \
       && "$bin/lumo-compare" "$out/raw-$mode.png" "$out/pm-$mode.png" --max-mean-de 1 >"$out/cmp.txt" 2>&1
    then ok "$mode: pm vs raw package, $(sed -n 's/.*\(mean dE76 [0-9.]*\).*/\1/p' "$out/cmp.txt")"
    else bad "$mode: pm vs raw package: $(cat "$out/cmp.txt" "$out/log.txt")"; fi
done

# Levels: all = every vertex; N caps each mesh (5 walls of 4 vertices keep
# theirs, the dragon has N); fewer triangles at lower levels.
render "$out/pm.lumo" -o "$out/all.png" --lod all
full=$(sed -n 's/.* \([0-9]*\) of \([0-9]*\) vertices.*/\1 \2/p' "$out/log.txt")
set -- $full
[ "$#" -eq 2 ] && [ "$1" -eq "$2" ] && ok "--lod all: $1 of $2 vertices" || bad "--lod all: '$full'"
render "$out/pm.lumo" -o "$out/n.png" --lod 1000
v=$(sed -n 's/.* \([0-9]*\) of [0-9]* vertices.*/\1/p' "$out/log.txt")
[ "$v" = 1020 ] && ok "--lod 1000: $v vertices (dragon 1000 + 5 walls x 4)" || bad "--lod 1000: $v vertices, want 1020"
prev=0
for lod in 0% 1% 10% 100%; do
    if render "$out/pm.lumo" -o "$out/lod-$lod.png" --lod "$lod"; then
        t=$(sed -n 's/.* vertices, \([0-9]*\) triangles$/\1/p' "$out/log.txt")
        [ -n "$t" ] && [ "$t" -gt "$prev" ] && ok "--lod $lod: $t triangles" || bad "--lod $lod: '$t' triangles after $prev"
        prev=${t:-0}
    else bad "--lod $lod: $(cat "$out/log.txt")"; fi
done
"$bin/lumo-compare" "$out/all.png" "$out/lod-100%.png" --max-mean-de 0 >/dev/null 2>&1 \
    && ok "--lod 100% is --lod all" || bad "--lod 100% differs from all"
"$bin/lumo-compare" "$out/all.png" "$out/lod-1%.png" --max-mean-de 0.5 >/dev/null 2>&1 \
    && bad "--lod 1% looks like the full mesh" || ok "--lod 1% differs from the full mesh"

# Usage errors (status 2) and a raw package with --lod (status 1).
for arg in abc 0 101% 5%x -3; do
    "$bin/lumo-render" "$out/pm.lumo" -o "$out/x.png" --lod "$arg" >/dev/null 2>&1
    [ $? -eq 2 ] && ok "--lod $arg refused" || bad "--lod $arg not a usage error"
done
"$bin/lumo-render" "$out/raw.lumo" -o "$out/x.png" --lod 10% >/dev/null 2>"$out/err.txt"
[ $? -eq 1 ] && [ "$(wc -l <"$out/err.txt")" -eq 1 ] && ok "raw package --lod 10%: one-line error" \
    || bad "raw package --lod 10%: $(cat "$out/err.txt")"

# A damaged last batch of the dragon's stream inside a package whose own
# CRCs are made valid again: the stream's batch check must catch it.
crc() { gzip -c | tail -c8 | head -c4; }    # CRC-32 (little-endian) of stdin
put() { dd of="$1" bs=1 seek="$2" conv=notrunc 2>/dev/null; }   # stdin at offset
cp "$out/pm.lumo" "$out/bad.lumo"
"$bin/lumo-inspect" "$out/bad.lumo" >"$out/chunks.txt"
set -- $(awk '/PMSH/ { k = $2; o = $5; l = $7 } END { print k, o, l }' "$out/chunks.txt")
k=$1; off=$2; len=$3
nchunks=$(sed -n 's/.* \([0-9]*\) chunks$/\1/p' "$out/chunks.txt")
printf '\125' | put "$out/bad.lumo" $((off + len - 8))
dd if="$out/bad.lumo" bs=1 skip="$off" count="$len" 2>/dev/null | crc | put "$out/bad.lumo" $((24 + 16 * k + 12))
dd if="$out/bad.lumo" bs=1 skip=24 count=$((16 * nchunks)) 2>/dev/null | crc | put "$out/bad.lumo" 16
head -c 20 "$out/bad.lumo" | crc | put "$out/bad.lumo" 20
"$bin/lumo-render" "$out/bad.lumo" -o "$out/x.png" >/dev/null 2>"$out/err.txt"
st=$?
if [ $st -eq 1 ] && [ "$(wc -l <"$out/err.txt")" -eq 1 ] && grep -q "progressive mesh $((k - 1)), batch [0-9]*: " "$out/err.txt"
then ok "damaged stream: $(cat "$out/err.txt")"
else bad "damaged stream: status $st, $(cat "$out/err.txt")"; fi
render "$out/bad.lumo" -o "$out/x.png" --lod 10% && ok "damaged stream: --lod 10% (before the damage) renders" \
    || bad "damaged stream --lod 10%: $(cat "$out/log.txt")"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
