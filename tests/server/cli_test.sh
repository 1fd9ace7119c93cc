#!/bin/sh
# tests/server/cli_test.sh BIN WORKDIR — lumo-bake / lumo-inspect from the
# outside: --help, bad input gives exactly one error line and exit 1, the
# same seed gives a byte-identical package for 1 and 2 threads, a damaged
# or version-1 package is refused, the summary lists the IVG streaming order
# (IVGS) and the interleaving (ORDR) and --order every round, consistent
# with the chunk table. Prints "RESULT: N passed, M failed".
bin=$1; dir=$2
mkdir -p "$dir"
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }

# expect_error NAME CMD...: exit status 1 and exactly one stderr line with "error:"
expect_error() {
    name=$1; shift
    "$@" >"$dir/out" 2>"$dir/err"; st=$?
    lines=$(wc -l <"$dir/err")
    if [ $st -eq 1 ] && [ "$lines" -eq 1 ] && grep -q "error:" "$dir/err"; then
        ok "$name: $(cat "$dir/err")"
    else
        bad "$name (status $st, $lines stderr lines)"; sed 's/^/    /' "$dir/err"
    fi
}

bake=$bin/lumo-bake; inspect=$bin/lumo-inspect
light="--light point:0,1,0:10,10,10"

"$bake" --help | grep -q "usage: lumo-bake" && ok "lumo-bake --help" || bad "lumo-bake --help"
"$inspect" --help | grep -q -- "--ivg" && ok "lumo-inspect --help lists --ivg" || bad "lumo-inspect --help"

# Scene files with one defect each.
printf 'v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n' >"$dir/good.obj"
printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n' >"$dir/flat.obj"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\nnan 0 0\n0 0 1\n3 0 1 2\n' >"$dir/nan.ply"
printf 'this is not a mesh \001\002\003\n' >"$dir/broken.ply"
printf 'mesh good.obj\n' >"$dir/nolight.txt"
printf 'light point:0,1,0:1,1,1\n' >"$dir/empty.txt"
printf 'mesh good.obj\nteapot 1\n' >"$dir/unknown.txt"
printf 'mesh missing.obj\n' >"$dir/missing.txt"

expect_error "missing scene file"   "$bake" "$dir/none.txt" -o "$dir/x.lumo"
expect_error "missing mesh file"    "$bake" "$dir/missing.txt" -o "$dir/x.lumo" $light
expect_error "broken mesh"          "$bake" "$dir/broken.ply" -o "$dir/x.lumo" $light
expect_error "NaN vertex"           "$bake" "$dir/nan.ply" -o "$dir/x.lumo" $light
expect_error "zero-area face"       "$bake" "$dir/flat.obj" -o "$dir/x.lumo" $light
expect_error "empty scene"          "$bake" "$dir/empty.txt" -o "$dir/x.lumo"
expect_error "no light"             "$bake" "$dir/nolight.txt" -o "$dir/x.lumo"
expect_error "unknown statement"    "$bake" "$dir/unknown.txt" -o "$dir/x.lumo"
awk 'BEGIN { printf "quad"; for (i = 0; i < 600; i++) printf " 0,0,0"; print "" }' >"$dir/long.txt"
expect_error "overlong line"        "$bake" "$dir/long.txt" -o "$dir/x.lumo"
expect_error "unknown option"       "$bake" --default --frobnicate -o "$dir/x.lumo"
expect_error "position needs 3 numbers, got 2" "$bake" --default --light point:1,2 -o "$dir/x.lumo"
expect_error "bad grid"             "$bake" --default --grid 1 -o "$dir/x.lumo"
expect_error "bad camera"           "$bake" --default --reference 8x8 --camera 0,0,0:0,0,0:0,1,0:40 -o "$dir/x.png"
expect_error "no output"            "$bake" --default
expect_error "scene and --default"  "$bake" --default "$dir/good.obj" -o "$dir/x.lumo"
expect_error "unwritable output"    "$bake" --default --grid 2 --spp 1 -o /nonexistent/dir/x.lumo
expect_error "inspect missing file" "$inspect" "$dir/none.lumo"
expect_error "inspect unknown opt"  "$inspect" --frobnicate "$dir/none.lumo"

# A single mesh file is a scene too (with lights from the command line).
if "$bake" "$dir/good.obj" $light --grid 3 --spp 4 -o "$dir/tri.lumo" 2>/dev/null &&
   "$inspect" --ivg "$dir/tri.lumo" >/dev/null; then ok "bake a flat mesh file, read its IVG"; else bad "bake a mesh file"; fi

