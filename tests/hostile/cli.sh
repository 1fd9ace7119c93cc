#!/bin/sh
# tests/hostile/cli.sh BUILD — every tool's command line as a hostile user
# types it (issue 24, part A). The cases are generated here at test time:
# for each numeric option of each tool, values that wrap, are not finite,
# are garbage or sit one past a bound; named files that are missing, empty,
# a directory, a device or not of their kind; outputs that cannot be
# written; packages the tool cannot draw. Each case has its expected exit
# status and refusal text: one "TOOL: error:" line on stderr that names the
# option and the value (or the file) and says why. Never a crash, a usage
# dump or a silent fallback. Prints "RESULT: N passed, M failed".
set -u
build=$1
bin=$build/bin
tmp=$build/tests/hostile-cli
rm -rf "$tmp"
mkdir -p "$tmp/adir"
pass=0; fail=0

# expect STATUS TEXT CMD...: CMD exits STATUS, its stderr is exactly one
# line and holds "error: TEXT" (TEXT a fixed string).
expect() {
    want=$1 text=$2; shift 2
    "$@" >"$tmp/out" 2>"$tmp/err" </dev/null
    got=$?
    lines=$(wc -l <"$tmp/err")
    if [ "$got" -eq "$want" ] && [ "$lines" -eq 1 ] && grep -qF -- "error: $text" "$tmp/err"; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
        echo "FAIL: $* -> status $got (want $want), stderr:"
        sed 's/^/    /' "$tmp/err" | head -5
        echo "    want: error: $text"
    fi
}

# The files the cases name.
: >"$tmp/empty.ply"
printf 'not a model\n' >"$tmp/garbage.obj"
printf '\211PNG\r\n\032\n' >"$tmp/picture.png"
model=$build/data/models/dragon_11k.ply
[ -f "$model" ] || { echo "RESULT: 0 passed, 1 failed ($model missing: run tools/setup.sh)"; exit 1; }
"$bin/lumo-render" --default -o "$tmp/a.png" --size 32x24 >/dev/null 2>&1 || echo "could not render a.png"
"$bin/lumo-pm" build "$model" -o "$tmp/pm.lumo" --batch 500 >/dev/null 2>&1 || echo "could not build pm.lumo"

# ---- numbers: wrap, not finite, garbage, one past a bound ------------------
# Each row: tool, fixed arguments, option, value, expected refusal.
r() { expect 2 "$3 $4: $5" "$bin/lumo-render" --default -o "$tmp/x.png" "$3" "$4"; }
while IFS='|' read -r opt val why; do
    r - - "$opt" "$val" "$why"
done <<'EOF'
--size|4294967312x16|width must be 1..2048
--size|16x4294967312|height must be 1..2048
--size|0x16|width must be 1..2048
--size|2049x16|width must be 1..2048
--size|640|not WxH (e.g. 320x240)
--size|-5x5|width must be 1..2048
--size|5x|height is not an integer
--frames|0|must be 1..100000
--frames|abc|not an integer
--frames|4294967297|must be 1..100000
--frames|1e3|not an integer
--bands|0|must be 1..2048
--bands|+5|not an integer
--warmup|-1|must be 0..1000
--warmup|1001|must be 0..1000
--exposure|nan|not a finite number
--exposure|inf|not a finite number
--exposure|1e999|not a finite number
--exposure|-0.1|must be 0..65535
--exposure|2x|not a number
--lod|abc|not all, N (at most N vertices) or P% (percent streamed)
--lod|0|must be 1..4294967295
--lod|4294967296|must be 1..4294967295
--lod|101%|percentage must be 0..100
--lod|nan%|percentage not a finite number
EOF

