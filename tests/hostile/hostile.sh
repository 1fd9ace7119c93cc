#!/bin/sh
# tests/hostile/hostile.sh BIN GEN WORK [GEN_FORMATS] — models, scene files, packages and
# bakes from hostile hands (issue 24, part B). GEN (gen_hostile) writes the
# corpus into WORK at test time from tests/fuzz/seeds/fuzz_package/lights.lumo
# (a real bake: 3 lights, raw meshes, an IVG), and GEN_FORMATS adds STL,
# glTF and GLB, the formats refused by name, lights field by field; every case runs each tool
# that reads it under a memory limit (ulimit -v, MEM_KB) and a time limit
# (timeout, SECS): a declared 10^9 faces over a few bytes must be refused
# within both, never crash (status > 1), and say the expected text. Good
# files of every reader must still pass. Prints "RESULT: N passed, M failed".
bin=$1; gen=$2; work=$3; gen_formats=${4:-}
MEM_KB=${MEM_KB:-1048576}   # 1 GiB of address space per tool run
SECS=${SECS:-20}
. tests/lib/background.sh
rm -rf "$work"; mkdir -p "$work/corpus" "$work/out"
corpus=$work/corpus; out=$work/out; log=$work/last.log

if ! "$gen" "$corpus" tests/fuzz/seeds/fuzz_package/lights.lumo ||
   { [ -n "$gen_formats" ] && ! "$gen_formats" "$corpus"; }; then
    bad "gen_hostile: cannot make the corpus"
    echo "RESULT: $pass passed, $fail failed"; exit 1
fi

# limited CMD...: CMD under the limits, stdout and stderr into $log; its status.
limited() {
    ( ulimit -v "$MEM_KB"; exec timeout "$SECS" "$@" ) >"$log" 2>&1
}

# check NAME EXPECT STATUS: "OK" wants status 0; anything else a refusal:
# status 1 (bad input) or 2 (a bad command line: the tools' own checks of
# a path, issue 24 part A) and EXPECT in the output, case aside (a crash, a
# timeout or a kill by the limit fails).
check() {
    if [ "$2" = OK ]; then
        if [ "$3" -eq 0 ]; then ok "$1"; else bad "$1: status $3, want 0"; sed 's/^/    /' "$log" | tail -3; fi
    elif { [ "$3" -eq 1 ] || [ "$3" -eq 2 ]; } && grep -qiF -- "$2" "$log"; then
        ok "$1: $(grep -iF -- "$2" "$log" | head -1 | cut -c1-150)"
    else
        bad "$1: status $3 (want 1 or 2 and '$2')"; sed 's/^/    /' "$log" | tail -3
    fi
}

run() {  # run NAME EXPECT CMD...
    n=$1; e=$2; shift 2
    limited "$@"; check "$n" "$e" $?
}

light="point:0,2,0:1,1,1"
model_case() {  # the importer front end, through both tools that read models
    f=$1; e=$2; b=$(basename "$f")
    run "lumo-pm build $b" "$e" "$bin/lumo-pm" build "$f" -o "$out/pm.lumo"
    run "lumo-bake $b" "$e" "$bin/lumo-bake" "$f" --light "$light" --grid 2 --spp 1 --no-progress \
        -o "$out/bake.lumo"
}

package_case() {  # one validation path: the same refusal from every reader
    f=$1; e=$2; b=$(basename "$f")
    case $b in
    info_none.lumo) ;;   # lumo-inspect lists stream-only packages (no INFO)
    *) run "lumo-inspect $b" "$e" "$bin/lumo-inspect" "$f" ;;
    esac
    run "lumo-render $b" "$e" "$bin/lumo-render" "$f" -o "$out/r.png"
    if [ "$e" != OK ]; then
        run "lumo-server $b" "$e" "$bin/lumo-server" "$f" --listen 127.0.0.1:0 --quiet
    fi
}

tab=$(printf '\t')
while IFS="$tab" read -r kind file expect; do
    case $kind in
    model) model_case "$file" "$expect" ;;
    scene) run "lumo-bake $(basename "$file")" "$expect" "$bin/lumo-bake" "$file" --grid 2 --spp 1 \
               --no-progress -o "$out/scene.lumo" ;;
    package) package_case "$file" "$expect" ;;
    png) run "lumo-compare $(basename "$file")" "$expect" "$bin/lumo-compare" "$file" "$file" ;;
    esac
done <"$corpus/manifest"