# Same seed -> identical bytes, whatever the thread count; another seed differs.
common="--default --grid 6 --spp 16 --no-progress"
"$bake" $common --seed 7 --threads 1 -o "$dir/a.lumo" 2>/dev/null
"$bake" $common --seed 7 --threads 2 -o "$dir/b.lumo" 2>/dev/null
"$bake" $common --seed 8 --threads 2 -o "$dir/c.lumo" 2>/dev/null
cmp -s "$dir/a.lumo" "$dir/b.lumo" && ok "same seed, 1 vs 2 threads: identical package" || bad "same seed differs"
cmp -s "$dir/a.lumo" "$dir/c.lumo" && bad "another seed gives the same package" || ok "another seed differs"

# --cell: spacing 0.5 m over the 2 m box -> 5 vertices per axis.
"$bake" --default --cell 0.5 --spp 2 -o "$dir/cell.lumo" 2>/dev/null && "$inspect" "$dir/cell.lumo" | grep -q "ivg       5x5x5" \
    && ok "--cell 0.5 gives a 5x5x5 grid" || bad "--cell"

# --mesh: progressive PMSH streams (the default), raw MESH chunks, or both.
"$bake" --default --grid 3 --spp 2 --mesh pm -o "$dir/pm.lumo" 2>/dev/null && "$inspect" "$dir/pm.lumo" >"$dir/pm.txt" \
    && grep -q PMSH "$dir/pm.txt" && ! grep -q "MESH  offset" "$dir/pm.txt" && ok "--mesh pm: PMSH chunks only" || bad "--mesh pm"
"$bake" --default --grid 3 --spp 2 -o "$dir/dflt.lumo" 2>/dev/null && cmp -s "$dir/pm.lumo" "$dir/dflt.lumo" \
    && ok "no --mesh: the same bytes as --mesh pm" || bad "default --mesh is not pm"
"$bake" --default --grid 3 --spp 2 --mesh raw -o "$dir/raw.lumo" 2>/dev/null && "$inspect" "$dir/raw.lumo" >"$dir/raw.txt" \
    && grep -q "MESH  offset" "$dir/raw.txt" && ! grep -q PMSH "$dir/raw.txt" && ok "--mesh raw: MESH chunks only" || bad "--mesh raw"
"$bake" --default --grid 3 --spp 2 --mesh both -o "$dir/both.lumo" 2>/dev/null && "$inspect" "$dir/both.lumo" >"$dir/both.txt" \
    && grep -q PMSH "$dir/both.txt" && grep -q "MESH  offset" "$dir/both.txt" && ok "--mesh both" || bad "--mesh both"
expect_error "bad --mesh"           "$bake" --default --mesh draco -o "$dir/x.lumo"

# The summary and the per-vertex dump.
"$inspect" "$dir/a.lumo" >"$dir/sum.txt" 2>&1 && grep -q "ivg       6x6x6" "$dir/sum.txt" \
    && ok "inspect summary" || bad "inspect summary"
n=$("$inspect" --ivg "$dir/a.lumo" | awk 'NF == 11' | wc -l)
[ "$n" -eq $((6 * 6 * 6 * 6)) ] && ok "inspect --ivg: $n lines of 11 fields" || bad "inspect --ivg: $n lines"

# Damaged packages: one flipped byte in the IVG, and a truncated file.
size=$(wc -c <"$dir/a.lumo")
cp "$dir/a.lumo" "$dir/flip.lumo"
printf '\377' | dd of="$dir/flip.lumo" bs=1 seek=$((size - 100)) conv=notrunc 2>/dev/null
expect_error "inspect flipped byte" "$inspect" "$dir/flip.lumo"
head -c $((size - 1)) "$dir/a.lumo" >"$dir/trunc.lumo"
expect_error "inspect truncated"    "$inspect" "$dir/trunc.lumo"

# A version-1 package (IVG in index order, no IVGS): one line that says to re-bake.
expect_error "inspect version-1 package" "$inspect" tests/server/data/v1_tiny.lumo
grep -q "package version 1: re-bake it with this lumo-bake" "$dir/err" && ok "version 1: says to re-bake" \
    || bad "version 1 message: $(cat "$dir/err")"
expect_error "inspect --stream version-1" "$inspect" --stream tests/server/data/v1_tiny.lumo
grep -q "package version 1: re-bake" "$dir/err" && ok "--stream version 1: says to re-bake" || bad "--stream version 1"

