# boards/mps2-an385/board.mk — the Cortex-M3 board under QEMU, where the
# board programs of tests/board/ run (docs/porting.md).
#
#   make board-facts              the QEMU facts the board relies on
#   make board-tests              tests/board/test_*.c under QEMU (and on the
#                                 host), tests/board/golden_*.c hashed on
#                                 host + board, must be equal
#   make bench-board              Cortex-M3 instruction counts (make bench)
#
# Adding a board test: drop tests/board/test_NAME.c (a main() using
# tests/board/harness.h) — the wildcard below builds and runs it. A golden
# program tests/board/golden_NAME.c prints "HASH <label> 0x<16 hex>" lines;
# the step fails unless the host build prints exactly the same lines.

MPS2_DIR  := boards/mps2-an385
MPS2_OUT  := $(BUILD)/board/mps2-an385
BHOST_OUT := $(BUILD)/board/host

# The one QEMU invocation. -icount shift=0: 1 ns of virtual time per guest
# instruction, so board_ticks() counts instructions deterministically;
# `timeout` keeps a hung guest from hanging CI (exit 124).
QEMU_TIMEOUT ?= 60
MPS2_QEMU_CMD := qemu-system-arm -machine mps2-an385 -cpu cortex-m3 -nographic \
                 -monitor none -serial none -semihosting-config enable=on,target=native
MPS2_QEMU := timeout $(QEMU_TIMEOUT) $(MPS2_QEMU_CMD) -icount shift=0 -kernel

# The board port — its board.c (timer, scratch memory), the ARMv7-M family
# code (boards/armv7m/: startup, faults, semihosting) and the console — and
# the test harness every board program links (checks, golden output, IVG
# bundle encoder; --gc-sections drops what a program ignores). The host
# builds of the same programs: boards/host/board.mk.
MPS2_PORT_SRCS := boards/armv7m/startup.c boards/common/stack_paint.c boards/armv7m/fault.c boards/armv7m/semihost.c $(MPS2_DIR)/board.c \
                  boards/common/console.c boards/common/no_screen.c
MPS2_TEST_SRCS := tests/board/harness.c tests/board/golden.c tests/board/ivg_wire.c
BOARD_TEST_SRCS   := $(sort $(wildcard tests/board/test_*.c))
BOARD_GOLDEN_SRCS := $(sort $(wildcard tests/board/golden_*.c))
BOARD_PROGS := $(basename $(notdir $(BOARD_TEST_SRCS) $(BOARD_GOLDEN_SRCS)))

MPS2_ELFS  := $(patsubst %,$(MPS2_OUT)/%.elf,$(BOARD_PROGS))
BHOST_BINS := $(patsubst %,$(BHOST_OUT)/%,$(BOARD_PROGS))
MPS2_LIBS  := $(BUILD)/m3/liblumo_net.a $(BUILD)/m3/liblumo_raster.a $(BUILD)/m3/liblumo.a

MPS2_LDFLAGS := $(M3_ARCH) -nostartfiles -specs=nano.specs -T $(MPS2_DIR)/mps2-an385.ld \
                -Wl,--gc-sections -Wl,--no-warn-rwx-segments
# Anything in a linked board image that means a heap (the harness must not
# need one either: newlib's printf would pull _sbrk) or float arithmetic.
BOARD_BANNED_SYMS := malloc|calloc|realloc|free|_sbrk|_sbrk_r|_malloc_r|_free_r|_calloc_r|_realloc_r|__aeabi_[fd].*

# Objects: the Cortex-M3 rule of boards/armv7m/armv7m.mk.
MPS2_OBJS := $(patsubst %.c,$(BUILD)/board/obj-m3/%.o,$(MPS2_PORT_SRCS) $(MPS2_TEST_SRCS))

define MPS2_LINK
	$(ARM_CC) $(MPS2_LDFLAGS) -Wl,-Map=$@.map -o $@ $< $(MPS2_OBJS) $(MPS2_LIBS)
	@if $(ARM_NM) $@ | awk '{print $$NF}' | grep -Ex '$(BOARD_BANNED_SYMS)'; then \
	    echo "$@: links a heap or soft-float symbol (above); board programs must not"; rm -f $@; exit 1; fi
endef
$(MPS2_OUT)/%.elf: $(BUILD)/board/obj-m3/tests/board/%.o $(MPS2_OBJS) $(MPS2_LIBS) $(MPS2_DIR)/mps2-an385.ld
	@mkdir -p $(@D)
	$(MPS2_LINK)
$(MPS2_OUT)/facts/%.elf: $(BUILD)/board/obj-m3/tests/board/facts/%.o $(MPS2_OBJS) $(MPS2_LIBS) $(MPS2_DIR)/mps2-an385.ld
	@mkdir -p $(@D)
	$(MPS2_LINK)

# The QEMU facts the board relies on (docs/porting.md), checked every run.
MPS2_FACTS := $(patsubst tests/board/facts/%.c,$(MPS2_OUT)/facts/%.elf,$(wildcard tests/board/facts/fact_*.c))
board-facts: $(MPS2_FACTS)
	@QEMU_CMD="$(MPS2_QEMU_CMD)" sh $(MPS2_DIR)/verify-facts.sh $(MPS2_OUT)/facts

