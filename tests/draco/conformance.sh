#!/bin/sh
# tests/draco/conformance.sh BUILD quick|full — lumo's Draco decoder against
# libdraco 1.5.5, byte for byte on the portable integers and connectivity.
#
# Every case encodes a mesh with draco_encoder, decodes it with the libdraco
# oracle (tests/draco/draco_oracle.cc) and with lumo (lumo-draco-decode
# --dump, sanitizer build, in the default and the --lean mode), and
# compares the dumps. Cases named
# "unsupported:..." must instead make lumo fail cleanly with "unsupported".
# Prints one line per failing case and "RESULT: N passed, M failed".
build=${1:-build}; mode=${2:-quick}
bin="$build/bin"
work="$build/draco-conformance-$mode"
models="$build/data/models"
lumo="$bin/lumo-draco-decode-san"
[ -x "$lumo" ] || lumo="$bin/lumo-draco-decode"
lumo_lean="$bin/lumo-draco-decode-lean-san"
rm -rf "$work"; mkdir -p "$work/gen" "$work/cases"
"$bin/gen-meshes" "$work/gen" || { echo "RESULT: 0 passed, 1 failed"; exit 1; }
# the attribute set of issue 25 (tests/draco/gen_attr_meshes.cc)
mkdir -p "$work/attr"
"$bin/gen-attr-meshes" "$work/attr" "$models/bunny.obj" || { echo "RESULT: 0 passed, 1 failed"; exit 1; }
attr_meshes="scan_20k scan_82k terrain cad holed parts bunny"

gen="sphere_uv.obj small.obj cube_seams.obj torus_color.ply cornell.obj nonmanifold.ply"
cases="$work/cases.txt"; : > "$cases"
add() { echo "$1|$2|$3" >> "$cases"; }   # kind|model|encoder options

if [ "$mode" = full ]; then
    levels="0 1 2 3 4 5 6 7 8 9 10"
    quants="default 8 9 10 11 12 13 14 15 16"
    for m in $gen; do for cl in $levels; do for q in $quants; do
        if [ "$q" = default ]; then add mesh "$work/gen/$m" "-cl $cl"
        else add mesh "$work/gen/$m" "-cl $cl -qp $q -qt $q -qn $((q > 12 ? 12 : q)) -qg $q"; fi
    done; done; done
    for m in bunny.obj dragon_11k.ply dragon_48k.ply; do for cl in $levels; do for q in default 8 12 16; do
        if [ "$q" = default ]; then add mesh "$models/$m" "-cl $cl"
        else add mesh "$models/$m" "-cl $cl -qp $q"; fi
    done; done; done
else
    for m in $gen bunny.obj; do
        case $m in bunny.obj) p="$models/$m" ;; *) p="$work/gen/$m" ;; esac
        for cl in 0 1 2 3 4 5 6 7 8 9 10; do
            add mesh "$p" "-cl $cl"
            case $cl in
                0|3|6|9) add mesh "$p" "-cl $cl -qp 8 -qt 8 -qn 6 -qg 8" ;;
                1|4|7|10) add mesh "$p" "-cl $cl -qp 16 -qt 14 -qn 12 -qg 16" ;;
                *) add mesh "$p" "-cl $cl -qp 13 -qt 11 -qn 9 -qg 12" ;;
            esac
        done
    done
    for cl in 0 1 2 3 4 5 6 7 8 9 10; do add mesh "$models/dragon_11k.ply" "-cl $cl"; done
    for cl in 0 7 10; do add mesh "$models/dragon_11k.ply" "-cl $cl -qp 14"; done
    for cl in 0 5 7 10; do add mesh "$models/dragon_48k.ply" "-cl $cl"; done
fi
# positions + normals, + texture coordinates, + colours, at the levels and
# the two quantizations of the benchmark (bench/draco_attrs.sh): every
# case in the full grid, one level per mesh and kind in the quick one
i=0
for m in $attr_meshes; do for k in n nt c; do
    case $k in c) f="$work/attr/${m}_c.ply" ;; *) f="$work/attr/${m}_$k.obj" ;; esac
    i=$((i + 1))
    for cl in 4 7 10; do
        [ "$mode" = full ] || [ $(((i + cl) % 3)) -eq 0 ] || continue
        add mesh "$f" "-cl $cl"
        add mesh "$f" "-cl $cl -qp 14 -qt 12 -qn 10"
    done
done; done
# more than 2^16 points: sequential connectivity with varint indices, and
# the exact rANS table of long streams (draco_rans.c LD_LUT_EXACT_BITS)
add mesh "$models/dragon_203k.ply" "-cl 0"
add mesh "$models/dragon_203k.ply" "-cl 7"
# point clouds: sequential (cl 0) and KD-tree (cl 1-10)
for cl in 0 1 2 3 4 5 6 7 8 9 10; do
    add cloud "$work/gen/cloud.ply" "-point_cloud -cl $cl"
    add cloud "$work/gen/torus_color.ply" "-point_cloud -cl $cl -qp 14 -qn 9"