b() { expect 1 "$1 $2: $3" "$bin/lumo-bake" --default -o "$tmp/x.lumo" --no-progress "$1" "$2"; }
while IFS='|' read -r opt val why; do b "$opt" "$val" "$why"; done <<'EOF'
--grid|1|must be 2..256 (N or NX,NY,NZ)
--grid|4294967298|must be 2..256 (N or NX,NY,NZ)
--grid|4,1,4|value 2 must be 2..256
--grid|4,4|1 or 3 values wanted, 2 given
--grid|4,4,4,4|more than 3 values
--cell|0|must be above 0 and at most 1e+06
--cell|nan|not a finite number
--cell|-1|must be above 0 and at most 1e+06
--spp|0|must be 1..16777216
--spp|16777217|must be 1..16777216
--seed|-1|must be 0..18446744073709551615
--seed|18446744073709551616|must be 0..18446744073709551615
--threads|0|must be 1..256
--albedo|1,1|3 values separated by commas wanted, 2 given
--albedo|1,nan,1|value 2: not a finite number
--albedo|0.5,0.5,2|value 3 must be 0..1
--reference|4294967312x16|width must be 1..16384
--exposure|inf|not a finite number
--mesh|foo|must be one of raw, pm, both
--camera|0,1,2:0,1,2:0,1,0:40|eye and target are the same point
--camera|0,1,2:0,1,3:0,0,1:40|UP is zero or parallel to the view direction
--camera|0,1,2:0,1,3:0,1,0:180|FOVY must be a number of degrees above 0 and below 180
--camera|a:b|not 4 fields EYE:TARGET:UP:FOVY
EOF

M=$model
p() { expect 2 "$1 $2: $3" "$bin/lumo-pm" build "$M" -o "$tmp/p.lumo" "$1" "$2"; }
while IFS='|' read -r opt val why; do p "$opt" "$val" "$why"; done <<'EOF'
--batch|0|must be 1..1048576
--batch|4294967396|must be 1..1048576
--batch|abc|not an integer
--bits|155|must be 1..20
--bits|0|must be 1..20
--min-vertices|2|must be 3..4294967295
--rounds|nan|not a finite number
--rounds|1.5|must be 0..1
EOF

i() { expect 1 "$1 $2: $3" "$bin/lumo-inspect" "$1" "$2" --ply "$tmp/l.ply" "$tmp/pm.lumo"; }
i --lod abc "not an integer"
i --lod 12x "not an integer"
i --lod 99999999999 "must be 1..4294967295"
expect 1 "--lod 2: levels go from" "$bin/lumo-inspect" --lod 2 --ply "$tmp/l.ply" "$tmp/pm.lumo"
expect 1 "--mesh x: not an integer" "$bin/lumo-inspect" --stream --mesh x "$tmp/pm.lumo"
expect 1 "--mesh 4294967296: must be 0..4294967295" "$bin/lumo-inspect" --stream --mesh 4294967296 "$tmp/pm.lumo"

c() { expect 2 "$1 $2: $3" "$bin/lumo-compare" "$tmp/a.png" "$tmp/a.png" "$1" "$2"; }
c --max-mean-de nan "not a finite number"
c --max-mean-de inf "not a finite number"
c --max-mean-de -1 "must be 0..1000"
c --min-psnr abc "not a number"
expect 2 "--min-psnr '': not a number" "$bin/lumo-compare" "$tmp/a.png" "$tmp/a.png" --min-psnr ""

s() { expect 1 "$1 $2: $3" "$bin/lumo-server" "$tmp/pm.lumo" --listen 127.0.0.1:0 "$1" "$2"; }
s --rate nan "not a finite number"
s --rate -1 "must be 0..1e+09"
s --latency 60001 "must be 0..60000"
s --loss 2 "must be 0..1"
s --seed 4294967296 "must be 0..4294967295"
s --max-clients 0 "must be 1..1000000"
s --idle-timeout abc "not an integer"

k() { expect 2 "$1 $2: $3" "$bin/lumo-client" --connect 127.0.0.1:1 "$1" "$2"; }
k --size 4294967312x16 "width must be 1..2048"
k --frames-at 50,10 "values must increase (value 2 is 10 after 50)"
k --frames-at 10,abc "value 2: not a number"
k --frames-at 0 "percentages must be above 0"
k --pipeline 9 "must be 1..8"
k --order foo "must be one of interleaved, geometry, lighting"
k --arena 0 "must be 1..4095"
k --max-payload 1 "must be 4096..16777216"
k --vertices 4294967296 "must be 1..268435456"
k --retries -1 "must be 0..1000"

