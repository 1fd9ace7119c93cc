#!/bin/sh
# tests/render/cross_backend.sh BUILD — soft, osmesa and egl (desktop GL 3.3
# core, and GLES 3.0 forced with LUMO_EGL_API=gles) draw the same
# scenes with one shading model (docs/rasterizer.md): every soft image must
# match each GL image within mean CIE Lab Delta E <= 2 and PSNR >= 38 dB (measured: 41-50 dB).
# Scenes: the baked default package (direct + IVG), the generated Cornell
# box (direct only), the bunny under point + spot + directional lights.
# With shadow maps (--shadows N: the soft path's maps and the GL backends'
# own, drawn from the same views with the same biases and 2x2 PCF) the
# bound is mean Delta E <= 0.5 (measured 0.04-0.10), and the shadows must
# show: the GL picture without shadows is beyond these bounds (mean or
# PSNR) from soft's with them.
set -u
build=$1
bin=$build/bin
out=$build/render/cross
mkdir -p "$out"
pass=0; fail=0
MAX_DE=2
MIN_PSNR=38

# A package older than lumo-bake is rebaked (its mesh chunks follow the
# baker's default: progressive PMSH streams since issue 5).
if [ ! "$build/render/default.lumo" -nt "$bin/lumo-bake" ]; then
    "$bin/lumo-bake" --default -o "$build/render/default.lumo" --spp 64 --no-progress >/dev/null || exit 1
fi

check() {  # check NAME ARGS... : render with the three backends and compare
    name=$1; shift
    for b in soft osmesa egl egl-gles; do
        api=gl; be=$b
        [ "$b" = egl-gles ] && { api=gles; be=egl; }
        if ! LUMO_EGL_API=$api "$bin/lumo-render" "$@" --backend $be -o "$out/$name-$b.png" \
                >"$out/$name-$b.log" 2>&1; then
            echo "FAIL $name: $b did not render"; cat "$out/$name-$b.log"
            fail=$((fail + 1)); return
        fi
    done
    for b in osmesa egl egl-gles; do
        if "$bin/lumo-compare" "$out/$name-soft.png" "$out/$name-$b.png" --labels "soft,$b" \
               --max-mean-de $MAX_DE --min-psnr $MIN_PSNR; then
            pass=$((pass + 1))
        else
            echo "FAIL $name: soft vs $b beyond mean dE $MAX_DE / PSNR $MIN_PSNR dB"
            fail=$((fail + 1))
        fi
    done
}

# check_shadows NAME ARGS... : check with the bound for shadows, and the
# shadows must matter (osmesa without them beyond the bound).
check_shadows() {
    name=$1; shift
    MAX_DE=0.5
    check "$name" "$@"
    MAX_DE=2
    if ! "$bin/lumo-render" $(echo "$@" | sed 's/--shadows [0-9]*//') --backend osmesa \
            -o "$out/$name-noshadow.png" >"$out/$name-noshadow.log" 2>&1; then
        echo "FAIL $name: osmesa without shadows did not render"; fail=$((fail + 1)); return
    fi
    if "$bin/lumo-compare" "$out/$name-soft.png" "$out/$name-noshadow.png" --max-mean-de 0.5 --min-psnr $MIN_PSNR >/dev/null; then
        echo "FAIL $name: the shadows do not show (soft with them ~ osmesa without)"
        fail=$((fail + 1))
    else
        pass=$((pass + 1))
    fi
}

pkg=$build/render/default.lumo
check pkg-pixel "$pkg" --per-pixel --size 320x240
check pkg-vertex "$pkg" --per-vertex --size 320x240
check pkg-pixel-noind "$pkg" --per-pixel --no-indirect --size 160x128
check cornell-pixel --default --per-pixel --size 320x240
check bunny-vertex --default --model build/data/models/bunny.obj --per-vertex --cull --size 640x480 \
    --camera 0.4,1.1,2.6:0,0.7,0:0,1,0:45 \
    --light point:0.8,1.6,1.2:12,10,8 --light spot:-0.9,1.8,0.5:0.7,-1,-0.3:30:30,30,40 \
    --light directional:0.2,-1,-0.4:0.4,0.4,0.5
check bunny-pixel-exposure --default --model build/data/models/bunny.obj --per-pixel --size 320x240 \
    --camera 0.4,1.1,2.6:0,0.7,0:0,1,0:45 --exposure 2.5 --light point:0.8,1.6,1.2:12,10,8

check_shadows pkg-pixel-shadows "$pkg" --per-pixel --size 320x240 --shadows 512
check_shadows pkg-vertex-shadows "$pkg" --per-vertex --size 320x240 --shadows 256
check_shadows bunny-pixel-shadows --default --model build/data/models/bunny.obj --per-pixel --size 320x240 \
    --camera 0.4,1.1,2.6:0,0.7,0:0,1,0:45 --shadows 256 \
    --light point:0.8,1.6,1.2:12,10,8 --light spot:-0.9,1.8,0.5:0.7,-1,-0.3:30:30,30,40 \
    --light directional:0.2,-1,-0.4:0.4,0.4,0.5

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
