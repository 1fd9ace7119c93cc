#!/bin/sh
# boards/mps2-an385/verify-facts.sh DIR — check what the board relies on in
# QEMU's mps2-an385 (docs/porting.md "Verified facts"), with the programs of
# tests/board/facts/ built into DIR/fact_*.elf. $QEMU_CMD is qemu-system-arm
# with machine, cpu and semihosting options but without -icount or -kernel.
# Prints one line per fact and "RESULT: N passed, M failed".
dir=$1
pass=0; fail=0
verdict() {  # verdict OK-STATUS TEXT
    if [ "$1" -eq 0 ]; then echo "ok   $2"; pass=$((pass + 1)); else echo "FAIL $2"; fail=$((fail + 1)); fi
}
run() {  # run SECONDS ELF OUTPREFIX [extra qemu args] -> status; stdout/stderr kept apart
    secs=$1; elf=$2; o=$3; shift 3
    timeout "$secs" $QEMU_CMD "$@" -kernel "$elf" </dev/null >"$o.out" 2>"$o.err"
}

# 1. SYS_EXIT_EXTENDED: QEMU's exit status is main's return value (42), and
#    semihosting console text arrives on QEMU's stderr, none on stdout.
run 20 "$dir/fact_exit.elf" "$dir/exit"; rc=$?
[ "$rc" -eq 42 ] && [ ! -s "$dir/exit.out" ] && grep -q 'fact_exit: console text' "$dir/exit.err"
verdict $? "SYS_EXIT_EXTENDED gives QEMU exit status 42 (got $rc); console on stderr, stdout empty"

# 1b. The same with the plain invocation of the issue (-nographic only: the
#     monitor is multiplexed on stdio, still nothing on stdout from us).
timeout 20 qemu-system-arm -machine mps2-an385 -cpu cortex-m3 -nographic \
    -semihosting-config enable=on,target=native -kernel "$dir/fact_exit.elf" \
    </dev/null >"$dir/exit2.out" 2>"$dir/exit2.err"; rc=$?
[ "$rc" -eq 42 ] && grep -q 'fact_exit: console text' "$dir/exit2.err"
verdict $? "plain '-nographic -semihosting-config enable=on,target=native' invocation: status 42 (got $rc), text on stderr"

# 2. A fault ends the run with 128 + exception number and a FAULT line.
run 20 "$dir/fact_fault.elf" "$dir/fault"; rc=$?
[ "$rc" -eq 131 ] && grep -q '^FAULT: HardFault pc=0x' "$dir/fault.err" && ! grep -q 'still running' "$dir/fault.err"
verdict $? "undefined instruction -> '$(head -c 60 "$dir/fault.err" | grep FAULT | head -n 1)...' exit 131 (got $rc)"

# 2b. Stack overflow hits the MPU guard below the stack: MemManage, 132.
run 20 "$dir/fact_overflow.elf" "$dir/overflow" -icount shift=0; rc=$?
[ "$rc" -eq 132 ] && grep -q '^FAULT: stack overflow' "$dir/overflow.err" && ! grep -q 'overwritten' "$dir/overflow.err"
verdict $? "stack overflow -> '$(grep FAULT "$dir/overflow.err" | head -n 1)' exit 132 (got $rc)"

# 3. A guest that never ends is stopped by timeout (status 124).
run 3 "$dir/fact_hang.elf" "$dir/hang" -icount shift=0; rc=$?
[ "$rc" -eq 124 ]
verdict $? "hung guest stopped by timeout after 3 s with status 124 (got $rc)"

# 4. -icount shift=0: the board timer counts guest instructions, so the same
#    program gives the same tick count on every run.
run 20 "$dir/fact_ticks.elf" "$dir/ticks1" -icount shift=0; r1=$?
run 20 "$dir/fact_ticks.elf" "$dir/ticks2" -icount shift=0; r2=$?
run 20 "$dir/fact_ticks.elf" "$dir/ticks3"; r3=$?
t1=$(grep '^TICKS' "$dir/ticks1.err"); t2=$(grep '^TICKS' "$dir/ticks2.err"); t3=$(grep '^TICKS' "$dir/ticks3.err")
[ "$r1" -eq 0 ] && [ "$r2" -eq 0 ] && [ -n "$t1" ] && [ "$t1" = "$t2" ] && [ "$(echo "$t1" | awk '{print $2}')" -gt 0 ]
verdict $? "-icount shift=0 deterministic: '$t1' twice (without -icount: '$t3')"

# 5. Semihosting file I/O reaches the host file system (target=native).
run 20 "$dir/fact_file.elf" "$dir/file" -icount shift=0; rc=$?
[ "$rc" -eq 0 ] && [ "$(wc -c <"$dir/fact_file.bin")" -eq 3000 ]
verdict $? "SYS_OPEN/WRITE/FLEN/READ/CLOSE: 3000-byte host file written and read back (exit $rc)"

echo "RESULT: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