expect 2 "--bench 0: must be 1..1000000" "$bin/lumo-draco-decode" --bench 0 "$tmp/a.png"
expect 2 "--bench x: not an integer" "$bin/lumo-draco-decode" --bench x "$tmp/a.png"
expect 1 "RECORDS -5: must be 0..4294967295" "$bin/lumo-pm" apply "$tmp/pm.lumo" -5

# ---- option words: unknown, missing value, a value given to a flag --------
for t in "lumo-render 2 --default -o $tmp/x.png" "lumo-bake 1 --default -o $tmp/x.lumo" \
         "lumo-client 2 --connect 127.0.0.1:1" "lumo-server 1 $tmp/pm.lumo"; do
    set -- $t; tool=$1 st=$2; shift 2
    expect "$st" "--frobnicate: unknown option (try --help)" "$bin/$tool" "$@" --frobnicate
    expect "$st" "--help=3: unknown option, or one that takes no value" "$bin/$tool" "$@" --help=3
done
expect 2 "--size needs a value (try --help)" "$bin/lumo-render" --default -o "$tmp/x.png" --size
expect 1 "--grid needs a value (try --help)" "$bin/lumo-bake" --default -o "$tmp/x.lumo" --grid
expect 2 "--bits needs a value (try --help)" "$bin/lumo-pm" build "$M" -o "$tmp/p.lumo" --bits
expect 2 "--min-psnr needs a value (try --help)" "$bin/lumo-compare" "$tmp/a.png" "$tmp/a.png" --min-psnr
expect 2 "--retries needs a value (try --help)" "$bin/lumo-client" --connect 127.0.0.1:1 --retries

# ---- named files: used or refused, never replaced ---------------------------
while IFS='|' read -r f why; do
    f=$(eval echo "$f")
    expect 1 "--model $f: $why" "$bin/lumo-render" --default --model "$f" -o "$tmp/x.png"
    expect 1 "--dragon $f: $why" "$bin/lumo-bake" --default --dragon "$f" -o "$tmp/x.lumo" --no-progress
    LUMO_DRAGON=$f expect 1 "LUMO_DRAGON $f: $why" "$bin/lumo-render" --default -o "$tmp/x.png"
done <<'EOF'
$tmp/missing.ply|cannot read: No such file or directory
$tmp/empty.ply|empty file, not a model file
$tmp/adir|a directory, not a model file
/dev/null|not a regular file
EOF
# (the model front end's own sentences, server/scene/model_check.h)
expect 1 "default scene: $tmp/picture.png: unknown model format (extension '.png'" "$bin/lumo-render" --default --model "$tmp/picture.png" -o "$tmp/x.png"
expect 1 "$tmp/garbage.obj: no vertex ('v' line)" "$bin/lumo-bake" --default --dragon "$tmp/garbage.obj" -o "$tmp/x.lumo"
expect 2 "--model $model: only with --default" "$bin/lumo-render" "$tmp/pm.lumo" --model "$model" -o "$tmp/x.png"
expect 1 "--dragon $model: only with --default" "$bin/lumo-bake" "$model" --dragon "$model" -o "$tmp/x.lumo"
expect 1 "$tmp/adir: a directory, not a scene or model file" "$bin/lumo-bake" "$tmp/adir" -o "$tmp/x.lumo"
expect 2 "$tmp/adir: a directory, not a mesh file" "$bin/lumo-pm" build "$tmp/adir" -o "$tmp/p.lumo"
for t in lumo-render lumo-inspect lumo-server; do
    case $t in lumo-render) a="-o $tmp/x.png" ;; lumo-server) a="--listen 127.0.0.1:0" ;; *) a="" ;; esac
    expect 1 "$tmp/adir: a directory, not a package" "$bin/$t" "$tmp/adir" $a
    expect 1 "$tmp/empty.ply: empty file, not a package" "$bin/$t" "$tmp/empty.ply" $a
    expect 1 "$tmp/nope.lumo: cannot read: No such file or directory" "$bin/$t" "$tmp/nope.lumo" $a
    expect 1 "$tmp/picture.png: not a valid package" "$bin/$t" "$tmp/picture.png" $a
