#!/bin/sh
# tests/render/prt_gl.sh BUILD — PRT on the GL backends (issue 19, seed 003
# Ch. 4-5; docs/prt.md "GL multipass"): the thesis's multipass (one pass
# per super-cluster, additive blending, lumo/raster_gl_prt.h) on osmesa,
# egl (desktop GL 3.3) and egl forced to GLES 3.0 must match the soft
# backend's PRT frame (one cluster per vertex, no overdraw) within the
# cross-backend bounds (tests/render/cross_backend.sh: mean CIE Lab
# Delta E <= 2, PSNR >= 38 dB), frame by frame of a turning sky; and the
# triangles each GL draw makes must be Eq. 8's count, the overdraw
# lumo-bake predicted, with the GL's own primitive count agreeing.
set -u
build=$1
bin=$build/bin
out=$build/render/prt-gl
mkdir -p "$out"
pass=0; fail=0
MAX_DE=2
MIN_PSNR=38
ok()  { pass=$((pass + 1)); echo "ok   $*"; }
bad() { fail=$((fail + 1)); echo "FAIL $*"; }

"$bin/prt-demo" env "$out/sky.png" 128 64 || bad "prt-demo env"
bake() {  # bake NAME MODEL PRT-OPTIONS
    "$bin/lumo-bake" "$2" --light directional:0.3,-1,0.2:2,2,2 --grid 3 --spp 2 --threads 2 --no-progress \
        --prt "$3" --prt-env "$out/sky.png" -o "$out/$1.lumo" 2>"$out/$1.bake" || { bad "bake $1"; cat "$out/$1.bake"; }
}

# check NAME PACKAGE ARGS... : soft against the three GL contexts, 3 frames
# of a sky turned 40 degrees a frame; the measured overdraw against the bake's
lod=
check() {
    name=$1; pkg=$2; shift 2
    for b in soft osmesa egl egl-gles; do
        api=gl; be=$b
        [ "$b" = egl-gles ] && { api=gles; be=egl; }
        if ! LUMO_EGL_API=$api "$bin/lumo-render" "$pkg" --prt --frames 3 --rotate 40 "$@" --backend $be \
                -o "$out/$name-$b.png" >"$out/$name-$b.log" 2>&1; then
            bad "$name: $b did not render"; cat "$out/$name-$b.log"; return
        fi
    done
    for b in osmesa egl egl-gles; do
        for f in 000 001 002; do
            if "$bin/lumo-compare" "$out/$name-soft_$f.png" "$out/$name-${b}_$f.png" --labels "soft,$b" \
                   --max-mean-de $MAX_DE --min-psnr $MIN_PSNR >"$out/$name-$b-$f.cmp"; then
                ok "$name frame $f: $(cat "$out/$name-$b-$f.cmp")"
            else
                bad "$name frame $f: soft vs $b beyond mean dE $MAX_DE / PSNR $MIN_PSNR dB"; cat "$out/$name-$b-$f.cmp"
            fi
        done
        # lumo-bake: "overdraw A, B in N passes"; lumo-render: "N passes, D of T triangles drawn (overdraw B)"
        want=$(sed -n 's/.*overdraw [0-9.]*, \([0-9.]*\) in \([0-9]*\) passes.*/\2 passes, overdraw \1/p' "${pkg%.lumo}.bake")
        got=$(sed -n 's/.*multipass: \([0-9]*\) passes, [0-9]* of [0-9]* triangles drawn (overdraw \([0-9.]*\)).*/\1 passes, overdraw \2/p' \
              "$out/$name-$b.log")
        if [ -n "$lod" ]; then
            # a coarser mesh's triangles straddle more passes than the bake's full mesh
            [ -n "$got" ] && ok "$name $b at --lod $lod: $got (full mesh: $want)" || bad "$name $b: no multipass line"
        elif [ -n "$want" ] && [ "$want" = "$got" ]; then ok "$name $b: $got as lumo-bake predicted (Eq. 8)"
        else bad "$name $b: measured '$got', predicted '$want'"; fi
        drawn=$(sed -n 's/.*passes, \([0-9]*\) of.*/\1/p' "$out/$name-$b.log")
        gen=$(sed -n 's/.*GL primitives generated \([0-9]*\).*/\1/p' "$out/$name-$b.log")
        if [ "$b" = egl-gles ]; then
            [ "$gen" = 0 ] && ok "$name $b: no primitive query in GLES 3.0" || bad "$name $b: query '$gen'"
        elif [ -n "$drawn" ] && [ "$gen" = "$drawn" ]; then ok "$name $b: the GL generated $gen primitives"
        else bad "$name $b: the GL generated '$gen', drawn '$drawn'"; fi
    done
}

bake bunny build/data/models/bunny.obj 6,clusters=64,components=8,strata=16
check bunny "$out/bunny.lumo" --size 320x240 --cull
# one pass per cluster (registers=0): every cluster its own pass
bake bunny-k build/data/models/bunny.obj 4,clusters=32,components=4,strata=8,registers=0
check bunny-k "$out/bunny-k.lumo" --size 160x120
# geometry coherence and super-clusters on the dragon, seen from its back too (no culling)
bake dragon build/data/models/dragon_11k.ply 6,clusters=128,components=8,strata=8,alpha=2
check dragon "$out/dragon.lumo" --size 320x240

# the level of detail: a prefix of the vertices relit, as the soft backend
lod=40%
check bunny-lod "$out/bunny.lumo" --size 160x120 --lod $lod
lod=
# the false-colour views stay the soft backend's
if "$bin/lumo-render" "$out/bunny.lumo" --prt --prt-view passes --backend osmesa -o "$out/x.png" >/dev/null 2>"$out/x.err"
then bad "--prt-view on osmesa accepted"
else grep -q "soft backend only" "$out/x.err" && ok "--prt-view on osmesa: $(cat "$out/x.err")" \
     || { bad "--prt-view on osmesa: unclear error"; cat "$out/x.err"; }
fi

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
