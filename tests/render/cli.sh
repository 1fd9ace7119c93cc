#!/bin/sh
# tests/render/cli.sh BUILD — lumo-render and lumo-compare as users meet
# them: outputs exist with the right size, orbit frames are numbered, bad
# arguments and bad files fail with status 1 or 2 and one message, never a
# crash; band/format options change no pixel of XRGB8888 output; --default,
# --model, --camera and --light go through the server's scene room.
set -u
build=$1
bin=$build/bin
out=$build/render/cli
mkdir -p "$out"
pass=0; fail=0
ok()   { pass=$((pass + 1)); }
bad()  { echo "FAIL $*"; fail=$((fail + 1)); }
expect_status() {  # expect_status WANT CMD...
    want=$1; shift
    "$@" >"$out/last.log" 2>&1
    got=$?
    if [ "$got" -eq "$want" ]; then ok; else bad "'$*' exited $got, want $want"; cat "$out/last.log"; fi
}
pkg=$build/render/default.lumo
# rebaked when older than lumo-bake (same rule as cross_backend.sh); the
# default package carries progressive meshes, decoded by lumo-render
[ "$pkg" -nt "$bin/lumo-bake" ] || "$bin/lumo-bake" --default -o "$pkg" --spp 64 --no-progress >/dev/null || exit 1

expect_status 0 "$bin/lumo-render" "$pkg" -o "$out/a.png" --size 64x48
if grep -q "progressive meshes at --lod all" "$out/last.log"; then ok; else bad "default package: no progressive meshes"; fi
expect_status 0 "$bin/lumo-render" "$pkg" -o "$out/lod.png" --size 64x48 --lod 10%
if "$bin/lumo-render" --help | grep -q -- "--lod N|P%|all"; then ok; else bad "--help lacks --lod"; fi
expect_status 2 "$bin/lumo-render" "$pkg" -o "$out/x.png" --lod 10q
expect_status 1 "$bin/lumo-render" --default -o "$out/x.png" --lod 10%
if file "$out/a.png" 2>/dev/null | grep -q "64 x 48"; then ok; else bad "a.png is not 64x48"; fi
expect_status 0 "$bin/lumo-render" "$pkg" -o "$out/orbit.png" --size 32x24 --frames 3 --orbit
if [ -f "$out/orbit_000.png" ] && [ -f "$out/orbit_002.png" ]; then ok; else bad "orbit frames missing"; fi
# bands, 16-bit depth and the vertex cache do not change the XRGB8888 bytes
expect_status 0 "$bin/lumo-render" "$pkg" -o "$out/full.png" --size 96x72 --per-pixel
expect_status 0 "$bin/lumo-render" "$pkg" -o "$out/band.png" --size 96x72 --per-pixel --bands 5 --no-cache
if "$bin/lumo-compare" "$out/full.png" "$out/band.png" | grep -q "PSNR 99.00"; then ok; else bad "bands changed pixels"; fi
# --default is the server's default scene (srv_default_scene, converted by
# scene_convert.c): without IVG it draws what the scene's raw-mesh package
# draws, both lighting modes (measured: mean dE 0.001)
raw=$out/default-raw.lumo
[ "$raw" -nt "$bin/lumo-bake" ] || "$bin/lumo-bake" --default --mesh raw --grid 2 --spp 1 -o "$raw" \
    --no-progress >/dev/null || exit 1
for mode in per-vertex per-pixel; do
    expect_status 0 "$bin/lumo-render" "$raw" --no-indirect --$mode -o "$out/raw-$mode.png" --size 160x120
    expect_status 0 "$bin/lumo-render" --default --$mode -o "$out/default-$mode.png" --size 160x120
    if "$bin/lumo-compare" "$out/raw-$mode.png" "$out/default-$mode.png" --max-mean-de 0.1 >"$out/cmp.log" 2>&1
    then ok; else bad "--default $mode is not the server's default scene: $(cat "$out/cmp.log")"; fi
done
# --model through the server's assimp import: a format the renderer never
# read itself (OFF), a cube of 12 triangles beside the 10 of the walls
printf 'OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n' \
    >"$out/cube.off"
expect_status 0 "$bin/lumo-render" --default --model "$out/cube.off" -o "$out/cube.png" --size 64x48
if grep -q " 22 triangles" "$out/last.log"; then ok; else bad "--model cube.off: $(cat "$out/last.log")"; fi
expect_status 1 "$bin/lumo-render" --default --model "$out/missing.obj" -o "$out/x.png"
printf 'not a model\n' >"$out/garbage.obj"
expect_status 1 "$bin/lumo-render" --default --model "$out/garbage.obj" -o "$out/x.png"
# camera and light strings through the server's parsers
expect_status 0 "$bin/lumo-render" --default -o "$out/area.png" --size 64x48 \
    --light area:-0.25,1.98,-0.25:0.5,0,0:0,0,0.5:20,20,20 --camera 0,1,3.4:0,1,0:0,1,0:40
# a bad light is a refused command line (status 2, docs/tool-options.md),
# named field by field (tests/hostile/cli.sh has the texts)
expect_status 2 "$bin/lumo-render" --default -o "$out/x.png" --light point:0,1,0:-1,1,1
expect_status 2 "$bin/lumo-render" --default -o "$out/x.png" --light spot:0,1,0:0,0,0:30:1,1,1
expect_status 1 "$bin/lumo-render" --default -o "$out/x.png" --camera 0,1,3:0,1,0:0,1,0:0.5
# errors
expect_status 2 "$bin/lumo-render" "$pkg"
expect_status 2 "$bin/lumo-render" "$pkg" -o "$out/x.png" --size 0x10
expect_status 2 "$bin/lumo-render" "$pkg" -o "$out/x.png" --bands 0
expect_status 1 "$bin/lumo-render" "$pkg" -o "$out/x.png" --camera 0,0,0:0,0,0:0,1,0:40
expect_status 1 "$bin/lumo-render" "$pkg" -o "$out/x.png" --camera 1,2,3
expect_status 1 "$bin/lumo-render" "$pkg" -o "$out/x.png" --backend vulkan
expect_status 1 "$bin/lumo-render" "$out/missing.lumo" -o "$out/x.png"
head -c 1000 "$pkg" > "$out/truncated.lumo"
expect_status 1 "$bin/lumo-render" "$out/truncated.lumo" -o "$out/x.png"
# a version-1 package (before the IVG streaming order): one line that says to re-bake
expect_status 1 "$bin/lumo-render" tests/server/data/v1_tiny.lumo -o "$out/x.png"
if [ "$(wc -l <"$out/last.log")" -eq 1 ] && grep -q "package version 1: re-bake it with this lumo-bake" "$out/last.log"
then ok; else bad "version-1 package: $(cat "$out/last.log")"; fi
expect_status 2 "$bin/lumo-compare" "$out/a.png"
expect_status 1 "$bin/lumo-compare" "$out/a.png" "$out/full.png"
expect_status 0 "$bin/lumo-compare" "$out/full.png" "$out/band.png" --max-mean-de 0 -o "$out/side.png"
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
