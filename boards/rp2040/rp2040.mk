# boards/rp2040/rp2040.mk — the Raspberry Pi RP2040 (Cortex-M0+, ARMv6-M: no
# FPU, no hardware divide, no CLZ, no MPU guard), built, not run
# (docs/porting.md §8).
#
#   make board-rp2040   the client libraries for the Cortex-M0+ (build/sdk/cortex-m0plus/, the SDK's cross build),
#                       the thin client (boards/client/client.c) linked with
#                       this port into build/board/rp2040/client.elf, its
#                       size (build/board/rp2040/size.txt) and the client
#                       rules proven on its objects (check-embedded.sh, nm)
#
# The port: rp2040.ld (the image in SRAM, loaded over SWD), startup.c,
# board.c (XOSC clocks, 1 MHz timer, UART0 link) and, shared with the ARMv7-M
# boards, semihosting (boards/armv7m/semihost.c: the same bkpt 0xab) and the
# console. The fixed-point code compiles for ARMv6-M as it is: 32-bit and
# 64-bit divisions become libgcc calls (__aeabi_uidiv, __aeabi_uldivmod),
# never float.
M0_ARCH          := -mcpu=cortex-m0plus -mthumb -mfloat-abi=soft
CLIENT_CFLAGS_m0 := $(CLIENT_STD) $(WARN) $(CLIENT_INC) $(M0_ARCH) -Os -g -ffunction-sections -fdata-sections
RP2040_OUT := $(BUILD)/board/rp2040

# The client libraries are the SDK's own Cortex-M0+ build (sdk/cross.mk,
# `make sdk CROSS=arm-none-eabi- CPU=cortex-m0plus`, also proven by the
# sdk-cross step), made by a sub-make: one recipe for a firmware's libraries.
# Its Draco decoder holds the lean mode only (LUMO_DRACO_MODES, as the
# ARMv7-M boards': boards/armv7m/draco_modes.mk), in a directory of its own
# (the objects do not depend on SDK_DEFS): the image runs from SRAM, where
# the default mode's instances of the decoder's walks cost about 10 KiB.
RP2040_SDK_TARGET := cortex-m0plus-lean
RP2040_SDK := $(BUILD)/sdk/$(RP2040_SDK_TARGET)
.PHONY: rp2040-sdk
rp2040-sdk:
	+@$(MAKE) --no-print-directory -s sdk CROSS=arm-none-eabi- CPU=cortex-m0plus \
	    SDK_TARGET=$(RP2040_SDK_TARGET) SDK_DEFS=-DLUMO_DRACO_MODES=LUMO_DRACO_MODES_LEAN >/dev/null

# The client sized for 264 KiB (boards/client/client.c's knobs): frames of
# at most 4 KiB, 24 KiB of picture memory (one 16-row band at 320 pixels
# is 15 KiB), no recording; board.c's scratch holds these and the scene.
RP2040_CLIENT_FLAGS := -DCLIENT_MAX_PAYLOAD=4096u -DCLIENT_PICTURE_BYTES=24576u -DCLIENT_RECORD_BYTES=0u \
                       -DRP2040_SCRATCH_BYTES=109568u
# (this file a prerequisite: the flags above are part of every object)
$(BUILD)/board/obj-m0/%.o: %.c boards/rp2040/rp2040.mk
	@mkdir -p $(@D)
	$(ARM_CC) $(CLIENT_CFLAGS_m0) -Iboards -Iboards/common $(RP2040_CLIENT_FLAGS) -MMD -MP -c $< -o $@
.PRECIOUS: $(BUILD)/board/obj-m0/%.o
RP2040_OBJS := $(patsubst %.c,$(BUILD)/board/obj-m0/%.o,$(BOARD_CLIENT_SRCS) boards/rp2040/startup.c boards/common/stack_paint.c \
    boards/rp2040/board.c boards/armv7m/semihost.c boards/common/console.c boards/common/no_screen.c)
RP2040_LIBS := $(RP2040_SDK)/liblumo_net.a $(RP2040_SDK)/liblumo_raster.a $(RP2040_SDK)/liblumo.a
# Only the top make asks the sub-make; inside it (CROSS set) the libraries
# are sdk/cross.mk's own targets, or it would call itself for ever.
ifeq ($(CROSS),)
$(RP2040_LIBS): rp2040-sdk
endif

$(RP2040_OUT)/client.elf: $(RP2040_OBJS) $(RP2040_LIBS) boards/rp2040/rp2040.ld
	@mkdir -p $(@D)
	$(ARM_CC) $(M0_ARCH) -nostartfiles -specs=nano.specs -T boards/rp2040/rp2040.ld -Wl,--gc-sections \
	    -Wl,--no-warn-rwx-segments -Wl,--print-memory-usage -Wl,-Map=$@.map -o $@ $(RP2040_OBJS) $(RP2040_LIBS) \
	    >$(RP2040_OUT)/memory-usage.txt
	@if $(ARM_NM) $@ | awk '{print $$NF}' | grep -Ex '$(BOARD_BANNED_SYMS)'; then \
	    echo "$@: links a heap or soft-float symbol (above); board programs must not"; rm -f $@; exit 1; fi

.PHONY: board-rp2040
board-rp2040: $(RP2040_OUT)/client.elf
	@{ echo "rp2040: $(RP2040_OUT)/client.elf (the thin client, Cortex-M0+, image in SRAM)"; \
	   cat $(RP2040_OUT)/memory-usage.txt; $(ARM_SIZE) -A $< | awk '$$2 > 0 && $$1 !~ /^\.(debug|comment|ARM\.attr)/'; } >$(RP2040_OUT)/size.txt
	@cat $(RP2040_OUT)/size.txt
	@sh boards/armv7m/check-embedded.sh $(ARM_NM) "$(patsubst %.c,$(RP2040_SDK)/%.o,$(CLIENT_SRCS)) $(RP2040_OBJS)" \
	    "$(CLIENT_SRCS) $(RP2040_OBJS:$(BUILD)/board/obj-m0/%.o=%.c)"
TEST_STEPS += board-rp2040