done
expect 1 "$tmp/adir: a directory, not a PNG picture" "$bin/lumo-compare" "$tmp/a.png" "$tmp/adir"
expect 1 "$tmp/garbage.obj: cannot read as an 8-bit PNG picture" "$bin/lumo-compare" "$tmp/a.png" "$tmp/garbage.obj"
expect 1 "$tmp/adir: a directory, not a Draco file" "$bin/lumo-draco-decode" "$tmp/adir" "$tmp/x.ply"

# ---- outputs that cannot be written: the file and errno ---------------------
no=/nonexistent/dir
expect 1 "$no/p.ply: cannot write: No such file or directory" "$bin/lumo-pm" clean "$M" -o "$no/p.ply"
expect 1 "$no/p.lumo: cannot write: No such file or directory" "$bin/lumo-pm" build "$M" -o "$no/p.lumo"
expect 1 "$no/p.bin: cannot write: No such file or directory" "$bin/lumo-pm" build "$M" --raw -o "$no/p.bin"
expect 1 "$tmp/adir: cannot write: Is a directory" "$bin/lumo-bake" --default --grid 2 --spp 1 --no-progress -o "$tmp/adir"
expect 1 "$no/x.png: cannot write PNG: No such file or directory" "$bin/lumo-render" --default -o "$no/x.png" --size 8x8
expect 1 "$no/s.png: cannot write PNG: No such file or directory" "$bin/lumo-compare" "$tmp/a.png" "$tmp/a.png" -o "$no/s.png"
expect 1 "$no/l.ply: cannot write: No such file or directory" "$bin/lumo-inspect" --lod all --ply "$no/l.ply" "$tmp/pm.lumo"
# a Draco file the decoder takes (the conformance cases hold refusals too)
drc=""
for f in $(find "$build" -name '*.drc' 2>/dev/null | head -n 40); do
    if "$bin/lumo-draco-decode" --info "$f" >/dev/null 2>&1; then drc=$f; break; fi
done
if [ -n "$drc" ]; then
    expect 1 "$no/x.ply: cannot write: No such file or directory" "$bin/lumo-draco-decode" "$drc" "$no/x.ply"
    expect 1 "$no/x.txt: cannot write: No such file or directory" "$bin/lumo-draco-decode" --dump "$drc" "$no/x.txt"
fi

# ---- a package written to a pipe (or a device: /dev/null) is written into it,
# never renamed over it (the writers' temporary-then-rename would replace the
# pipe or device itself: as root, /dev/null) -----------------------------------
into_pipe() {
    rm -f "$tmp/pipe" "$tmp/piped"
    mkfifo "$tmp/pipe"
    # (a writer that renames over the pipe never opens it: the reader's
    # timeout ends the wait)
    timeout 30 cat "$tmp/pipe" >"$tmp/piped" &
    reader=$!
    "$@" -o "$tmp/pipe" >/dev/null 2>"$tmp/err" </dev/null
    got=$?
    wait "$reader"
    if [ "$got" -eq 0 ] && [ -p "$tmp/pipe" ] && "$bin/lumo-inspect" "$tmp/piped" >/dev/null 2>&1; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
        echo "FAIL: $* -o $tmp/pipe -> status $got; still a pipe: $([ -p "$tmp/pipe" ] && echo yes || echo no)"
    fi
}
into_pipe "$bin/lumo-pm" build "$M"
into_pipe "$bin/lumo-bake" --default --grid 2 --spp 1 --no-progress

# ---- what the tools cannot draw, said plainly -------------------------------
expect 1 "$tmp/pm.lumo: no INFO chunk, so no scene to draw (camera, lights)" "$bin/lumo-render" "$tmp/pm.lumo" -o "$tmp/x.png"
# ... while lumo-inspect lists it (docs/package-format.md): status 0, the chunk
# table, and a line saying there is no scene
if "$bin/lumo-inspect" "$tmp/pm.lumo" >"$tmp/out" 2>"$tmp/err" && [ ! -s "$tmp/err" ] \
    && grep -q '^  chunk  0 PMSH' "$tmp/out" && grep -q '^scene     none: no INFO chunk' "$tmp/out"; then
    pass=$((pass + 1))
else
    fail=$((fail + 1))
    echo "FAIL: lumo-inspect $tmp/pm.lumo (a stream-only package) is not listed:"
    sed 's/^/    /' "$tmp/out" "$tmp/err" | head -5
