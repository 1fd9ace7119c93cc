# boards/lm3s6965evb/client.mk — the thin client (boards/client/client.c) on
# the 64 KiB lm3s6965evb, drawing on its OLED (docs/porting.md §8).
#
#   make board-lm3s-client   lumo-server serves the small scene
#                            (boards/lm3s6965evb/scene.sh) on loopback; the
#                            host build streams it (128x64 pictures, their
#                            grey reductions written as PGM); QEMU's
#                            lm3s6965evb streams it live over UART0, shows
#                            each picture on the SSD0323 and holds the last;
#                            the test takes a QMP screendump of the OLED and
#                            compares it with the host's grey picture, and
#                            the HASH lines with the host's
#                            (boards/lm3s6965evb/client-test.sh)
#
# Built apart from the other M3 programs: the client libraries with the
# limits of this scene (LUMO_MAX_MESHES 1, LUMO_MAX_LIGHTS 1: the session
# and driver shrink from 21.8 KB to about 1.2 KB; a package with more is
# refused in WELCOME, never cut) into build/m3s/, the client and the port
# into build/board/obj-m3s/ with the client's knobs: 4 KiB frames (the
# protocol's least), 8-row bands of 128 pixels, 128x64 pictures only, the
# grey screen, no recording, and the scratch array that fills SRAM up to
# the stack (5 KiB: 1 KiB MPU guard and 4 KiB for a measured peak of about
# 3 KiB).
M3S_LIMITS := -DLUMO_MAX_MESHES=1 -DLUMO_MAX_LIGHTS=1
CLIENT_CFLAGS_m3s := $(CLIENT_CFLAGS_m3) $(M3S_LIMITS)
LM3S_CLIENT_KNOBS := -DCLIENT_MAX_PAYLOAD=4096u -DCLIENT_PICTURE_BYTES=6144u -DCLIENT_RECORD_BYTES=0u \
    -DCLIENT_BAND_ROWS=4u "-DCLIENT_SIZES={128, 64}" -DCLIENT_SCREEN_W=128u -DCLIENT_SCREEN_H=64u
# 57,656 since the updates poller joined the client's state (88 bytes of
# .bss: docs/porting.md §8).
LM3S_CLIENT_SCRATCH := 57656u
LM3S_CLIENT_OUT := $(BUILD)/board/lm3s6965evb-client

$(BUILD)/m3s/%.o: %.c
	@mkdir -p $(@D)
	$(ARM_CC) $(CLIENT_CFLAGS_m3s) -MMD -MP -c $< -o $@
.SECONDEXPANSION:
$(BUILD)/m3s/liblumo.a: $$(patsubst %.c,$(BUILD)/m3s/%.o,$$(LUMO_SRCS))
	rm -f $@ && arm-none-eabi-ar rcs $@ $^
$(BUILD)/m3s/liblumo_raster.a: $$(patsubst %.c,$(BUILD)/m3s/%.o,$$(RASTER_SRCS))
	rm -f $@ && arm-none-eabi-ar rcs $@ $^
$(BUILD)/m3s/liblumo_net.a: $$(patsubst %.c,$(BUILD)/m3s/%.o,$$(NET_SRCS))
	rm -f $@ && arm-none-eabi-ar rcs $@ $^

$(BUILD)/board/obj-m3s/%.o: %.c boards/lm3s6965evb/client.mk
	@mkdir -p $(@D)
	$(ARM_CC) $(CLIENT_CFLAGS_m3s) $(BOARD_CPPFLAGS) $(LM3S_CLIENT_KNOBS) \
	    -DLM3S_SCRATCH_BYTES=$(LM3S_CLIENT_SCRATCH) -MMD -MP -c $< -o $@
.PRECIOUS: $(BUILD)/board/obj-m3s/%.o
# The host build writes its pictures (--out): room for the PPM and PGM
# images besides the board's band (same bytes drawn, docs/porting.md §7).
$(BUILD)/board/obj-host-lm3s/%.o: %.c boards/lm3s6965evb/client.mk
	@mkdir -p $(@D)
	$(CC) $(CLIENT_CFLAGS_san) $(BOARD_CPPFLAGS) $(LM3S_CLIENT_KNOBS) -UCLIENT_PICTURE_BYTES \
	    -DCLIENT_PICTURE_BYTES=65536u -MMD -MP -c $< -o $@
.PRECIOUS: $(BUILD)/board/obj-host-lm3s/%.o

LM3S_CLIENT_OBJS := $(patsubst %.c,$(BUILD)/board/obj-m3s/%.o,$(BOARD_CLIENT_SRCS) \
    boards/armv7m/startup.c boards/common/stack_paint.c boards/armv7m/fault.c boards/armv7m/semihost.c boards/lm3s6965evb/board.c \
    boards/common/console.c)
