#!/bin/sh
# bench/ivg_compact.sh BUILD PEER_COMMIT BENCH MEMORY — the packed grid
# against its peer, the SDK of PEER_COMMIT (entries unpacked: 20 bytes a
# hemisphere), built here from `git archive` with the same compiler and
# flags: arena bytes per grid vertex, and callgrind instruction counts of
# lumo_ivg_pushpull and lumo_ivg_irradiance (deterministic), both sides in
# this run. Writes BUILD/bench/sections/21-ivg-compact.md. Run by
# `make bench-ivg-compact`.
set -eu
build=$1; peer=$2; bench=$3; memory=$4
dir="$build/bench/ivg-compact"; out="$build/bench/sections/21-ivg-compact.md"
src="$dir/peer-src"
rm -rf "$src"; mkdir -p "$src" "$(dirname "$out")"
git archive "$peer" sdk bench/ivg_bench.c server/package/ivg_encode.c server/package/ivg_encode.h | tar -x -C "$src"
cp bench/ivg_memory.c "$src/"
cc="${CC:-cc}"
flags="-std=c99 -O2 -I$src/sdk/include -I$src/sdk/shared -I$src/server"
objs=""
for f in "$src"/sdk/src/*.c; do
    o="$dir/peer-$(basename "$f" .c).o"; $cc $flags -c "$f" -o "$o"; objs="$objs $o"
done
$cc -std=c11 -D_GNU_SOURCE -O2 -I$src/sdk/include -I$src/server -o "$dir/peer-bench" \
    "$src/bench/ivg_bench.c" "$src/server/package/ivg_encode.c" $objs -lm
$cc $flags -o "$dir/peer-memory" "$src/ivg_memory.c" $objs

instr() {  # instr BENCH FUNCTION ARGS... -> instructions executed in FUNCTION
    b=$1; fn=$2; shift 2
    valgrind --tool=callgrind --callgrind-out-file="$dir/cg.out" --toggle-collect="$fn" "$b" "$@" >/dev/null 2>&1
    sed -n 's/^totals: *\([0-9]*\).*/\1/p' "$dir/cg.out"
}
"$memory" > "$dir/memory.txt"
"$dir/peer-memory" > "$dir/peer-memory.txt"
: > "$dir/pushpull.txt"
for n in 16 32; do
    for f in 0 1; do
        echo "$n $f $(instr "$dir/peer-bench" lumo_ivg_pushpull pushpull $n 25 $f) $(instr "$bench" lumo_ivg_pushpull pushpull $n 25 $f)" >> "$dir/pushpull.txt"
    done
done
samples=20000
: > "$dir/sample.txt"
for m in 0 2; do
    echo "$m $(instr "$dir/peer-bench" lumo_ivg_irradiance sample $samples $m) $(instr "$bench" lumo_ivg_irradiance sample $samples $m)" >> "$dir/sample.txt"
done
{
    echo "## IVG memory: the packed grid against the unpacked one (seed 000 §3.3, §4.1)"
    echo
    echo "Command: \`make bench-ivg-compact\` (bench/ivg_compact.sh): the peer is the SDK of commit"
    echo "\`$(git rev-parse --short "$peer")\` (every entry unpacked, 20 bytes a hemisphere), built by the script from"
    echo "\`git archive\` with \`$cc -O2\` beside the current one (\`make\` builds it -O2 too); memory from"
    echo "\`lumo_ivg_memory_size\` (bench/ivg_memory.c linked against each), instructions from"
    echo "\`valgrind --tool=callgrind --toggle-collect=FUNCTION lumo-bench-ivg ...\` on x86-64, both in this run."
    echo
    echo "Arena bytes of the whole grid (entries, received/solid/duplicate bitmaps, the push-pull"
    echo "pyramid and its smoothing sums) per grid vertex:"
    echo
    echo "| grid | unpacked bytes | packed bytes | unpacked B/vertex | packed B/vertex | ratio |"
    echo "|---|---:|---:|---:|---:|---:|"
    paste "$dir/peer-memory.txt" "$dir/memory.txt" |
        awk '{ printf "| %d^3 | %d | %d | %.1f | %.1f | %.2f x |\n", $1, $2, $5, $3, $6, $2 / $5 }'
    echo
    echo "Push-pull (\`pushpull N 25 FLAGS\`: N^3 grid, 25 % received) and shading"
    echo "(\`sample $samples MODE\`: 32^3, 25 % received, push-pulled), instructions:"
    echo
    echo "| work | unpacked | packed | packed / unpacked |"
    echo "|---|---:|---:|---:|"
    awk '{ printf "| push-pull %d^3 %s | %.1f M | %.1f M | %.2f |\n", $1, $2 ? "smooth" : "plain", $3 / 1e6, $4 / 1e6, $4 / $3 }' "$dir/pushpull.txt"
    awk -v n="$samples" '{ printf "| irradiance, %s | %.0f / point | %.0f / point | %.2f |\n",
        $1 == 0 ? "random points and normals" : "axis-aligned normals", $2 / n, $3 / n, $3 / $2 }' "$dir/sample.txt"
} > "$out"
echo "bench-ivg-compact: wrote $out"
