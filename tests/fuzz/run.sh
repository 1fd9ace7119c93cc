#!/bin/sh
# tests/fuzz/run.sh BUILD SECONDS BIN... — run each libFuzzer target for
# SECONDS, seeded from tests/fuzz/seeds/NAME/ (checked in) and a corpus kept
# in BUILD/fuzz/corpus/NAME. Prints "RESULT: N passed, M failed".
build=$1; secs=$2; shift 2
pass=0; fail=0
for bin in "$@"; do
    name=$(basename "$bin")
    corpus="$build/fuzz/corpus/$name"
    seeds="tests/fuzz/seeds/$name"
    mkdir -p "$corpus"
    [ -d "$seeds" ] || seeds=""
    if "$bin" -max_total_time="$secs" -print_final_stats=0 -timeout=10 -rss_limit_mb=2048 \
        -artifact_prefix="$build/fuzz/" "$corpus" $seeds >"$build/fuzz/$name.log" 2>&1; then
        echo "fuzz $name: ok (${secs}s)"; pass=$((pass + 1))
    else
        echo "fuzz $name: FAILED — see $build/fuzz/$name.log"; tail -n 40 "$build/fuzz/$name.log"
        fail=$((fail + 1))
    fi
done
echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