LM3S_CLIENT_LIBS := $(BUILD)/m3s/liblumo_net.a $(BUILD)/m3s/liblumo_raster.a $(BUILD)/m3s/liblumo.a
LM3S_CLIENT_ELF  := $(LM3S_CLIENT_OUT)/client.elf
LM3S_CLIENT_HOST := $(BUILD)/board/host/client-lm3s

$(LM3S_CLIENT_ELF): $(LM3S_CLIENT_OBJS) $(LM3S_CLIENT_LIBS) boards/lm3s6965evb/lm3s6965evb.ld
	@mkdir -p $(@D)
	$(ARM_CC) $(M3_ARCH) -nostartfiles -specs=nano.specs -T boards/lm3s6965evb/lm3s6965evb.ld \
	    -Wl,--defsym=LM3S_STACK=5120 -Wl,--gc-sections -Wl,--no-warn-rwx-segments -Wl,--print-memory-usage -Wl,-Map=$@.map \
	    -o $@ $(LM3S_CLIENT_OBJS) $(LM3S_CLIENT_LIBS) >$(LM3S_CLIENT_OUT)/memory-usage.txt
	@if $(ARM_NM) $@ | awk '{print $$NF}' | grep -Ex '$(BOARD_BANNED_SYMS)'; then \
	    echo "$@: links a heap or soft-float symbol (above); board programs must not"; rm -f $@; exit 1; fi

$(LM3S_CLIENT_HOST): $(patsubst %.c,$(BUILD)/board/obj-host-lm3s/%.o,$(BOARD_CLIENT_SRCS) \
                     boards/host/board.c boards/host/link_tcp.c boards/common/console.c boards/common/no_screen.c) $(HOST_BOARD_LIBS)
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^

# The scene: a sphere of LM3S_SEGMENTS segments and a LM3S_GRID^3 grid, the
# largest that fit the scene arena (docs/porting.md §8, the budget).
LM3S_SEGMENTS := 8
LM3S_GRID     := 4
LM3S_SCENE    := $(LM3S_CLIENT_OUT)/scene.lumo
$(LM3S_SCENE): $(BIN)/lumo-bake boards/lm3s6965evb/scene.sh
	@sh boards/lm3s6965evb/scene.sh $(LM3S_CLIENT_OUT)/scene $(LM3S_SEGMENTS)
	$(BIN)/lumo-bake $(LM3S_CLIENT_OUT)/scene/scene.txt --grid $(LM3S_GRID) --no-progress -o $@ \
	    >$(LM3S_CLIENT_OUT)/bake.log 2>&1 || { cat $(LM3S_CLIENT_OUT)/bake.log; exit 1; }

LM3S_CLIENT_QEMU := qemu-system-arm -machine lm3s6965evb -cpu cortex-m3 -display none -monitor none \
    -semihosting-config enable=on,target=native -icount shift=0

.PHONY: board-lm3s-client
# Desktop helpers of the test (tests/board/): the OLED compared with the
# host's grey picture, and QMP's screendump.
LM3S_OLED_COMPARE := $(LM3S_CLIENT_OUT)/oled-compare
$(LM3S_OLED_COMPARE): tests/board/oled_compare.c
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -o $@ $<
$(LM3S_CLIENT_OUT)/qmp-screendump: tests/board/qmp_screendump.c
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -o $@ $<

board-lm3s-client: $(LM3S_CLIENT_ELF) $(LM3S_CLIENT_HOST) $(LM3S_SCENE) $(BIN)/lumo-server $(LM3S_OLED_COMPARE) \
                   $(LM3S_CLIENT_OUT)/qmp-screendump \
                   $$(patsubst %.c,$(BUILD)/m3s/%.o,$$(CLIENT_SRCS))
	@{ echo "lm3s6965evb client: $(LM3S_CLIENT_ELF)"; cat $(LM3S_CLIENT_OUT)/memory-usage.txt; \
	   $(ARM_SIZE) -A $(LM3S_CLIENT_ELF) | awk '$$2 > 0 && $$1 !~ /^\.(debug|comment|ARM\.attr)/'; } \
	    >$(LM3S_CLIENT_OUT)/size.txt
	@cat $(LM3S_CLIENT_OUT)/size.txt
	@sh boards/armv7m/check-embedded.sh $(ARM_NM) "$(filter $(BUILD)/m3s/%.o,$^) $(LM3S_CLIENT_OBJS)" \
	    "$(CLIENT_SRCS) $(LM3S_CLIENT_OBJS:$(BUILD)/board/obj-m3s/%.o=%.c)"
	@sh boards/lm3s6965evb/client-test.sh $(LM3S_CLIENT_OUT) $(LM3S_SCENE) $(BIN)/lumo-server $(LM3S_CLIENT_HOST) \
	    $(LM3S_CLIENT_ELF) "$(LM3S_CLIENT_QEMU)" $(LM3S_OLED_COMPARE)
TEST_STEPS += board-lm3s-client