fi
expect 1 "--camera 0,1,2:0,1,2:0,1,0:40: eye and target are the same point" \
    "$bin/lumo-render" --default -o "$tmp/x.png" --camera 0,1,2:0,1,2:0,1,0:40
expect 1 "--camera 0,1,2:0,1,2.000001:0,1,0:40: eye and target are the same point in Q16.16 fixed point" \
    "$bin/lumo-render" --default -o "$tmp/x.png" --camera 0,1,2:0,1,2.000001:0,1,0:40
expect 1 "--camera 0,1,2:0,1,3:0,1,0:179.9: FOVY must be 1..179 degrees" \
    "$bin/lumo-render" --default -o "$tmp/x.png" --camera 0,1,2:0,1,3:0,1,0:179.9
lights=""; n=0
while [ $n -lt 17 ]; do lights="$lights --light point:0,1,0:1,1,1"; n=$((n + 1)); done
expect 2 "--light point:0,1,0:1,1,1: more than 16 lights (LUMO_MAX_LIGHTS" "$bin/lumo-render" --default -o "$tmp/x.png" $lights
expect 1 "--light point:0,1,0:1,1,1: more than 16 lights; a scene holds at most 16 (LUMO_MAX_LIGHTS" "$bin/lumo-bake" --default -o "$tmp/x.lumo" $lights

# ---- round three: lights field by field, --prt, --dynamic, the benchmarks ---
# (issue 24): a light's refusal names the field and its value; every
# number of --prt and --dynamic, and of the benchmark and demo programs,
# goes through the one strict parser.
lr() { expect 2 "--light '$1': $2" "$bin/lumo-render" --default -o "$tmp/x.png" --light "$1"; }
lb() { expect 1 "--light '$1': $2" "$bin/lumo-bake" --default -o "$tmp/x.lumo" --light "$1"; }
for t in lr lb; do
    $t 'point:0,1:1,1,1' "position needs 3 numbers, got 2"
    $t 'point:0,1,0:1,1' "power needs 3 numbers, got 2"
    $t 'point:0,1,0:1,-1,1' "power value 2 = -1 is outside [0, 1e+09] W"
    $t 'point:0,x,0:1,1,1' "position value 2 'x' is not a finite number"
    $t 'point:0,1e9,0:1,1,1' "position value 2 = 1e+09 is outside [-32000, 32000] m"
    $t 'laser:0,1,0:1,1,1' "kind 'laser' is not point, spot, directional or area"
    $t 'point:0,1,0:1,1,1:4' "a point light is point:X,Y,Z:R,G,B (3 fields), got 4"
    $t 'spot:0,1,0:0,0,0:30:1,1,1' "direction 0,0,0 has no length"
    $t 'spot:0,1,0:0,-1,0:200:1,1,1' "cone half-angle = 200 is outside [0, 180] degrees"
    $t 'spot:0,1,0:0,-1,0:nan:1,1,1' "cone half-angle 'nan' is not a finite number"
    $t 'directional:0,-1,0:1,1,inf' "irradiance value 3 'inf' is not a finite number"
    $t 'area:0,1,0:1,0,0:2,0,0:1,1,1' "edges U 1,0,0 and V 2,0,0 are parallel or zero: no area"
    $t 'area:0,1,0:1,0,0:0,0' "a area light is"
done
pr() { expect 1 "$2" "$bin/lumo-bake" --default -o "$tmp/x.lumo" --prt "$1"; }
pr 4,clusters=1.5 "--prt clusters 1.5: not an integer"
pr 4,clusters=0 "--prt clusters 0: must be 1.."
pr 4,alpha=nan "--prt alpha nan: not a finite number"
pr 4,teapot=1 "--prt: unknown setting 'teapot'"
pr 4,strata "--prt: 'strata' needs a value (strata=N)"
pr 99 "--prt ORDER 99: must be 1..6"
pr x "--prt ORDER x: not an integer"
scene=tests/fuzz/package_seeds/tiny.txt
"$bin/lumo-bake" "$scene" --grid 4 --spp 4 --mesh pm --no-progress -o "$tmp/dyn.lumo" >/dev/null 2>&1 ||
    echo "could not bake dyn.lumo"
