# boards/armv7m/armv7m.mk — the ARMv7-M family (the Cortex-M3 boards
# mps2-an385 and lm3s6965evb) and the proof of the client rules on the
# Cortex-M3 build of the client libraries (docs/porting.md).
#
#   make check-embedded           nm + source rules on the objects of
#                                 build/m3/liblumo.a, liblumo_raster.a and
#                                 liblumo_net.a
#   make check-embedded-selftest  feeds the check deliberately bad objects
#
# A board of the family links the family code — startup.c (vector table,
# reset, stack paint and MPU guard), fault.c (fault report) and semihost.c
# (console, exit, files) — with boards/common/console.c, its own board.c
# (ticks, scratch) and its linker script. Its fragment names these files
# itself: fragments are included in any order.

# Board code and board programs, for every M3 board: the client flags.
$(BUILD)/board/obj-m3/%.o: %.c
	@mkdir -p $(@D)
	$(ARM_CC) $(CLIENT_CFLAGS_m3) $(BOARD_CPPFLAGS) $(BOARD_PROG_CPPFLAGS) -MMD -MP -c $< -o $@
.PRECIOUS: $(BUILD)/board/obj-m3/%.o

# Board images checked too (their fragments add their objects here and make
# check-embedded depend on them): the board client and the port it links.
BOARD_CHECK_OBJS ?=

# Client sources and headers the source rules apply to: everything the
# fragments put in CLIENT_SRCS, the headers beside them, the SDK's public
# headers, and every other header a client object was compiled with (from
# the compiler's .d files; system headers have absolute paths and are left
# to the include rule). Desktop-only headers nobody on the client includes
# (rasterizer/include/lumo/raster_gl.h) are not client code.
CHECK_EMBEDDED_SRCS = $(sort $(CLIENT_SRCS) $(wildcard $(addsuffix *.h,$(sort $(dir $(CLIENT_SRCS))))) \
    $(wildcard sdk/include/lumo/*.h))

.PHONY: check-embedded check-embedded-selftest
check-embedded: $(BUILD)/m3/liblumo.a $(BUILD)/m3/liblumo_raster.a $(BUILD)/m3/liblumo_net.a
	@deps=$$(cat $(CLIENT_OBJS_m3:.o=.d) $(BOARD_CHECK_OBJS:.o=.d) 2>/dev/null | tr ' \\' '\n\n' | sed 's/:$$//' \
	        | grep '\.h$$' | grep -v '^/' | sort -u); \
	srcs=$$({ for f in $(CHECK_EMBEDDED_SRCS) $(BOARD_CHECK_OBJS:$(BUILD)/board/obj-m3/%.o=%.c); do echo $$f; done; \
	          for f in $$deps; do [ -f $$f ] && echo $$f; done; } | sort -u); \
	sh boards/armv7m/check-embedded.sh $(ARM_NM) "$(CLIENT_OBJS_m3) $(BOARD_CHECK_OBJS)" "$$srcs"

check-embedded-selftest:
	@sh tests/board/check_embedded_selftest.sh $(BUILD)/check-embedded-selftest \
	    "$(ARM_CC) $(CLIENT_CFLAGS_m3)" $(ARM_NM) boards/armv7m/check-embedded.sh

TEST_STEPS += check-embedded check-embedded-selftest
