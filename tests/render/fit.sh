#!/bin/sh
# tests/render/fit.sh BUILD TESTBIN — a scene without a camera is framed
# (issue 21, docs/scene-format.md "Fitted camera"): random models of
# random size (1 cm to 300 m), place and shape (one to three ellipsoids and
# boxes, written as OBJ by awk) baked by lumo-bake with no --camera, then
# drawn by lumo-render from the package's camera, by `lumo-render --fit` in
# a portrait frame and by `lumo-client --fit` streaming from lumo-server:
# the lit object is whole in every picture (no lit pixel on an edge) and
# not lost in the distance (tests/render/framed.c). Also: the bake says the
# bounds and the fitted camera, and a bad --camera is refused by name.
set -u
build=$1; tbin=$2
bin=$build/bin
dir=$build/render/fit
mkdir -p "$dir"
. tests/lib/background.sh

# model SEED FILE: an OBJ of 1-3 parts (UV ellipsoids, boxes) around a
# random centre, sized by a random scale.
model() {
    awk -v seed="$1" 'BEGIN {
        srand(seed); scale = 10 ^ (rand() * 4.5 - 2); parts = 1 + int(rand() * 3)
        cx = (rand() * 2 - 1) * 1000 * (scale < 3 ? scale : 3); cy = (rand() * 2 - 1) * 50; cz = (rand() * 2 - 1) * 200
        n = 0; pi = 3.14159265
        for (q = 0; q < parts; q++) {
            ox = cx + (rand() * 2 - 1) * scale; oy = cy + (rand() * 2 - 1) * scale; oz = cz + (rand() * 2 - 1) * scale
            rx = scale * (0.1 + rand()); ry = scale * (0.1 + rand()); rz = scale * (0.1 + rand())
            if (rand() < 0.6) {
                S = 16; R = 10; base = n
                for (i = 0; i <= R; i++) for (j = 0; j < S; j++) {
                    t = pi * i / R; p = 2 * pi * j / S
                    printf "v %.6f %.6f %.6f\n", ox + rx * sin(t) * cos(p), oy + ry * cos(t), oz + rz * sin(t) * sin(p); n++
                }
                for (i = 0; i < R; i++) for (j = 0; j < S; j++) {
                    a = base + i * S + j + 1; b = base + i * S + (j + 1) % S + 1; c = a + S; d = b + S
                    if (i > 0) printf "f %d %d %d\n", a, b, d
                    if (i < R - 1) printf "f %d %d %d\n", a, d, c
                }
            } else {
                base = n
                for (k = 0; k < 8; k++) {
                    printf "v %.6f %.6f %.6f\n", ox + (k % 2 ? rx : -rx), oy + (int(k / 2) % 2 ? ry : -ry), oz + (k >= 4 ? rz : -rz); n++
                }
                split("1 3 4 2 5 6 8 7 1 2 6 5 3 7 8 4 1 5 7 3 2 4 8 6", f, " ")
                for (k = 0; k < 6; k++) {
                    printf "f %d %d %d\n", base + f[4*k+1], base + f[4*k+2], base + f[4*k+3]
                    printf "f %d %d %d\n", base + f[4*k+1], base + f[4*k+3], base + f[4*k+4]
                }
            }
        }
    }' > "$2"
}

framed() {  # framed WHAT PNG
    if "$tbin/framed" "$2" 30 >"$dir/framed.txt" 2>&1; then ok "$1: $(cat "$dir/framed.txt")"
    else bad "$1: $(cat "$dir/framed.txt")"; fi
}