dy() { expect 1 "$2" timeout 20 "$bin/lumo-server" "$tmp/dyn.lumo" --listen 127.0.0.1:0 --dynamic "$scene,$1"; }
dy vsl=1.5 "--dynamic vsl 1.5: not an integer"
dy pool=0 "--dynamic pool 0: must be 1..1000000000000"
dy tau=2 "--dynamic tau 2: must be 0..1"
dy seed=-1 "--dynamic seed -1: must be 0..18446744073709551615"
dy photon-rate=inf "--dynamic photon-rate inf: not a finite number"
dy teapot=1 "--dynamic: unknown setting 'teapot'"
dy vsl "--dynamic: setting 'vsl' has no '='"
expect 2 "REPS 1e3: not an integer" "$bin/draco-bench" "$model" 1e3
expect 2 "REPS -1: must be 1..1000000" "$bin/draco-bench-libdraco" "$model" -1
expect 2 "FLAGS x: not an integer" "$bin/lumo-bench-ivg" pushpull 8 25 x
expect 2 "N 4294967304: must be 2..256" "$bin/lumo-bench-ivg" pushpull 4294967304 25 0
expect 2 "MODE 7: must be 0..2" "$bin/lumo-bench-ivg" sample 10 7
expect 2 "PEER_CPU_S nan: not a finite number" "$build/host/bench/lumo-bench-mpi-model" 8 1 nan 0
expect 2 "--order 9: must be 1..6" "$bin/prt-bench" --order 9 --out "$tmp/p.md" "$model"
expect 2 "--clusters 64,1.5: value 2 is not an integer" "$bin/prt-bench" --clusters 64,1.5 --out "$tmp/p.md" "$model"
expect 2 "--rounds 1.5: not an integer" "$bin/lumo-bench-stream" run 127.0.0.1:1 --rounds 1.5
expect 2 "CLIENTS -5: must be 1..100000" "$bin/lumo-bench-stream" load 127.0.0.1:1 -5 3
expect 1 "--grid 1e2: not an integer" "$bin/dyn-error" "$scene" --grid 1e2
expect 1 "--times 0,3,2: values must increase" "$bin/dyn-error" "$scene" --times 0,3,2
expect 2 "W 0: must be 1..16384" "$bin/prt-demo" env "$tmp/e.png" 0 10
# motion lines (scene files of lumo-server --dynamic and dyn-error): the key,
# its number and the part that is wrong.
mo() {  # mo NAME LINE EXPECT
    printf 'quad -1,0,-1 0,0,2 2,0,0\nlight point:0,1,0:1,1,1\nmotion %s\n' "$2" >"$tmp/$1.txt"
    expect 1 "$tmp/$1.txt:3: motion: $3" "$bin/dyn-error" "$tmp/$1.txt" --grid 4 --spp 1
}
mo m_pos "light 0 0:0,1,0 1:0,x,0" "key 2 '1:0,x,0': position '0,x,0' is not 3 finite numbers X,Y,Z"
mo m_far "light 0 0:0,1e9,0" "key 1 '0:0,1e9,0': position Y = 1e+09 is beyond"
mo m_time "light 0 0:0,1,0 -1:0,1,0" "key 2 '-1:0,1,0': time '-1' is not a number of seconds in [0, 1e9]"
mo m_order "light 0 2:0,1,0 1:0,1,0" "key 2 '1:0,1,0': time 1 does not follow 2 (times increase)"
mo m_yaw "light 0 0:0,1,0:30" "key 1 '0:0,1,0:30': a light has no yaw ('30')"
mo m_oyaw "object 0 0:0,0,0:nan" "key 1 '0:0,0,0:nan': yaw 'nan' is not a number of degrees"

# ---- --help stays clear: usage on stdout, status 0 --------------------------
for t in lumo-render lumo-bake lumo-pm lumo-inspect lumo-server lumo-client lumo-compare lumo-draco-decode; do
    if "$bin/$t" --help >"$tmp/out" 2>"$tmp/err" && grep -q "^usage: $t" "$tmp/out" && [ ! -s "$tmp/err" ]; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1)); echo "FAIL: $t --help"
    fi
done

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
