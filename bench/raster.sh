#!/bin/sh
# bench/raster.sh BUILD — the soft rasterizer against Mesa through OSMesa
# (llvmpipe on one thread, LP_NUM_THREADS=0, and softpipe), same packages,
# same camera orbit, in one run; callgrind instructions per frame; RAM per
# resolution and band height. Writes BUILD/bench/sections/50-raster.md.
set -eu
build=$1
bin=$build/bin
work=$build/bench/raster
out=$build/bench/sections/50-raster.md
mkdir -p "$work" "$(dirname "$out")"
FRAMES=${RASTER_BENCH_FRAMES:-6}
SP_FRAMES=${RASTER_BENCH_SOFTPIPE_FRAMES:-2}

for m in 48k 203k; do
    [ -f "$work/dragon_$m.lumo" ] || "$bin/lumo-bake" --default --dragon "build/data/models/dragon_$m.ply" \
        --spp 16 -o "$work/dragon_$m.lumo" --no-progress >/dev/null
done

ms() {  # ms BACKEND DRIVER FRAMES ARGS... -> mean ms/frame
    be=$1; drv=$2; n=$3; shift 3
    LP_NUM_THREADS=0 GALLIUM_DRIVER=$drv "$bin/lumo-render" "$@" --backend "$be" --frames "$n" --orbit \
        --warmup 1 -o "$work/frame.png" | sed -n 's/.* \([0-9.]*\) ms\/frame mean.*/\1/p'
}
REPS=${RASTER_BENCH_REPS:-3}
med() {  # med V... -> the median
    printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'
}

