#!/bin/sh
# tests/pm/pm_tools.sh BIN MODEL TMPDIR — the progressive-mesh tools end to
# end: lumo-pm build (package with a PMSH chunk), lumo-inspect --stream and
# --lod N --ply at the base, a middle and the full level, bad arguments.
bin=$1; model=$2; tmp=$3
pass=0; fail=0
ok() { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
mkdir -p "$tmp"
if [ ! -f "$model" ]; then echo "RESULT: 0 passed, 1 failed ($model missing)"; exit 1; fi
if "$bin/lumo-pm" build "$model" -o "$tmp/m.lumo" --batch 100 >"$tmp/build.txt"; then ok "lumo-pm build"; else bad "lumo-pm build"; fi
if "$bin/lumo-inspect" --stream "$tmp/m.lumo" >"$tmp/stream.txt"; then ok "lumo-inspect --stream"; else bad "lumo-inspect --stream"; fi
# lumo-pm apply takes the package lumo-pm build wrote (it took bare streams only)
if "$bin/lumo-pm" apply "$tmp/m.lumo" 3 | grep -q "^3 records, .*: ok$"; then ok "lumo-pm apply PACKAGE 3"
else bad "lumo-pm apply PACKAGE 3: $("$bin/lumo-pm" apply "$tmp/m.lumo" 3 2>&1)"; fi
n=$(sed -n 's/^progressive mesh: \([0-9]*\) vertices, \([0-9]*\) faces; base \([0-9]*\) vertices.*/\1 \2 \3/p' "$tmp/stream.txt")
set -- $n; nv=$1; nf=$2; base=$3
rows=$(awk 'NR > 2' "$tmp/stream.txt" | wc -l)
want=$(( 1 + (nv - base + 99) / 100 ))
[ "$rows" -eq "$want" ] && ok "--stream lists $rows batches" || bad "--stream lists $rows batches, want $want"
# how the positions travel: the build's choice, named as lumo-pm build named it
lat=no; grep -q "(lattice copies)" "$tmp/build.txt" && lat=yes
if { [ $lat = no ] && grep -q "positions [0-9]* bits (coded)" "$tmp/stream.txt"; } ||
   { [ $lat = yes ] && grep -q "positions [0-9]* bits (coded, lattice copies)" "$tmp/stream.txt"; }; then
    ok "--stream names the position coding"
else bad "--stream position coding: $(head -1 "$tmp/stream.txt")"; fi
# Every column of the listing against the header and itself: indices 0, 1,
# ...; each batch starts where the last ended and the vertices add up to the
# mesh; record = head + side + Draco bytes; records tile the stream from the
# header (its length in the summary line) to its end; the last level has
# every face.
bytes=$(sed -n 's/.*; stream \([0-9]*\) bytes.*/\1/p' "$tmp/stream.txt")
hbytes=$(sed -n 's/.*bits\/triangle; header \([0-9]*\)).*/\1/p' "$tmp/stream.txt")
why=$(awk -v nv="$nv" -v nf="$nf" -v bytes="$bytes" -v off="${hbytes:-0}" '
    NR <= 2 { next }
    { if ($1 != NR - 3) { print "batch index " $1 " in row " NR - 2; exit }
      if ($2 != v) { print "batch " $1 " starts at " $2 ", not " v; exit }
      if ($8 != $5 + $6 + $7) { print "batch " $1 ": record " $8 " != head+side+draco"; exit }
      if ($9 != off) { print "batch " $1 " at offset " $9 ", not " off; exit }
      if ($5 < 5 || $5 > 14) { print "batch " $1 ": head of " $5 " bytes"; exit }
      v += $3; off += $8; f = $4 }
    BEGIN { v = 0; if (off < 38 || off > 70) { print "header of " off " bytes"; exit } }
    END { if (v != nv || off != bytes || f != nf) print "sums: " v " vertices, " off " bytes, " f " faces" }' "$tmp/stream.txt")
[ -z "$why" ] && [ -n "$bytes" ] && ok "--stream columns agree with the header and the stream" \
    || bad "--stream columns: ${why:-no stream size}"
for lod in "$base" $(( (base + nv) / 2 )) all; do
    if "$bin/lumo-inspect" --lod "$lod" --ply "$tmp/l.ply" "$tmp/m.lumo" >/dev/null; then
        v=$(sed -n 's/^element vertex //p' "$tmp/l.ply"); f=$(sed -n 's/^element face //p' "$tmp/l.ply")
        body=$(awk '/^end_header/ {h = 1; next} h' "$tmp/l.ply" | wc -l)
        expect=$lod; [ "$lod" = all ] && expect=$nv
        if [ "$v" -eq "$expect" ] && [ "$body" -eq $((v + f)) ] && { [ "$lod" != all ] || [ "$f" -eq "$nf" ]; }; then
            ok "--lod $lod: $v vertices, $f faces"
        else bad "--lod $lod: $v vertices, $f faces, $body lines"; fi
    else bad "--lod $lod"; fi
done
for args in "--lod $((base - 1)) --ply $tmp/x.ply" "--lod $((nv + 1)) --ply $tmp/x.ply" "--lod 12x --ply $tmp/x.ply"; do
    if "$bin/lumo-inspect" $args "$tmp/m.lumo" 2>"$tmp/err.txt" >/dev/null; then bad "lumo-inspect $args accepted"
    elif grep -q "lumo-inspect: error:" "$tmp/err.txt"; then ok "lumo-inspect $args: one-line error"
    else bad "lumo-inspect $args: no error line"; fi
done
# lumo-bake --mesh pm: one PMSH stream per scene mesh, each decodable.
if [ -x "$bin/lumo-bake" ] && "$bin/lumo-bake" --default --grid 4 --spp 2 --mesh pm -o "$tmp/scene.lumo" >/dev/null 2>&1; then
    i=0; while "$bin/lumo-inspect" --stream --mesh $i "$tmp/scene.lumo" >/dev/null 2>&1; do i=$((i + 1)); done
    if [ "$i" -ge 1 ] && "$bin/lumo-inspect" --lod all --ply "$tmp/s.ply" --mesh $((i - 1)) "$tmp/scene.lumo" >/dev/null; then
        ok "lumo-bake --mesh pm: $i streams decode, --mesh $i is refused"
    else bad "lumo-bake --mesh pm package: $i streams"; fi
    # a baked mesh carries its albedo, coded with its positions (stream version 7)
    "$bin/lumo-inspect" --stream --mesh $((i - 1)) "$tmp/scene.lumo" >"$tmp/scene-stream.txt" 2>&1
    if grep -q "^progressive mesh: .*positions [0-9]* bits (coded[^)]*); albedo;" "$tmp/scene-stream.txt" \
        && awk 'NR > 2 && $7 != 0 { exit 1 }' "$tmp/scene-stream.txt"; then
        ok "--stream: the baked mesh's positions and albedo coded, no Draco payload"
    else bad "--stream: baked mesh listing $(head -1 "$tmp/scene-stream.txt")"; fi
else bad "lumo-bake --default --mesh pm"; fi
head -c 1000 "$tmp/m.lumo" >"$tmp/cut.lumo"
if "$bin/lumo-inspect" --stream "$tmp/cut.lumo" >/dev/null 2>&1; then bad "truncated package accepted"; else ok "truncated package rejected"; fi
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
