#!/bin/sh
# tests/render/truth.sh BUILD — the client against the server's path-traced
# reference on the default scene (docs/rasterizer.md, "Error against truth").
# The reference is a low-noise one: 1024 paths per pixel at 320x240
# (its own noise, from two independent 512-spp halves: about 0.8 mean
# Delta E), rendered by this test once and kept in BUILD/render/truth/
# with the command that made it (a different command renders it again;
# delete the file to force it). The package is baked at 2048 spp (16^3:
# 256 spp leaves blotches of bake noise on the walls). The soft client with
# shadowed direct (1024^2 shadow maps) + IVG indirect light must reach
# issue 21's goal per pixel, mean CIE Lab Delta E <= 2.0 and p99 <= 15;
# the shadows must cut the p99 of the unshadowed client by a quarter, and
# the client must be at least twice as close as direct light alone: the
# IVG has to earn its bytes.
set -u
build=$1
bin=$build/bin
out=$build/render/truth
mkdir -p "$out"
pass=0; fail=0
MAX_DE=2.0
MAX_P99=15
SHADOWS=1024
BAKE_SPP=2048
REF_SPP=1024

"$bin/lumo-bake" --default -o "$out/default.lumo" --spp $BAKE_SPP --no-progress >/dev/null || exit 1
ref=$out/reference-$REF_SPP.png
refcmd="lumo-bake --default --reference 320x240 --spp $REF_SPP --seed 1"
if [ ! -s "$ref" ] || [ "$(cat "$ref.cmd" 2>/dev/null)" != "$refcmd" ]; then
    echo "truth: rendering the $REF_SPP-spp reference once ($refcmd)"
    nice "$bin/lumo-bake" --default --reference 320x240 --spp $REF_SPP --seed 1 -o "$ref.tmp.png" --no-progress \
        >/dev/null || exit 1
    mv "$ref.tmp.png" "$ref" && echo "$refcmd" >"$ref.cmd"
fi
cp "$ref" "$out/reference.png"
for mode in per-pixel per-vertex; do
    "$bin/lumo-render" "$out/default.lumo" --$mode --shadows $SHADOWS -o "$out/client-$mode.png" >/dev/null || exit 1
    "$bin/lumo-render" "$out/default.lumo" --$mode -o "$out/unshadowed-$mode.png" >/dev/null || exit 1
    "$bin/lumo-render" "$out/default.lumo" --$mode --shadows $SHADOWS --no-indirect -o "$out/direct-$mode.png" \
        >/dev/null || exit 1
    "$bin/lumo-compare" "$out/client-$mode.png" "$out/unshadowed-$mode.png" "$out/direct-$mode.png" \
        "$out/reference.png" --labels "client $mode,no shadows,direct only,reference" -o "$out/side-$mode.png" \
        | tee "$out/$mode.txt"
done
de() {  # de FILE PAIR -> mean dE of that line
    sed -n "s/^$2: mean dE76 \([0-9.]*\),.*/\1/p" "$1"
}
p99() {  # p99 FILE PAIR -> p99 dE of that line
    sed -n "s/^$2: mean dE76 [0-9.]*, p99 dE \([0-9.]*\),.*/\1/p" "$1"
}
c=$(de "$out/per-pixel.txt" "client per-pixel vs reference")
d=$(de "$out/per-pixel.txt" "direct only vs reference")
cp=$(p99 "$out/per-pixel.txt" "client per-pixel vs reference")
up=$(p99 "$out/per-pixel.txt" "no shadows vs reference")
if awk -v c="$c" -v m=$MAX_DE 'BEGIN { exit !(c <= m) }'; then pass=$((pass + 1))
else echo "FAIL per-pixel client vs reference: mean dE $c > $MAX_DE"; fail=$((fail + 1)); fi
if awk -v c="$cp" -v m=$MAX_P99 'BEGIN { exit !(c <= m) }'; then pass=$((pass + 1))
else echo "FAIL per-pixel client vs reference: p99 dE $cp > $MAX_P99"; fail=$((fail + 1)); fi
if awk -v c="$cp" -v u="$up" 'BEGIN { exit !(4 * c <= 3 * u) }'; then pass=$((pass + 1))
else echo "FAIL shadows do not cut the p99 by a quarter: $cp vs $up without"; fail=$((fail + 1)); fi
if awk -v c="$c" -v d="$d" 'BEGIN { exit !(2 * c <= d) }'; then pass=$((pass + 1))
else echo "FAIL IVG does not halve the error: client $c vs direct only $d"; fail=$((fail + 1)); fi
cv=$(de "$out/per-vertex.txt" "client per-vertex vs reference")
dv=$(de "$out/per-vertex.txt" "direct only vs reference")
if awk -v c="$cv" -v d="$dv" 'BEGIN { exit !(c < d) }'; then pass=$((pass + 1))
else echo "FAIL per-vertex: IVG does not reduce the error ($cv vs $dv)"; fail=$((fail + 1)); fi
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