light=directional:0.3,-1,-0.4:3,3,3
for seed in 11 23 37 41 59 67; do
    m="$dir/model-$seed.obj"; pkg="$dir/model-$seed.lumo"
    model "$seed" "$m"
    if ! "$bin/lumo-bake" "$m" --light "$light" --grid 4 --spp 16 --no-progress -o "$pkg" >"$dir/bake.txt" 2>&1; then
        bad "model $seed: bake failed: $(cat "$dir/bake.txt")"; continue
    fi
    grep -q "scene bounds .* no camera given, fitted: --camera " "$dir/bake.txt" \
        && ok "model $seed: the bake says the bounds and the fitted camera" \
        || bad "model $seed: no fitted-camera line: $(cat "$dir/bake.txt")"
    "$bin/lumo-render" "$pkg" --size 160x120 -o "$dir/model-$seed.png" >/dev/null 2>&1 \
        && framed "model $seed, package camera, 160x120" "$dir/model-$seed.png" \
        || bad "model $seed: lumo-render failed"
    "$bin/lumo-render" "$pkg" --fit --size 90x160 --per-pixel -o "$dir/model-$seed-portrait.png" >/dev/null 2>&1 \
        && framed "model $seed, --fit, 90x160" "$dir/model-$seed-portrait.png" \
        || bad "model $seed: lumo-render --fit failed"
done

# A model's own camera wins: the bake keeps --camera and says nothing of a fit.
"$bin/lumo-bake" "$dir/model-11.obj" --light "$light" --grid 4 --spp 16 --no-progress \
    --camera 0,0,100:0,0,0:0,1,0:40 -o "$dir/own.lumo" >"$dir/bake.txt" 2>&1 && ! grep -q fitted "$dir/bake.txt" \
    && ok "--camera given: no fit" || bad "--camera given: $(cat "$dir/bake.txt")"

# lumo-client --fit over TCP draws the streamed scene framed in a portrait frame.
if spawn "lumo-server" "$dir/server.port" "$dir/server.log" \
        timeout 120 "$bin/lumo-server" "$dir/model-23.lumo" --listen 127.0.0.1:0 --port-file "$dir/server.port"; then
    port=$(cut -d' ' -f1 "$dir/server.port")
    rm -rf "$dir/client" && mkdir -p "$dir/client"
    if timeout 120 "$bin/lumo-client" --connect "127.0.0.1:$port" --fit --size 120x160 --quiet \
            --out "$dir/client" >"$dir/client.txt" 2>&1; then
        framed "lumo-client --fit, 120x160" "$dir/client/frame-100.00.png"
    else bad "lumo-client --fit: $(cat "$dir/client.txt")"; fi
    # --camera (parsed once, applied to every frame) draws what lumo-render draws from it
    cam=0.3,0.2,2:0,0,0:0,1,0:50
    rm -rf "$dir/client-cam" && mkdir -p "$dir/client-cam"
    if timeout 120 "$bin/lumo-client" --connect "127.0.0.1:$port" --camera "$cam" --size 120x160 --quiet \
            --frames-at 10,100 --out "$dir/client-cam" >"$dir/client.txt" 2>&1 &&
        "$bin/lumo-render" "$dir/model-23.lumo" --camera "$cam" --size 120x160 -o "$dir/render-cam.png" \
            >/dev/null 2>&1 && cmp -s "$dir/client-cam/frame-100.00.png" "$dir/render-cam.png"; then
        ok "lumo-client --camera: the streamed scene equals lumo-render --camera's picture"
    else bad "lumo-client --camera: $(cat "$dir/client.txt")"; fi
fi
"$bin/lumo-client" --connect 127.0.0.1:1 --camera 1,1,1:1,1,1:0,1,0:40 >"$dir/cam.txt" 2>&1
[ $? -eq 2 ] && grep -q -- "--camera 1,1,1:1,1,1:0,1,0:40: not EYE:TARGET:UP:FOVY" "$dir/cam.txt" \
    && ok "lumo-client: eye == target refused by name" || bad "lumo-client --camera eye == target: $(cat "$dir/cam.txt")"
"$bin/lumo-render" "$dir/model-11.lumo" --camera 1,1,1:1,1,1:0,1,0:40 -o "$dir/x.png" >"$dir/cam.txt" 2>&1
[ $? -eq 1 ] && grep -q -- "--camera 1,1,1:1,1,1:0,1,0:40: " "$dir/cam.txt" \
    && ok "lumo-render: eye == target refused by name" || bad "lumo-render --camera eye == target: $(cat "$dir/cam.txt")"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
