# boards/client/client.mk — the thin client as a board program
# (boards/client/client.c, docs/porting.md §7): built for mps2-an385 (QEMU)
# and for the Linux board, and tested end to end by `make board-client`.
#
#   make board-client   the default scene through lumo-server's serial
#                       listener: recorded by the host build, replayed on the
#                       host and under QEMU, streamed live under QEMU over the
#                       UART, and once more through --loss 0.01; HASH lines
#                       compared (boards/client/client-test.sh)
#
# The program links a board's port and the client libraries, never test
# code; its objects come from the boards' rules (boards/armv7m/armv7m.mk,
# boards/host/board.mk). Files of other fragments are named literally:
# fragments are included in any order.
CLIENT_ELF  := $(BUILD)/board/mps2-an385/client.elf
CLIENT_HOST := $(BUILD)/board/host/client
# The thin client program's own sources: every board build of it (here, the
# lm3s6965evb, the RP2040, the Linux gadget) links these with its port.
BOARD_CLIENT_SRCS := boards/client/client.c boards/client/grey4.c
CLIENT_M3_OBJS := $(patsubst %.c,$(BUILD)/board/obj-m3/%.o,$(BOARD_CLIENT_SRCS) boards/armv7m/startup.c boards/common/stack_paint.c \
    boards/armv7m/fault.c boards/armv7m/semihost.c boards/mps2-an385/board.c boards/common/console.c boards/common/no_screen.c)
CLIENT_HOST_OBJS := $(patsubst %.c,$(BUILD)/board/obj-host/%.o,$(BOARD_CLIENT_SRCS) \
    boards/host/board.c boards/host/link_tcp.c boards/common/console.c boards/common/no_screen.c)
CLIENT_M3_LIBS := $(BUILD)/m3/liblumo_net.a $(BUILD)/m3/liblumo_raster.a $(BUILD)/m3/liblumo.a

# make check-embedded proves the client rules on the image's own objects too
# (boards/armv7m/armv7m.mk), beside the libraries'.
BOARD_CHECK_OBJS += $(CLIENT_M3_OBJS)
check-embedded: $(CLIENT_M3_OBJS)

$(CLIENT_ELF): $(CLIENT_M3_OBJS) $(CLIENT_M3_LIBS) boards/mps2-an385/mps2-an385.ld
	@mkdir -p $(@D)
	$(ARM_CC) $(M3_ARCH) -nostartfiles -specs=nano.specs -T boards/mps2-an385/mps2-an385.ld -Wl,--gc-sections \
	    -Wl,--no-warn-rwx-segments -Wl,-Map=$@.map -o $@ $(CLIENT_M3_OBJS) $(CLIENT_M3_LIBS)
	@if $(ARM_NM) $@ | awk '{print $$NF}' | grep -Ex '$(BOARD_BANNED_SYMS)'; then \
	    echo "$@: links a heap or soft-float symbol (above); board programs must not"; rm -f $@; exit 1; fi

$(CLIENT_HOST): $(CLIENT_HOST_OBJS) $(BUILD)/san/liblumo_net.a $(BUILD)/san/liblumo_raster.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^

# The scene: lumo-bake's default (the Cornell box with the 48k dragon when
# the models are set up, a 16^3 grid): about 280 KB to stream, 13 s live
# through QEMU's UART (about 30 KB/s).
CLIENT_DIR   := $(BUILD)/board/client
CLIENT_SCENE := $(CLIENT_DIR)/default.lumo
$(CLIENT_SCENE): $(BIN)/lumo-bake
	@mkdir -p $(@D)
	$(BIN)/lumo-bake --default --no-progress -o $@ >$(CLIENT_DIR)/bake.log 2>&1 || { cat $(CLIENT_DIR)/bake.log; exit 1; }

.PHONY: board-client
board-client: $(CLIENT_ELF) $(CLIENT_HOST) $(CLIENT_SCENE) $(BIN)/lumo-server
	@sh boards/client/client-test.sh $(CLIENT_DIR) $(CLIENT_SCENE) $(BIN)/lumo-server $(CLIENT_HOST) \
	    $(CLIENT_ELF) "$(MPS2_QEMU_CMD) -icount shift=0"
TEST_STEPS += board-client

# The client's instruction counts on the Cortex-M3 and the session's time on
# a 100 MHz M3 at 115200 baud and 1 Mbit/s: a section of docs/benchmarks.md.
CLIENT_BENCH_MD := $(BUILD)/bench/sections/26-board-client.md
.PHONY: bench-client
bench-client: $(CLIENT_ELF) $(CLIENT_HOST) $(CLIENT_SCENE) $(BIN)/lumo-server
	@mkdir -p $(dir $(CLIENT_BENCH_MD))
	@sh boards/client/client-bench.sh $(CLIENT_DIR) $(CLIENT_SCENE) $(BIN)/lumo-server $(CLIENT_HOST) \
	    $(CLIENT_ELF) "$(MPS2_QEMU_CMD) -icount shift=0" $(CLIENT_BENCH_MD)
BENCH_STEPS += bench-client

# The updates phase (--updates N, docs/dynamic.md §6): lumo-server --dynamic
# on the demo's moving Cornell box; live, replayed on the host and under
# QEMU, live under QEMU over the UART, and a damaged recording refused
# (boards/client/client-updates-test.sh).
.PHONY: board-client-updates
board-client-updates: $(CLIENT_ELF) $(CLIENT_HOST) $(BIN)/lumo-server $(BIN)/lumo-bake
	@sh boards/client/client-updates-test.sh $(BUILD)/board/client-updates $(BIN)/lumo-server $(BIN)/lumo-bake \
	    $(CLIENT_HOST) $(CLIENT_ELF) "$(MPS2_QEMU_CMD) -icount shift=0"
TEST_STEPS += board-client-updates