{
echo "## Rasterizer: soft (fixed point) vs Mesa llvmpipe and softpipe"
echo
echo "Made by \`make bench-raster\` (bench/raster.sh): \`lumo-render PKG --backend B --size WxH"
echo "--per-vertex|--per-pixel --frames $FRAMES --orbit --warmup 1\` with \`LP_NUM_THREADS=0\`"
echo "(llvmpipe rasterizes on the calling thread) and \`GALLIUM_DRIVER=llvmpipe|softpipe\`;"
echo "softpipe runs $SP_FRAMES frames. Scene: the default Cornell box with the Stanford dragon"
echo "(\`lumo-bake --default --dragon dragon_N.ply --spp 16\`), direct spot light + IVG indirect"
echo "light, an orbit of the camera around the target. ms/frame is the mean over the orbit, after"
echo "one untimed frame (GL shader compilation). Ratio = Mesa time / soft time (> 1: soft is faster)."
echo "All three read the same package and draw the same shading model (tests/render/cross_backend.sh)."
echo "Load average at the start: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores; on a shared machine the"
echo "ms columns are noisy, the callgrind counts below are not."
echo
echo "Soft lights the vertices once (per-vertex rows; \`lumo_raster_light_vertices\`, again only when a"
echo "light or the IVG changes — diffuse light does not depend on the view); \"soft, lit each frame\" is"
echo "\`--relight\` (the cost before the cache), \"soft + shadows\" adds 512² shadow maps (\`--shadows 512\`,"
echo "drawn in the warm-up frame, once: the light does not move); \"llvmpipe + shadows\" the GL backend's own"
echo "maps of the same size (rasterizer/gl/raster_gl_shadow.c, also drawn once)."
echo
echo "Soft and llvmpipe runs alternate $REPS times per row (soft, llvmpipe, soft, llvmpipe, ...); each ms"
echo "column is the median of its $REPS runs, and the ratio llvmpipe/soft is taken of the medians."
echo "\"soft, IVG per vertex\" (per-pixel rows) samples the IVG once per vertex side and interpolates it"
echo "(\`--ivg-vertex\`; direct light and shadows stay per pixel; docs/rasterizer.md \"IVG per vertex\")."
echo "Soft per pixel samples the IVG through a sampler with a memo of the last opened cell (\`lumo_ivg_sampler\`)"
echo "and draws with \`LUMO_RASTER_DEPTH_FIRST\` (a depth-only pass, then each pixel shaded once); both give the"
echo "same bytes as without (docs/rasterizer.md \"Round four\")."
echo "Commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)."
echo
echo "| mesh | size | lighting | soft ms | soft, lit each frame ms | soft, IVG per vertex ms | soft + shadows ms | llvmpipe ms | llvmpipe + shadows ms | softpipe ms | llvmpipe/soft | llvmpipe/soft IVG per vertex | llvmpipe/soft with shadows | softpipe/soft |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for m in 48k 203k; do
    for size in 320x240 640x480; do
        for mode in per-vertex per-pixel; do
            a="$work/dragon_$m.lumo --size $size --$mode"
            S=""; L=""; V=""
            for k in $(seq "$REPS"); do
                S="$S $(ms soft llvmpipe "$FRAMES" $a)"
                L="$L $(ms osmesa llvmpipe "$FRAMES" $a)"
                [ "$mode" = per-pixel ] && V="$V $(ms soft llvmpipe "$FRAMES" $a --ivg-vertex)"
            done
            s=$(med $S); l=$(med $L)
            r=$(ms soft llvmpipe "$FRAMES" $a --relight)
            h=$(ms soft llvmpipe "$FRAMES" $a --shadows 512)
            lh=$(ms osmesa llvmpipe "$FRAMES" $a --shadows 512)
            p=$(ms osmesa softpipe "$SP_FRAMES" $a)
            if [ "$mode" = per-pixel ]; then
                r="="; v=$(med $V); lv=$(awk -v a="$l" -v b="$v" 'BEGIN{printf "%.2f", a/b}')
            else
                v="="; lv="="
            fi
            echo "| dragon $m | $size | $mode | $s | $r | $v | $h | $l | $lh | $p | $(awk -v a="$l" -v b="$s" 'BEGIN{printf "%.2f", a/b}') | $lv | $(awk -v a="$lh" -v b="$h" 'BEGIN{printf "%.2f", a/b}') | $(awk -v a="$p" -v b="$s" 'BEGIN{printf "%.2f", a/b}') |"
        done
    done
done
echo
echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)."
echo
echo "### Instructions per frame (callgrind)"
echo
echo "\`valgrind --tool=callgrind --toggle-collect='timed_frame*' lumo-render PKG --frames 2 --orbit --warmup 1 ...\`:"
echo "instructions executed inside the timed frames (the draw and, for GL, the read-back), divided by 2."
echo
echo "| backend | mesh | size | lighting | instructions / frame |"
echo "|---|---|---|---|---|"
cg() {  # cg LABEL BACKEND ARGS...
    label=$1; be=$2; shift 2
    n=$(LP_NUM_THREADS=0 GALLIUM_DRIVER=llvmpipe valgrind --tool=callgrind --toggle-collect='timed_frame*' \
        --callgrind-out-file=/dev/null "$bin/lumo-render" "$@" --backend "$be" --frames 2 --orbit --warmup 1 \
        -o "$work/cg.png" 2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p')
    echo "| $label | $(echo "$@" | sed 's/.*dragon_\([0-9k]*\).lumo --size \([0-9x]*\) --\([a-z-]*\).*/dragon \1 | \2 | \3/') | $(awk -v n="$n" 'BEGIN{printf "%.1f M", n/2e6}') |"
}
for m in 48k 203k; do
    for size in 320x240 640x480; do
        for mode in per-vertex per-pixel; do
            cg soft soft "$work/dragon_$m.lumo" --size $size --$mode
            cg "osmesa llvmpipe" osmesa "$work/dragon_$m.lumo" --size $size --$mode
        done
        cg "soft, IVG per vertex" soft "$work/dragon_$m.lumo" --size $size --per-pixel --ivg-vertex
    done
done
cg "soft, lit each frame" soft "$work/dragon_48k.lumo" --size 320x240 --per-vertex --relight
cg "soft + shadows 512" soft "$work/dragon_48k.lumo" --size 320x240 --per-pixel --shadows 512
echo
echo "### RAM of the soft rasterizer per resolution and band height"
echo
echo "\`lumo-raster-ram\`: colour + depth bytes of one band (lumo_raster_band_bytes); a frame is drawn"
echo "as ceil(H / K) bands, each a pass over the mesh. Plus about 3.1 KB of stack in lumo_raster_draw on Cortex-M3"
echo "(docs/rasterizer.md) and the mesh itself."
echo
"$bin/lumo-raster-ram"
echo
echo "Band height trades RAM for time (dragon 48k, 320x240, per-vertex, RGB565 + 16-bit depth, soft):"
echo
echo "| K | ms/frame |"
echo "|---|---|"
for k in 240 60 16 4; do
    echo "| $k | $(ms soft llvmpipe "$FRAMES" "$work/dragon_48k.lumo" --size 320x240 --per-vertex --rgb565 --depth16 --bands $k) |"
done
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "bench-raster: wrote $out" >&2
