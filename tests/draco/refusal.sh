#!/bin/sh
# tests/draco/refusal.sh BUILD — refusal conformance (issue 24): small
# streams of every kind (sequential, standard and valence EdgeBreaker with
# per-corner normals and texture coordinates, colours, KD-tree and
# sequential point clouds), each mutated byte by byte by draco-refusal
# (tests/draco/draco_refusal.cc): whatever libdraco refuses, lumo refuses.
build=${1:-build}
bin="$build/bin"
work="$build/draco-refusal"
rm -rf "$work"; mkdir -p "$work/gen"
"$bin/gen-meshes" "$work/gen" || { echo "RESULT: 0 passed, 1 failed"; exit 1; }
set --
enc() {  # enc NAME MODEL OPTIONS...
    name=$1; model=$2; shift 2
    draco_encoder -i "$work/gen/$model" -o "$work/$name.drc" "$@" > /dev/null || {
        echo "FAIL encode $name"; echo "RESULT: 0 passed, 1 failed"; exit 1; }
}
enc cube_cl0 cube_seams.obj -cl 0
enc cube_cl4 cube_seams.obj -cl 4
enc cube_cl10 cube_seams.obj -cl 10 -qn 12
enc small_cl7 small.obj -cl 7
enc torus_cl10 torus_color.ply -cl 10 -qp 8
enc cloud_cl6 single.ply -point_cloud -cl 6
"$bin/draco-refusal" "$work"/*.drc
