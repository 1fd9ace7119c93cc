#!/bin/sh
# tests/vsl/vsl_render_test.sh BIN DIR — seed 004's GL renderer
# (lumo-vsl-render, rasterizer/gl/raster_gl_vsl.c) on OSMesa: the engine
# settled at two moments of the demo's motion, each frame drawn three ways
# (deferred spheres, the whole scene per VSL, one pass) which must agree;
# the GL's VSL light against the engine's srv_vsl_irradiance (the tool
# fails past 1e-3); with cut-off spheres that do not cover the frame
# (eps 0.01); OSMesa and EGL alike; against the path tracer of the same moment; the light's move
# changes the picture; bad settings and an area light are one-line errors.
# Prints "RESULT: N passed, M failed".
bin=$1; dir=$2
scene=tools/dynamic-demo/cornell_dynamic.txt
pass=0; fail=0
ok()  { pass=$((pass + 1)); echo "ok   $1"; }
bad() { fail=$((fail + 1)); echo "FAIL $1"; }
rm -rf "$dir"; mkdir -p "$dir"
run="timeout 300 $bin/lumo-vsl-render"
common="--size 160x120 --vsl 120 --pool 40000 --batch 20000"

# pct LOG LABEL: the relative L1 percentage of LABEL's line (first), x10 as an integer
pct() { sed -n "s/^  $2 *relative L1 *\([0-9.]*\)%.*/\1/p" "$1" | head -1 | awk '{printf "%d", $1 * 10}'; }

if $run "$scene" --out "$dir/a" --times 0,6 --reference 48 $common >"$dir/a.log" 2>&1; then
    ok "two moments drawn, the GL's VSL light within 1e-3 of srv_vsl_irradiance: $(grep -o 'difference .*' "$dir/a.log" | tr '\n' ' ')"
    w=$(pct "$dir/a.log" "whole-scene vs deferred"); p=$(pct "$dir/a.log" "one-pass vs deferred")
    [ "$w" -le 1 ] && [ "$p" -le 1 ] && ok "deferred, whole scene and one pass agree (<= 0.1%)" ||
        bad "the three ways differ: whole $w, one-pass $p (x0.1%)"
    r=$(pct "$dir/a.log" "VSL picture vs path traced")
    [ -n "$r" ] && [ "$r" -le 250 ] && ok "VSL picture vs the path tracer (48 spp): $((r / 10)).$((r % 10))% <= 25%" ||
        { bad "VSL picture vs path traced: ${r:-none} (x0.1%)"; cat "$dir/a.log"; }
    n=$(ls "$dir"/a/*.png 2>/dev/null | wc -l)
    [ "$n" -eq 10 ] && ok "10 pictures (3 ways, IVG, reference; 2 moments)" || bad "$n pictures, not 10"
    cmp -s "$dir/a/vsl-t00.00.png" "$dir/a/vsl-t06.00.png" && bad "the light moved and the picture did not change" ||
        ok "the picture follows the moving light"
else
    bad "lumo-vsl-render"; cat "$dir/a.log"
fi

# spheres that cover part of the frame: the deferred pass still agrees
if $run "$scene" --out "$dir/b" --eps 0.01 $common >"$dir/b.log" 2>&1; then
    w=$(pct "$dir/b.log" "whole-scene vs deferred")
    [ "$w" -le 1 ] && ok "eps 0.01 (cut-off spheres inside the box): deferred equals the whole scene" ||
        bad "eps 0.01: whole scene vs deferred $w (x0.1%)"
else
    bad "lumo-vsl-render --eps 0.01"; cat "$dir/b.log"
fi

# EGL (surfaceless, desktop core): the same engine state, the same picture
if $run "$scene" --backend egl --out "$dir/e" --eps 0.01 $common >"$dir/e.log" 2>&1; then
    cmp -s "$dir/b/vsl-t00.00.png" "$dir/e/vsl-t00.00.png" && ok "--backend egl draws OSMesa's picture" ||
        bad "--backend egl: another picture than OSMesa's"
else
    bad "lumo-vsl-render --backend egl"; cat "$dir/e.log"
fi
LUMO_EGL_API=gles $run "$scene" --backend egl --out "$dir/g" $common >"$dir/g.log" 2>&1
[ $? -eq 1 ] && grep -q "needs desktop OpenGL 3.3" "$dir/g.log" && ok "a GLES-only context is refused by name" ||
    { bad "GLES context not refused"; cat "$dir/g.log"; }

# refusals: one line each, no crash
printf 'quad -1,0,-1 0,0,2 2,0,0\nlight area:-0.2,1.99,-0.2:0.4,0,0:0,0,0.4:10,10,10\n' >"$dir/area.txt"
for args in "--size 0x0" "--backend nope" "--vsl 0" "--times x" "$dir/area.txt"; do
    # shellcheck disable=SC2086
    $run $( [ "$args" = "$dir/area.txt" ] || echo "$scene" ) $args --out "$dir/c" >"$dir/c.log" 2>&1
    st=$?
    [ $st -eq 1 ] && grep -q "^lumo-vsl-render: error: " "$dir/c.log" && ok "refused: $args ($(head -c 90 "$dir/c.log" | tr '\n' ' '))" ||
        { bad "not refused cleanly ($st): $args"; cat "$dir/c.log"; }
done
echo "RESULT: $pass passed, $fail failed"
[ $fail -eq 0 ]
