# boards/armv7m/draco_modes.mk — which modes of the Draco decoder the
# ARMv7-M boards' client libraries hold (LUMO_DRACO_MODES, lumo/draco.h;
# docs/porting.md "The Draco decoder's modes").
#
# build/m3/ is the one Cortex-M3 build of the client libraries that the
# family's boards link (the QEMU test board, the lm3s6965evb thin client)
# and that check-embedded proves. Its decoder holds the lean mode only:
# every walk instantiated per opposite store then exists once, which is
# what keeps the decoder within its 48 KB of code (docs/draco-decoder.md,
# "Round five"). Every decode on these boards is lean (same output; the
# golden programs hash host == board for both flags). The host builds
# (rel, san) keep both modes; `make board-tests DRACO_M3_MODES=LUMO_DRACO_MODES_ALL`
# builds the board with both (a clean build/m3 first: the objects depend
# on this file, not on the variable).
DRACO_M3_MODES ?= LUMO_DRACO_MODES_LEAN
DRACO_M3_OBJS  := $(patsubst %.c,$(BUILD)/m3/%.o,$(wildcard sdk/src/draco_*.c))
$(DRACO_M3_OBJS): CLIENT_CFLAGS_m3 += -DLUMO_DRACO_MODES=$(DRACO_M3_MODES)
$(DRACO_M3_OBJS): boards/armv7m/draco_modes.mk