# The IVG streaming order and the interleaving in the summary (a.lumo: 6x6x6,
# 6 slices along x of 36 vertices: round 0 the 8 corners, rounds 1..32 one
# vertex per slice, 33..36 the 4 interior slices).
grep -q "^package   version 2.0, " "$dir/sum.txt" && ok "summary: version 2.0" || bad "summary version"
grep -q "^ivg order 37 rounds over 6 slices along x, 216 records, seed 7$" "$dir/sum.txt" \
    && ok "summary: IVGS line" || bad "summary: IVGS line"
awk '/^  rounds /{ sub(/\.\./, " "); n += ($3 - $2 + 1) * $4 } END { exit n != 216 }' "$dir/sum.txt" \
    && ok "summary: the rounds' records add up to the grid" || bad "summary: rounds do not add up"
grep -q "^  rounds     1\.\.32 *6 records each" "$dir/sum.txt" && grep -q "^  rounds    33\.\.36 *4 records each" "$dir/sum.txt" \
    && ok "summary: 6 records per round, then 4" || bad "summary: round runs"
grep -q "^order     7 prefix steps, then a cycle of " "$dir/sum.txt" && grep -q "^  prefix  lighting, 1 round$" "$dir/sum.txt" \
    && grep -q "^  cycle   lighting, " "$dir/sum.txt" && ok "summary: ORDR prefix and cycle" || bad "summary: ORDR"
# --order: one line per round; records and both byte ranges contiguous from
# 16 to the end of IVGQ / IVGF (their lengths from the chunk table).
"$inspect" --order "$dir/a.lumo" >"$dir/order.txt" 2>&1
qlen=$(awk '$3 == "IVGQ" { print $7 }' "$dir/sum.txt"); flen=$(awk '$3 == "IVGF" { print $7 }' "$dir/sum.txt")
awk -v q="$qlen" -v f="$flen" '!/^#/ { if ($1 != r || $2 != rec || $4 != qo || $6 != fo) bad = 1
        r++; rec += $3; qo = $4 + $5; fo = $6 + $7 }
    BEGIN { qo = 16; fo = 16 } END { exit bad || r != 37 || rec != 216 || qo != q || fo != f }' "$dir/order.txt" \
    && ok "--order: 37 contiguous rounds ending at the bundles' ends" || bad "--order"
"$inspect" --help | grep -q -- "--order" && ok "lumo-inspect --help lists --order" || bad "--help --order"
# Each light listed with what its kind has (lights.lumo: area, spot, directional)
"$inspect" tests/fuzz/seeds/fuzz_package/lights.lumo >"$dir/lights.txt" 2>&1 &&
    grep -q "^light 0   area at (-0.200, 1.990, -0.200) dir (0.000, -1.000, 0.000) power (10.000" "$dir/lights.txt" &&
    grep -q "^light 1   spot at (0.500, 1.500, 0.000) dir (0.000, -1.000, 0.000) power .* half-angle 45.00 deg" \
        "$dir/lights.txt" &&
    grep -q "^light 2   directional dir (0.000, -0.981, 0.196) irradiance (0.500" "$dir/lights.txt" &&
    "$bake" tests/fuzz/package_seeds/tiny.txt --mesh raw --grid 2 --spp 1 --light point:0,2,0:5,5,5 \
        -o "$dir/point.lumo" >/dev/null 2>&1 &&
    "$inspect" "$dir/point.lumo" | grep "^light" | grep -v "dir (" | grep -q "point at (0.000, 2.000, 0.000) power" \
    && ok "lumo-inspect lists each light by what its kind has (a point light without a direction)" \
    || bad "lumo-inspect light lines: $(cat "$dir/lights.txt")"

# Reference images: full and indirect-only, PNG signature.
"$bake" --default --reference 32x24 --spp 4 -o "$dir/ref.png" 2>/dev/null && \
    head -c 8 "$dir/ref.png" | od -An -c | grep -q "P   N   G" && ok "reference PNG" || bad "reference PNG"
"$bake" --default --reference 32x24 --spp 4 --indirect-only -o "$dir/ind.png" 2>/dev/null && \
    ok "indirect-only PNG" || bad "indirect-only PNG"
"$bake" --default --reference 32x24 --spp 4 --threads 1 -o "$dir/ref1.png" 2>/dev/null
cmp -s "$dir/ref.png" "$dir/ref1.png" && ok "reference: same seed, 1 vs 2 threads: identical PNG" \
    || bad "reference differs between thread counts"
cmp -s "$dir/ref.png" "$dir/ind.png" && bad "indirect-only equals full" || ok "indirect-only differs from full"

echo "RESULT: $pass passed, $fail failed"
[ $fail -eq 0 ]
