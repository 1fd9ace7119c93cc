# boards/lm3s6965evb/board.mk — the 64 KiB low-end budget (docs/porting.md).
#
#   make board-lm3s   links tests/board/lm3s_ivg.c with this board's port and
#                     the SDK for the LM3S6965 (256 KiB flash, 64 KiB SRAM),
#                     reports its size in build/board/lm3s6965evb/size.txt,
#                     runs it under QEMU's lm3s6965evb and checks its hash
#                     against the Linux board's build (boards/host/board.mk).
#
# The port: this board's board.c (no timer, scratch in SRAM) and linker
# script, the ARMv7-M family code of boards/armv7m/ (startup, faults,
# semihosting; objects by its Cortex-M3 rule) and the console. The program
# only needs the IVG: it links liblumo.a alone.
LM3S_DIR  := boards/lm3s6965evb
LM3S_OUT  := $(BUILD)/board/lm3s6965evb
LM3S_OBJS := $(patsubst %.c,$(BUILD)/board/obj-m3/%.o, \
    tests/board/lm3s_ivg.c $(LM3S_DIR)/board.c boards/armv7m/startup.c boards/common/stack_paint.c boards/armv7m/fault.c boards/armv7m/semihost.c \
    boards/common/console.c tests/board/harness.c tests/board/golden.c tests/board/ivg_wire.c)
LM3S_HOST := $(BUILD)/board/host/lm3s_ivg
LM3S_QEMU := timeout 60 qemu-system-arm -machine lm3s6965evb -cpu cortex-m3 -nographic \
             -monitor none -serial none -semihosting-config enable=on,target=native -kernel

$(LM3S_OUT)/lm3s_ivg.elf: $(LM3S_OBJS) $(BUILD)/m3/liblumo.a $(LM3S_DIR)/lm3s6965evb.ld
	@mkdir -p $(@D)
	$(ARM_CC) $(M3_ARCH) -nostartfiles -specs=nano.specs -T $(LM3S_DIR)/lm3s6965evb.ld \
	    -Wl,--gc-sections -Wl,--no-warn-rwx-segments -Wl,--print-memory-usage \
	    -Wl,-Map=$@.map -o $@ $(LM3S_OBJS) $(BUILD)/m3/liblumo.a >$(LM3S_OUT)/memory-usage.txt

.PHONY: board-lm3s
board-lm3s: $(LM3S_OUT)/lm3s_ivg.elf $(LM3S_HOST)
	@{ echo "lm3s6965evb: $(LM3S_OUT)/lm3s_ivg.elf (IVG 6x6x6 + push-pull + sampling)"; \
	   cat $(LM3S_OUT)/memory-usage.txt; $(ARM_SIZE) $(LM3S_OUT)/lm3s_ivg.elf; } >$(LM3S_OUT)/size.txt
	@cat $(LM3S_OUT)/size.txt
	@$(LM3S_QEMU) $(LM3S_OUT)/lm3s_ivg.elf </dev/null >$(LM3S_OUT)/board.log 2>&1; echo "board exit $$?" >>$(LM3S_OUT)/board.log
	@$(LM3S_HOST) >$(LM3S_OUT)/host.log 2>&1; echo "host exit $$?" >>$(LM3S_OUT)/host.log
	@cat $(LM3S_OUT)/board.log
	@grep '^HASH' $(LM3S_OUT)/host.log >$(LM3S_OUT)/host.hash; grep '^HASH' $(LM3S_OUT)/board.log >$(LM3S_OUT)/board.hash
	@if grep -q 'board exit 0' $(LM3S_OUT)/board.log && [ -s $(LM3S_OUT)/host.hash ] \
	    && cmp -s $(LM3S_OUT)/host.hash $(LM3S_OUT)/board.hash; then \
	    echo "RESULT: 1 passed, 0 failed"; \
	else echo "lm3s6965evb hash differs from host (or the run failed):"; \
	    diff $(LM3S_OUT)/host.hash $(LM3S_OUT)/board.hash; echo "RESULT: 0 passed, 1 failed"; exit 1; fi

ARM_SIZE ?= arm-none-eabi-size
TEST_STEPS += board-lm3s
