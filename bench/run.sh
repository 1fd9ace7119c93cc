#!/bin/sh
# bench/run.sh BUILD "STEPS" — run every benchmark step (a make target) and
# assemble docs/benchmarks.md from the sections they write into
# BUILD/bench/sections/NN-name.md (each section names the command that made it).
build=$1; steps=$2
sections="$build/bench/sections"
mkdir -p "$sections"
for s in $steps; do
    echo "bench: $s" >&2
    ${MAKE:-make} --no-print-directory -s "$s" || echo "bench: $s failed" >&2
done
{
    echo "# lumo benchmarks"
    echo
    echo "Made by \`make bench\` on $(date -u +%Y-%m-%d) — $(nproc) cores, $(uname -m), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')."
    echo "Each section names the command that produced it. Numbers, not pass/fail."
    echo
    for f in $(ls "$sections"/*.md 2>/dev/null | sort); do cat "$f"; echo; done
} > docs/benchmarks.md
echo "bench: wrote docs/benchmarks.md" >&2
