#!/bin/sh
# tests/run.sh BUILD "UNIT_TESTS" "TEST_STEPS" — run every test, print totals.
#
# A unit test is a cmocka binary; its "[  PASSED  ] N" / "[  FAILED  ] N"
# lines are counted. A step is a make target (board tests under QEMU,
# check-embedded, end-to-end scripts); it may print its own line
# "RESULT: N passed, M failed", otherwise its exit status counts as one test.
# Logs go to BUILD/test-logs/, each test's wall time to its line (and to
# test-logs/times.txt, slowest first: where the 15-minute budget goes).
# The last line is "N passed, N failed".
build=$1; units=$2; steps=$3
logs="$build/test-logs"
mkdir -p "$logs"
passed=0; failed=0; failed_names=""
rm -f "$logs/times.unsorted"

now() { date +%s%N; }
took() {  # took START: seconds since START, one decimal
    ns=$(( $(now) - $1 ))
    echo "$((ns / 1000000000)).$((ns / 100000000 % 10))"
}

count() {  # count NAME LOGFILE STATUS SECONDS
    p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$2" | awk '{s+=$1} END {print s+0}')
    f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$2" | awk '{s+=$1} END {print s+0}')
    rp=$(sed -n 's/^RESULT: \([0-9]*\) passed, \([0-9]*\) failed.*/\1/p' "$2" | awk '{s+=$1} END {print s+0}')
    rf=$(sed -n 's/^RESULT: \([0-9]*\) passed, \([0-9]*\) failed.*/\2/p' "$2" | awk '{s+=$1} END {print s+0}')
    p=$((p + rp)); f=$((f + rf))
    if [ $((p + f)) -eq 0 ]; then
        if [ "$3" -eq 0 ]; then p=1; else f=1; fi
    elif [ "$3" -ne 0 ] && [ "$f" -eq 0 ]; then
        f=1   # crashed or exited non-zero after its passes
    fi
    passed=$((passed + p)); failed=$((failed + f))
    if [ "$f" -ne 0 ]; then
        failed_names="$failed_names $1"
        echo "FAIL $1 ($p passed, $f failed, $4 s) — log: $2"
        tail -n 30 "$2" | sed 's/^/    /'
    else
        echo "ok   $1 ($p passed, $4 s)"
    fi
    echo "$4 $1" >>"$logs/times.unsorted"
}

for t in $units; do
    name=$(basename "$t")
    log="$logs/$name.log"
    t0=$(now)
    "$t" >"$log" 2>&1
    count "$name" "$log" $? "$(took "$t0")"
done

for s in $steps; do
    log="$logs/$s.log"
    t0=$(now)
    ${MAKE:-make} --no-print-directory -s "$s" >"$log" 2>&1
    count "$s" "$log" $? "$(took "$t0")"
done

sort -rn "$logs/times.unsorted" >"$logs/times.txt" 2>/dev/null; rm -f "$logs/times.unsorted"
[ -n "$failed_names" ] && echo "failed:$failed_names"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
