# boards/mps2-an385/board.mk — the Cortex-M3 board under QEMU, and the proof
# of the client rules (docs/porting.md).
#
#   make check-embedded           nm + source rules on build/m3/liblumo.a
#   make check-embedded-selftest  feeds the check deliberately bad objects
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

# Board runtime (startup, semihosting, timer, scratch memory) and the
# board-agnostic layer every board program links (console, harness, golden
# output, IVG bundle encoder; --gc-sections drops what a program ignores).
MPS2_RT_SRCS   := $(MPS2_DIR)/startup.c $(MPS2_DIR)/semihost.c $(MPS2_DIR)/timer.c $(MPS2_DIR)/scratch.c
BOARD_LIB_SRCS := tests/board/console.c tests/board/harness.c tests/board/golden.c tests/board/ivg_wire.c
BOARD_TEST_SRCS   := $(sort $(wildcard tests/board/test_*.c))
BOARD_GOLDEN_SRCS := $(sort $(wildcard tests/board/golden_*.c))
BOARD_PROGS := $(basename $(notdir $(BOARD_TEST_SRCS) $(BOARD_GOLDEN_SRCS)))

MPS2_ELFS  := $(patsubst %,$(MPS2_OUT)/%.elf,$(BOARD_PROGS))
BHOST_BINS := $(patsubst %,$(BHOST_OUT)/%,$(BOARD_PROGS))

MPS2_LDFLAGS := $(M3_ARCH) -nostartfiles -specs=nano.specs -T $(MPS2_DIR)/mps2-an385.ld \
                -Wl,--gc-sections -Wl,--no-warn-rwx-segments
# Anything in a linked board image that means a heap (the harness must not
# need one either: newlib's printf would pull _sbrk) or float arithmetic.
BOARD_BANNED_SYMS := malloc|calloc|realloc|free|_sbrk|_sbrk_r|_malloc_r|_free_r|_calloc_r|_realloc_r|__aeabi_[fd].*

# Board program objects, Cortex-M3 (shared by every M3 board: the same
# flags as the client library) and host; board-agnostic code in both.
BOARD_M3_OBJ   := $(BUILD)/board/obj-m3
BOARD_HOST_OBJ := $(BUILD)/board/obj-host
BOARD_CPPFLAGS := -Itests/board -DLUMO_BUILD_DIR='"$(BUILD)"'
$(BOARD_M3_OBJ)/%.o: %.c
	@mkdir -p $(@D)
	$(ARM_CC) $(CLIENT_CFLAGS_m3) $(BOARD_CPPFLAGS) -MMD -MP -c $< -o $@
# Host builds run under ASan/UBSan against the sanitizer build of the SDK,
# so the board programs double as sanitizer tests of the code they drive.
$(BOARD_HOST_OBJ)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(CLIENT_CFLAGS_san) $(BOARD_CPPFLAGS) -MMD -MP -c $< -o $@

MPS2_RT_OBJS    := $(patsubst %.c,$(BOARD_M3_OBJ)/%.o,$(MPS2_RT_SRCS) $(BOARD_LIB_SRCS))
BHOST_RT_OBJS   := $(patsubst %.c,$(BOARD_HOST_OBJ)/%.o,tests/board/host_io.c $(BOARD_LIB_SRCS))

define MPS2_LINK
	$(ARM_CC) $(MPS2_LDFLAGS) -Wl,-Map=$@.map -o $@ $< $(MPS2_RT_OBJS) $(BUILD)/m3/liblumo.a
	@if $(ARM_NM) $@ | awk '{print $$NF}' | grep -Ex '$(BOARD_BANNED_SYMS)'; then \
	    echo "$@: links a heap or soft-float symbol (above); board programs must not"; rm -f $@; exit 1; fi
endef
$(MPS2_OUT)/%.elf: $(BOARD_M3_OBJ)/tests/board/%.o $(MPS2_RT_OBJS) $(BUILD)/m3/liblumo.a $(MPS2_DIR)/mps2-an385.ld
	$(MPS2_LINK)
$(MPS2_OUT)/facts/%.elf: $(BOARD_M3_OBJ)/tests/board/facts/%.o $(MPS2_RT_OBJS) $(BUILD)/m3/liblumo.a $(MPS2_DIR)/mps2-an385.ld
	@mkdir -p $(@D)
	$(MPS2_LINK)
$(BHOST_OUT)/%: $(BOARD_HOST_OBJ)/tests/board/%.o $(BHOST_RT_OBJS) $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $< $(BHOST_RT_OBJS) $(BUILD)/san/liblumo.a

.PRECIOUS: $(BOARD_M3_OBJ)/%.o $(BOARD_HOST_OBJ)/%.o
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

.PHONY: board-tests board-elfs board-facts check-embedded-selftest bench-board
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

# Client sources and headers the source rules apply to: everything the
# fragments put in CLIENT_SRCS, the headers beside them, the SDK's public
# headers, and every other header a client object was compiled with (from
# the compiler's .d files; system headers have absolute paths and are left
# to the include rule). Desktop-only headers nobody on the client includes
# (rasterizer/include/lumo/raster_gl.h) are not client code.
CHECK_EMBEDDED_SRCS = $(sort $(CLIENT_SRCS) $(wildcard $(addsuffix *.h,$(sort $(dir $(CLIENT_SRCS))))) \
    $(wildcard sdk/include/lumo/*.h))

check-embedded: $(BUILD)/m3/liblumo.a
	@deps=$$(cat $(CLIENT_OBJS_m3:.o=.d) 2>/dev/null | tr ' \\' '\n\n' | sed 's/:$$//' \
	        | grep '\.h$$' | grep -v '^/' | sort -u); \
	srcs=$$({ for f in $(CHECK_EMBEDDED_SRCS); do echo $$f; done; \
	          for f in $$deps; do [ -f $$f ] && echo $$f; done; } | sort -u); \
	sh $(MPS2_DIR)/check-embedded.sh $(ARM_NM) "$(CLIENT_OBJS_m3)" "$$srcs"

check-embedded-selftest:
	@sh tests/board/check_embedded_selftest.sh $(BUILD)/check-embedded-selftest \
	    "$(ARM_CC) $(CLIENT_CFLAGS_m3)" $(ARM_NM) $(MPS2_DIR)/check-embedded.sh

TEST_STEPS  += check-embedded check-embedded-selftest board-facts board-tests
