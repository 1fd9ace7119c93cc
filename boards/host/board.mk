# boards/host/board.mk — the Linux board: boards/board.h on stdio
# (boards/host/board.c, its link boards/host/link_tcp.c), so every board program also runs natively, under
# ASan/UBSan against the sanitizer builds of the client libraries; the host
# half of the host == board hash checks (board-tests, board-lm3s).
#
# $(BUILD)/board/host/NAME is tests/board/NAME.c linked with this port, the
# test harness (harness.c, golden.c, ivg_wire.c) and the client libraries.
HOST_BOARD_OBJS := $(patsubst %.c,$(BUILD)/board/obj-host/%.o,boards/host/board.c boards/host/link_tcp.c \
    boards/common/console.c boards/common/no_screen.c)
HOST_BOARD_TEST_OBJS := $(patsubst %,$(BUILD)/board/obj-host/tests/board/%.o,harness golden ivg_wire)
HOST_BOARD_LIBS := $(BUILD)/san/liblumo_net.a $(BUILD)/san/liblumo_raster.a $(BUILD)/san/liblumo.a

$(BUILD)/board/obj-host/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(CLIENT_CFLAGS_san) $(BOARD_CPPFLAGS) $(BOARD_PROG_CPPFLAGS) -MMD -MP -c $< -o $@
.PRECIOUS: $(BUILD)/board/obj-host/%.o

$(BUILD)/board/host/%: $(BUILD)/board/obj-host/tests/board/%.o $(HOST_BOARD_TEST_OBJS) $(HOST_BOARD_OBJS) \
                       $(HOST_BOARD_LIBS)
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $< $(HOST_BOARD_TEST_OBJS) $(HOST_BOARD_OBJS) $(HOST_BOARD_LIBS)
