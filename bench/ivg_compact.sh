#!/bin/sh
# bench/ivg_compact.sh BUILD PEER_COMMIT ROUND1_COMMIT BENCH MEMORY — the
# packed grid against two peers, each the SDK of a commit built here from
# `git archive` with the same compiler and flags: PEER_COMMIT (entries
# unpacked: 20 bytes a hemisphere) and ROUND1_COMMIT (packed, the whole
# pyramid kept, RGB9E5 opened channel by channel). Arena bytes per grid
# vertex, and callgrind instruction counts of lumo_ivg_pushpull and
# lumo_ivg_irradiance (deterministic), all three in this run. Writes
# BUILD/bench/sections/21-ivg-compact.md. Run by `make bench-ivg-compact`.
set -eu
build=$1; peer=$2; round1=$3; bench=$4; memory=$5
dir="$build/bench/ivg-compact"; out="$build/bench/sections/21-ivg-compact.md"
mkdir -p "$dir" "$(dirname "$out")"
cc="${CC:-cc}"

# build_peer NAME COMMIT: $dir/NAME-bench and $dir/NAME-memory from COMMIT.
build_peer() {
    name=$1; src="$dir/$1-src"
    rm -rf "$src"; mkdir -p "$src"
    git archive "$2" sdk bench/ivg_bench.c server/package/ivg_encode.c server/package/ivg_encode.h | tar -x -C "$src"
    cp bench/ivg_memory.c "$src/"
    flags="-std=c99 -O2 -I$src/sdk/include -I$src/sdk/shared -I$src/server"
    objs=""
    for f in "$src"/sdk/src/*.c; do
        o="$dir/$name-$(basename "$f" .c).o"; $cc $flags -c "$f" -o "$o"; objs="$objs $o"
    done
    $cc -std=c11 -D_GNU_SOURCE -O2 -I$src/sdk/include -I$src/server -o "$dir/$name-bench" \
        "$src/bench/ivg_bench.c" "$src/server/package/ivg_encode.c" $objs -lm
    $cc $flags -o "$dir/$name-memory" "$src/ivg_memory.c" $objs
}
build_peer peer "$peer"
build_peer round1 "$round1"

instr() {  # instr BENCH FUNCTION ARGS... -> instructions executed in FUNCTION
    b=$1; fn=$2; shift 2
    valgrind --tool=callgrind --callgrind-out-file="$dir/cg.out" --toggle-collect="$fn" "$b" "$@" >/dev/null 2>&1
    sed -n 's/^totals: *\([0-9]*\).*/\1/p' "$dir/cg.out"
}
three() {  # three FUNCTION ARGS... -> "unpacked round1 now"
    echo "$(instr "$dir/peer-bench" "$@") $(instr "$dir/round1-bench" "$@") $(instr "$bench" "$@")"
}
"$memory" > "$dir/memory.txt"
"$dir/peer-memory" > "$dir/peer-memory.txt"
"$dir/round1-memory" > "$dir/round1-memory.txt"
: > "$dir/pushpull.txt"
for n in 16 32; do
    for f in 0 1; do
        echo "$n $f $(three lumo_ivg_pushpull pushpull $n 25 $f)" >> "$dir/pushpull.txt"
    done
done
samples=20000
: > "$dir/sample.txt"
for m in 0 2; do
    echo "$m $(three lumo_ivg_irradiance sample $samples $m)" >> "$dir/sample.txt"
done
{
    echo "## IVG memory: the packed grid against the unpacked one (seed 000 §3.3, §4.1)"
    echo
    echo "Command: \`make bench-ivg-compact\` (bench/ivg_compact.sh): two peers built by the script"
    echo "from \`git archive\` with \`$cc -O2\` beside the current SDK (\`make\` builds it -O2 too):"
    echo "**unpacked**, the SDK of commit \`$(git rev-parse --short "$peer")\` (every entry 20 bytes a hemisphere),"
    echo "and **packed, round one**, commit \`$(git rev-parse --short "$round1")\` (entries packed, the whole"
    echo "pyramid kept, RGB9E5 opened channel by channel); **now** keeps level 1 as two rings of three"
    echo "planes made again on the way down and opens RGB9E5 with one table step (docs/ivg-format.md §6)."
    echo "Memory from \`lumo_ivg_memory_size\` (bench/ivg_memory.c linked against each), instructions from"
    echo "\`valgrind --tool=callgrind --toggle-collect=FUNCTION lumo-bench-ivg ...\` on x86-64, all in this run."
    echo
    echo "Arena bytes of the whole grid (entries, received/solid/duplicate bitmaps, the push-pull"
    echo "pyramid and its smoothing sums) per grid vertex:"
    echo
    echo "| grid | unpacked bytes | round one bytes | now bytes | unpacked B/vertex | round one B/vertex | now B/vertex | unpacked / now |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|"
    paste "$dir/peer-memory.txt" "$dir/round1-memory.txt" "$dir/memory.txt" |
        awk '{ printf "| %d^3 | %d | %d | %d | %.1f | %.1f | %.1f | %.2f x |\n", $1, $2, $5, $8, $3, $6, $9, $2 / $8 }'
    echo
    echo "Push-pull (\`pushpull N 25 FLAGS\`: N^3 grid, 25 % received) and shading"
    echo "(\`sample $samples MODE\`: 32^3, 25 % received, push-pulled), instructions:"
    echo
    echo "| work | unpacked | round one | now | now / round one | now / unpacked |"
    echo "|---|---:|---:|---:|---:|---:|"
    awk '{ printf "| push-pull %d^3 %s | %.1f M | %.1f M | %.1f M | %.2f | %.2f |\n", $1, $2 ? "smooth" : "plain",
        $3 / 1e6, $4 / 1e6, $5 / 1e6, $5 / $4, $5 / $3 }' "$dir/pushpull.txt"
    awk -v n="$samples" '{ printf "| irradiance, %s | %.0f / point | %.0f / point | %.0f / point | %.2f | %.2f |\n",
        $1 == 0 ? "random points and normals" : "axis-aligned normals", $2 / n, $3 / n, $4 / n, $4 / $3, $4 / $2 }' \
        "$dir/sample.txt"
} > "$out"
echo "bench-ivg-compact: wrote $out"
