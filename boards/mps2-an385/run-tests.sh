#!/bin/sh
# boards/mps2-an385/run-tests.sh OUT "TEST_ELFS" "GOLDEN_HOST_BINS"
#
# Runs every board test ELF under QEMU ($QEMU, ending in -kernel) and its
# host build (OUT/../host/test_X, the same vectors checked natively), and every
# golden program twice — natively (OUT/../host/golden_X) and on the board
# (OUT/golden_X.elf) — then prints one "RESULT: N passed, M failed".
#  - a test ELF counts the passes and failures of its own RESULT line; a
#    timeout (124), a fault (128 + exception number), a non-zero exit or a
#    missing RESULT line counts as one more failure;
#  - a golden program is one test: it passes when it exits 0 on both sides,
#    prints at least one "HASH" line and the HASH lines are identical.
# Logs: OUT/logs/NAME.log (board) and NAME.host.log.
out=$1; tests=$2; goldens=$3
logs="$out/logs"
mkdir -p "$logs"
pass=0; fail=0
if ! command -v qemu-system-arm >/dev/null 2>&1; then
    echo "qemu-system-arm is not installed: run sh tools/setup.sh"
    echo "RESULT: 0 passed, 1 failed"
    exit 1
fi

run_board() {  # run_board ELF LOG -> exit status of QEMU
    $QEMU "$1" </dev/null >"$2" 2>&1
}

run_host() {  # run_host BIN LOG -> exit status
    timeout 60 "$1" </dev/null >"$2" 2>&1
}

# count_run WHERE NAME LOG RC: add one program's RESULT line (plus one failure
# when it timed out, faulted, exited non-zero or printed no RESULT).
count_run() {
    where=$1; name=$2; log=$3; rc=$4
    line=$(grep '^RESULT: ' "$log" | tail -n 1)
    p=$(echo "$line" | sed -n 's/^RESULT: \([0-9]*\) passed, \([0-9]*\) failed.*/\1/p')
    f=$(echo "$line" | sed -n 's/^RESULT: \([0-9]*\) passed, \([0-9]*\) failed.*/\2/p')
    p=${p:-0}; f=${f:-0}
    why=""
    if [ "$rc" -eq 124 ]; then why="timed out"
    elif [ "$rc" -ge 128 ]; then why="fault, exit $rc: $(grep '^FAULT' "$log" | head -n 1)"
    elif [ -z "$line" ]; then why="no RESULT line, exit $rc"
    elif [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then why="exit $rc"
    fi
    [ -n "$why" ] && f=$((f + 1))
    pass=$((pass + p)); fail=$((fail + f))
    if [ "$f" -ne 0 ]; then
        echo "FAIL $where $name: $p passed, $f failed ${why:+($why)} — $log"
        grep -E '^( *FAIL|FAILED|FAULT)' "$log" | head -n 20 | sed 's/^/    /'
    else
        echo "ok   $where $name: $p passed $(grep '^stack peak' "$log")"
    fi
}

for elf in $tests; do
    name=$(basename "$elf" .elf)
    run_board "$elf" "$logs/$name.log"
    count_run board "$name" "$logs/$name.log" $?
    host="$out/../host/$name"
    if [ -x "$host" ]; then
        run_host "$host" "$logs/$name.host.log"
        count_run host "$name" "$logs/$name.host.log" $?
    fi
done

for host in $goldens; do
    name=$(basename "$host")
    elf="$out/$name.elf"
    hlog="$logs/$name.host.log"; blog="$logs/$name.log"
    run_host "$host" "$hlog"; hrc=$?
    run_board "$elf" "$blog"; brc=$?
    grep '^HASH ' "$hlog" >"$hlog.hash"; grep '^HASH ' "$blog" >"$blog.hash"
    nh=$(wc -l <"$hlog.hash")
    if [ "$hrc" -eq 0 ] && [ "$brc" -eq 0 ] && [ "$nh" -gt 0 ] && cmp -s "$hlog.hash" "$blog.hash"; then
        pass=$((pass + 1))
        echo "ok   golden $name: $nh hashes equal on host and board"
        sed 's/^/    /' "$blog.hash"
        grep -E "^(COST|stack peak)" "$blog" | sed "s/^/    board /"
    else
        fail=$((fail + 1))
        echo "FAIL golden $name: host exit $hrc, board exit $brc, $nh host hashes"
        diff "$hlog.hash" "$blog.hash" | sed 's/^/    /'
        grep -E '^( *FAIL|FAULT)' "$blog" "$hlog" | head -n 10 | sed 's/^/    /'
    fi
done

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