# Files that are not model files at all.
mkdir -p "$corpus/dir.obj"
run "lumo-pm build a directory" "a directory, not a" "$bin/lumo-pm" build "$corpus/dir.obj" -o "$out/d.lumo"
run "lumo-pm build a missing file" "no such file" "$bin/lumo-pm" build "$corpus/none.obj" -o "$out/d.lumo"
run "lumo-pm build a FIFO" "not a regular file" "$bin/lumo-pm" build /dev/stdin -o "$out/d.lumo" </dev/null
mkfifo "$corpus/pipe.mtl" && printf 'mtllib pipe.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$corpus/pipe.obj"
run "lumo-pm build an OBJ whose mtllib is a FIFO" "line 1: mtllib 'pipe.mtl' is not a regular file" \
    "$bin/lumo-pm" build "$corpus/pipe.obj" -o "$out/d.lumo"
printf '%s' '{"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"pipe.mtl"}],"bufferViews":[{"buffer":0,' \
    '"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],' \
    '"max":[1,1,0]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],' \
    '"scenes":[{"nodes":[0]}]}' >"$corpus/pipe.gltf"
run "lumo-pm build a glTF whose buffer is a FIFO" "buffer 0: 'pipe.mtl' is not a regular file" \
    "$bin/lumo-pm" build "$corpus/pipe.gltf" -o "$out/d.lumo"

# A hostile HTTP server (lumo-client --http): a Content-Range whose total is
# "-1" (sscanf's %llu read it as 2^64 - 1) or past 64 bits is not a size.
# busybox nc answers the first request with the canned response.
http_case() {  # http_case NAME TOTAL
    http_n=$((${http_n:-0} + 1)); port=$((20000 + ($$ * 3 + http_n) % 20000))
    printf 'HTTP/1.1 206 Partial Content\r\nContent-Range: bytes 0-23/%s\r\nContent-Length: 24\r\n' "$2" \
        >"$corpus/http.resp"
    printf 'Connection: close\r\n\r\nLUMO0123456789abcdefghij' >>"$corpus/http.resp"
    busybox nc -l -p "$port" <"$corpus/http.resp" >/dev/null 2>&1 &
    nc_pid=$!
    sleep 0.3
    run "lumo-client --http $1" "the server did not say the file's size (Content-Range)" \
        "$bin/lumo-client" --http "http://127.0.0.1:$port/x.lumo" --out "$out"
    kill "$nc_pid" 2>/dev/null; wait "$nc_pid" 2>/dev/null
}
if command -v busybox >/dev/null; then
    http_case "Content-Range total -1" -1
    http_case "Content-Range total past 64 bits" 99999999999999999999999
    http_case "Content-Range total 1x" 1x
else
    bad "busybox (tools/setup.sh: busybox-static) is missing: no hostile HTTP server"
fi

# The bake's budget: said, refused past it, taken with --allow-large.
scene=tests/fuzz/package_seeds/tiny.txt
run "bake --cell 0.000001" "asks for a 2000002x600002x2000002 grid; the most is 256 per axis" \
    "$bin/lumo-bake" "$scene" --cell 0.000001 --no-progress -o "$out/b.lumo"
run "bake --cell 0" "--cell 0" "$bin/lumo-bake" "$scene" --cell 0 --no-progress -o "$out/b.lumo"
run "bake --grid 256" "grid 256x256x256 (16777216 vertices), 256 spp: 4294.97 M paths, at least 7728 MB: past the budget" \
    "$bin/lumo-bake" "$scene" --grid 256 --no-progress -o "$out/b.lumo"
run "bake --grid 65 --spp 1" "past the budget of 262144 vertices" \
    "$bin/lumo-bake" "$scene" --grid 65 --spp 1 --no-progress -o "$out/b.lumo"
run "bake --grid 32 --spp 1024" "33.55 M paths" \
    "$bin/lumo-bake" "$scene" --grid 32 --spp 1024 --no-progress -o "$out/b.lumo"
run "bake --cell 0.01 says its grid" "grid 202x62x202 (2529848 vertices)" \
    "$bin/lumo-bake" "$scene" --cell 0.01 --no-progress -o "$out/b.lumo"
run "bake --grid 65 --spp 1 --allow-large" OK \
    "$bin/lumo-bake" "$scene" --grid 65 --spp 1 --threads 2 --allow-large --no-progress -o "$out/b.lumo"
run "bake --cell 0.5 announces its grid" OK "$bin/lumo-bake" "$scene" --cell 0.5 --spp 1 --no-progress -o "$out/b.lumo"
if grep -qF "lumo-bake: grid 5x3x5 (75 vertices), 1 spp" "$log"; then ok "bake --cell 0.5: grid said before tracing"
else bad "bake --cell 0.5: no plan line"; sed 's/^/    /' "$log"; fi

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