done
for cl in 0 2 4 6 10; do add cloud "$models/dragon_11k.ply" "-point_cloud -cl $cl -qp 12"; done
# degenerate sizes: one triangle, one point
for cl in 0 1 7 10; do
    add mesh "$work/gen/triangle.obj" "-cl $cl"
    add cloud "$work/gen/single.ply" "-point_cloud -cl $cl"
done
# metadata (skipped) and a material attribute
for cl in 0 1 5 7 10; do add mesh "$work/gen/materials.obj" "-cl $cl -metadata"; done
add cloud "$work/gen/materials.obj" "-point_cloud -cl 7 -metadata"
# dequantized PLY output of lumo-draco-decode against draco_decoder's
add ply "$work/gen/sphere_uv.obj" "-cl 7"
add ply "$work/gen/torus_color.ply" "-cl 10 -qp 16 -qn 12"
add ply "$work/gen/cube_seams.obj" "-cl 5 -qp 8"
add ply "$models/bunny.obj" "-cl 0"
add ply "$models/dragon_11k.ply" "-cl 9 -qp 14"
add ply "$work/gen/cloud.ply" "-point_cloud -cl 6"
# not decoded, must be refused cleanly: unquantized floats (generic coding)
add unsupported "$work/gen/small.obj" "-cl 7 -qp 0 -qt 0 -qn 0"
add unsupported "$work/gen/torus_color.ply" "-cl 0 -qp 0 -qn 0"

run_case() {  # run_case N LINE
    n=$1; kind=${2%%|*}; rest=${2#*|}; model=${rest%%|*}; opts=${rest#*|}
    name="$(basename "$model") $opts"
    d="$work/cases/$n"; mkdir -p "$d"
    if ! draco_encoder -i "$model" -o "$d/in.drc" $opts > "$d/enc.log" 2>&1; then
        echo "FAIL encode: $name"; return
    fi
    if [ "$kind" = unsupported ]; then
        if "$lumo" --dump "$d/in.drc" "$d/lumo.txt" 2> "$d/lumo.err"; then
            echo "FAIL expected unsupported: $name"
        elif grep -q "unsupported" "$d/lumo.err"; then echo "PASS $name"
        else echo "FAIL wrong error ($(cat "$d/lumo.err")): $name"; fi
        return
    fi
    if [ "$kind" = ply ]; then
        if ! draco_decoder -i "$d/in.drc" -o "$d/ref.ply" > "$d/dec.log" 2>&1; then
            echo "FAIL draco_decoder: $name"; return
        fi
        if ! "$bin/lumo-draco-decode" "$d/in.drc" "$d/lumo.ply" 2> "$d/lumo.err"; then
            echo "FAIL lumo ply ($(head -c 200 "$d/lumo.err")): $name"; return
        fi
        if "$bin/ply-compare" "$d/ref.ply" "$d/lumo.ply" > "$d/cmp.txt" 2>&1; then
            echo "PASS ply $name"; rm -rf "$d"
        else echo "FAIL ply differs (see $d/cmp.txt): $name"; fi
        return
    fi
    if ! "$bin/draco-oracle" "$d/in.drc" "$d/oracle.txt" 2> "$d/oracle.err"; then
        echo "FAIL oracle: $name"; return
    fi
    # both decoding modes (LUMO_DRACO_LEAN: a 24-bit corner table, read as
    # decoded or packed), and the build with the lean mode only
    # (LUMO_DRACO_MODES, the ARMv7-M boards' choice) without the flag: the
    # same integers and faces, each in exactly its own arena need
    for m in "" --lean --lean-only; do
        dec="$lumo"; flag=$m
        if [ "$m" = --lean-only ]; then
            [ -x "$lumo_lean" ] || continue
            dec="$lumo_lean"; flag=
        fi
        if ! "$dec" $flag --dump "$d/in.drc" "$d/lumo$m.txt" 2> "$d/lumo$m.err"; then
            echo "FAIL lumo $m($(head -c 200 "$d/lumo$m.err")): $name"; return
        fi
        if ! cmp -s "$d/oracle.txt" "$d/lumo$m.txt"; then
            echo "FAIL differs $m(see $d): $name"; return
        fi
    done
    echo "PASS $name"; rm -rf "$d"
}

jobs=${DRACO_JOBS:-2}
i=0
while IFS= read -r line; do
    i=$((i + 1))
    run_case "$i" "$line" > "$work/cases/r$i.txt" &
    if [ $((i % jobs)) -eq 0 ]; then wait; fi
done < "$cases"
wait
cat "$work"/cases/r*.txt > "$work/results.txt"
grep '^FAIL' "$work/results.txt"
pass=$(grep -c '^PASS' "$work/results.txt")
fail=$(grep -c '^FAIL' "$work/results.txt")
echo "conformance ($mode): $(wc -l < "$cases") cases"
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
