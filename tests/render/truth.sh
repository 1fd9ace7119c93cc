#!/bin/sh
# tests/render/truth.sh BUILD — the client against the server's path-traced
# reference on the default scene (docs/rasterizer.md, "Error against truth").
# The soft client with shadowed direct (512^2 shadow maps) + IVG indirect
# light must stay within mean CIE Lab Delta E <= 3.5 and p99 <= 20 of the
# reference (128 spp: the reference's own noise is about 2 of that mean,
# docs/rasterizer.md), the shadows must cut the p99 of the unshadowed
# client by a quarter, and the client must be at least twice as close as
# direct light alone: the IVG has to earn its bytes.
set -u
build=$1
bin=$build/bin
out=$build/render/truth
mkdir -p "$out"
pass=0; fail=0
MAX_DE=3.5
MAX_P99=20
SHADOWS=512

"$bin/lumo-bake" --default -o "$out/default.lumo" --spp 256 --no-progress >/dev/null || exit 1
"$bin/lumo-bake" --default --reference 320x240 --spp 128 -o "$out/reference.png" --no-progress \
    >/dev/null || exit 1
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
