#!/bin/sh
# tests/render/client_shadows.sh BUILD — lumo-client --shadows N (issue 21):
# the default package streamed from lumo-server over loopback and drawn with
# shadow maps must give lumo-render's picture of the same package with the
# same maps (soft: the very bytes, per pixel and per vertex), the GL backend
# the soft picture within raster-cross-backend's shadow bound (mean Delta E
# <= 0.5, PSNR >= 38 dB), the shadows must show (the unshadowed client's
# picture is beyond that bound), and a bad size is refused by name.
set -u
build=$1
bin=$build/bin
dir=$build/render/client-shadows
. tests/lib/background.sh
rm -rf "$dir" && mkdir -p "$dir"
pkg=$build/render/default.lumo
# rebaked when older than lumo-bake (same rule as cross_backend.sh)
[ "$pkg" -nt "$bin/lumo-bake" ] || "$bin/lumo-bake" --default -o "$pkg" --spp 64 --no-progress >/dev/null || exit 1

# same NAME A B MAX_DE MIN_PSNR: A and B within the bounds
same() {
    if "$bin/lumo-compare" "$2" "$3" --max-mean-de "$4" --min-psnr "$5" >"$dir/$1.cmp"; then ok "$1: $(cat "$dir/$1.cmp")"
    else bad "$1: $(cat "$dir/$1.cmp")"; fi
}

if spawn "lumo-server" "$dir/server.port" "$dir/server.log" \
        timeout 300 "$bin/lumo-server" "$pkg" --listen 127.0.0.1:0 --port-file "$dir/server.port"; then
    port=$(cut -d' ' -f1 "$dir/server.port")
    for run in "pixel-soft-512:--shadows 512" "vertex-soft-256:--per-vertex --shadows 256" \
               "pixel-osmesa-512:--backend osmesa --shadows 512" "pixel-soft-0:"; do
        name=${run%%:*}; args=${run#*:}
        # shellcheck disable=SC2086 # args are words
        timeout 120 "$bin/lumo-client" --connect "127.0.0.1:$port" --quiet --out "$dir/$name" $args \
            >"$dir/$name.txt" 2>&1 || bad "lumo-client $args: $(cat "$dir/$name.txt")"
    done
    "$bin/lumo-render" "$pkg" --per-pixel --shadows 512 -o "$dir/render-pixel.png" >/dev/null 2>&1 \
        && "$bin/lumo-render" "$pkg" --per-vertex --shadows 256 -o "$dir/render-vertex.png" >/dev/null 2>&1 \
        || bad "lumo-render did not draw the package"
    same "client == lumo-render, per pixel, 512^2 maps" "$dir/pixel-soft-512/frame-100.00.png" \
        "$dir/render-pixel.png" 0 99
    same "client == lumo-render, per vertex, 256^2 maps" "$dir/vertex-soft-256/frame-100.00.png" \
        "$dir/render-vertex.png" 0 99
    same "client soft ~ client osmesa with shadows" "$dir/pixel-soft-512/frame-100.00.png" \
        "$dir/pixel-osmesa-512/frame-100.00.png" 0.5 38
    if "$bin/lumo-compare" "$dir/pixel-soft-512/frame-100.00.png" "$dir/pixel-soft-0/frame-100.00.png" \
            --max-mean-de 0.5 --min-psnr 38 >"$dir/show.cmp"; then
        bad "the client's shadows do not show: $(cat "$dir/show.cmp")"
    else ok "the client's shadows show: $(cat "$dir/show.cmp")"; fi
fi
"$bin/lumo-client" --connect 127.0.0.1:1 --shadows 3 >"$dir/bad.txt" 2>&1
st=$?
[ $st -ne 0 ] && grep -q -- "--shadows 3: 0 (no shadows) or 8..2048 texels per side" "$dir/bad.txt" \
    && ok "lumo-client --shadows 3 refused by name" || bad "lumo-client --shadows 3: status $st, $(cat "$dir/bad.txt")"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