# Draco streams for golden_draco: the committed fuzz seeds plus real meshes
# encoded here from the test models (skipped when the models are absent).
BOARD_DRACO     := $(BUILD)/board/draco
BOARD_DRACO_SEEDS := $(sort $(wildcard tests/fuzz/seeds/fuzz_draco/*.drc))
BOARD_DRACO_GEN := $(BOARD_DRACO)/bunny_cl0.drc $(BOARD_DRACO)/bunny_cl7.drc \
                   $(BOARD_DRACO)/bunny_cl10.drc $(BOARD_DRACO)/dragon_48k_cl7.drc
$(BOARD_DRACO)/bunny_cl%.drc:
	@mkdir -p $(@D)
	@if [ -f $(BUILD)/data/models/bunny.obj ]; then \
	    draco_encoder -i $(BUILD)/data/models/bunny.obj -o $@ -cl $* >/dev/null; fi
$(BOARD_DRACO)/dragon_48k_cl%.drc:
	@mkdir -p $(@D)
	@if [ -f $(BUILD)/data/models/dragon_48k.ply ]; then \
	    draco_encoder -i $(BUILD)/data/models/dragon_48k.ply -o $@ -cl $* >/dev/null; fi
$(BOARD_DRACO)/list.txt: $(BOARD_DRACO_GEN) $(BOARD_DRACO_SEEDS)
	@mkdir -p $(@D)
	@for f in $(BOARD_DRACO_SEEDS) $(BOARD_DRACO_GEN); do [ -f $$f ] && echo $$f; done >$@; true

# Progressive-mesh streams for golden_pmesh: the committed fuzz seeds plus
# `lumo-pm build --raw` streams of the bunny and the 11k dragon (skipped
# when the models are absent).
BOARD_PMESH       := $(BUILD)/board/pmesh
BOARD_PMESH_SEEDS := $(sort $(wildcard tests/fuzz/seeds/fuzz_pmesh/*.lpm))
BOARD_PMESH_GEN   := $(BOARD_PMESH)/bunny.lpm $(BOARD_PMESH)/dragon_11k.lpm
$(BOARD_PMESH)/bunny.lpm: $(BIN)/lumo-pm
	@mkdir -p $(@D)
	@if [ -f $(BUILD)/data/models/bunny.obj ]; then \
	    $(BIN)/lumo-pm build $(BUILD)/data/models/bunny.obj -o $@ --raw >/dev/null; fi
$(BOARD_PMESH)/dragon_11k.lpm: $(BIN)/lumo-pm
	@mkdir -p $(@D)
	@if [ -f $(BUILD)/data/models/dragon_11k.ply ]; then \
	    $(BIN)/lumo-pm build $(BUILD)/data/models/dragon_11k.ply -o $@ --raw >/dev/null; fi
$(BOARD_PMESH)/list.txt: $(BOARD_PMESH_GEN) $(BOARD_PMESH_SEEDS)
	@mkdir -p $(@D)
	@for f in $(BOARD_PMESH_SEEDS) $(BOARD_PMESH_GEN); do [ -f $$f ] && echo $$f; done >$@; true

.PHONY: board-tests board-elfs board-facts bench-board
board-elfs: $(MPS2_ELFS) $(BHOST_BINS)
board-tests: board-elfs $(BOARD_DRACO)/list.txt $(BOARD_PMESH)/list.txt
	@QEMU="$(MPS2_QEMU)" sh $(MPS2_DIR)/run-tests.sh $(MPS2_OUT) \
	    "$(filter $(MPS2_OUT)/test_%,$(MPS2_ELFS))" "$(filter $(BHOST_OUT)/golden_%,$(BHOST_BINS))"

# Cortex-M3 instruction counts of the IVG core (tests/board/bench_ivg.c),
# a section of docs/benchmarks.md.
BOARD_BENCH_MD := $(BUILD)/bench/sections/25-board-ivg.md
bench-board: $(MPS2_OUT)/bench_ivg.elf
	@mkdir -p $(dir $(BOARD_BENCH_MD))
	@$(MPS2_QEMU) $< </dev/null >$(MPS2_OUT)/bench_ivg.log 2>&1 || { cat $(MPS2_OUT)/bench_ivg.log; exit 1; }
	@{ echo "## IVG on the Cortex-M3 (QEMU mps2-an385, instruction counts)"; echo; \
	   echo "Command: \`make bench-board\` — runs \`build/board/mps2-an385/bench_ivg.elf\` under"; \
	   echo "\`$(MPS2_QEMU)\`."; \
	   echo "Counts are guest instructions (-icount shift=0: the 25 MHz board timer ticks every"; \
	   echo "40 instructions), not cycles; arm-none-eabi-gcc -Os, Thumb-2, soft float. Quantized"; \
	   echo "bundles with a random subset of vertices; irradiance is the mean over 1000 random"; \
	   echo "points and normals on the grid without smoothing. 64^3 (41 MB of arena) does not fit"; \
	   echo "the board's 16 MiB PSRAM."; echo; \
	   grep '^|' $(MPS2_OUT)/bench_ivg.log; } >$(BOARD_BENCH_MD)
	@cat $(BOARD_BENCH_MD)
BENCH_STEPS += bench-board

TEST_STEPS += board-facts board-tests
