# bench/prt_board.mk — `make bench-prt-board` (issue 19): Cortex-M3
# instruction counts of the PRT client under QEMU (tests/board/bench_prt.c,
# the same mps2-an385 set-up as bench-board). Writes
# build/bench/sections/71-prt-board.md (pasted into docs/benchmarks.md). The
# board fragment is included after this one: its paths are named literally
# in prerequisites (recipes expand late).
PRT_BOARD_MD := $(BUILD)/bench/sections/71-prt-board.md

BENCH_STEPS += bench-prt-board
.PHONY: bench-prt-board
bench-prt-board: $(BUILD)/board/mps2-an385/bench_prt.elf
	@mkdir -p $(dir $(PRT_BOARD_MD))
	@$(MPS2_QEMU) $< </dev/null >$(MPS2_OUT)/bench_prt.log 2>&1 || { cat $(MPS2_OUT)/bench_prt.log; exit 1; }
	@{ echo "Command: \`make bench-prt-board\` — runs \`build/board/mps2-an385/bench_prt.elf\` under"; \
	   echo "\`$(MPS2_QEMU)\`."; echo; \
	   grep '^|' $(MPS2_OUT)/bench_prt.log; } >$(PRT_BOARD_MD)
	@cat $(PRT_BOARD_MD)
