# boards/linux-gadget/linux-gadget.mk — the thin client (boards/client/
# client.c) as a USB gadget of a Linux board with a device-mode port
# (docs/porting.md §8): the Linux board's port (boards/host/board.c) with
# the link over FunctionFS (link_ffs.c, ffs_desc.c). Release builds (-O2,
# no sanitizers): they run inside the QEMU guest of tests/usb/ and on real
# boards; the client's code runs under ASan/UBSan in the host builds of
# boards/client/client.mk.
#
#   $(GADGET_BIN)      the gadget client
#   $(GADGET_TCP_BIN)  the same client over TCP (boards/host/link_tcp.c),
#                      the peer of the USB throughput figure
GADGET_DIR     := $(BUILD)/board/linux-gadget
GADGET_BIN     := $(GADGET_DIR)/lumo-gadget
GADGET_TCP_BIN := $(GADGET_DIR)/lumo-client-tcp
GADGET_COMMON  := $(BOARD_CLIENT_SRCS) boards/host/board.c boards/common/console.c boards/common/no_screen.c
GADGET_OBJS     := $(patsubst %.c,$(BUILD)/board/obj-gadget/%.o,$(GADGET_COMMON) boards/linux-gadget/link_ffs.c \
                   boards/linux-gadget/ffs_desc.c)
GADGET_TCP_OBJS := $(patsubst %.c,$(BUILD)/board/obj-gadget/%.o,$(GADGET_COMMON) boards/host/link_tcp.c)
GADGET_LIBS     := $(BUILD)/rel/liblumo_net.a $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo.a

# gnu99, not -pedantic: <linux/usb/functionfs.h> uses GNU attributes.
$(BUILD)/board/obj-gadget/%.o: %.c
	@mkdir -p $(@D)
	$(CC) -std=gnu99 $(WARN) $(CLIENT_INC) $(BOARD_CPPFLAGS) -Iboards/linux-gadget -O2 -g -pthread -MMD -MP -c $< -o $@
.PRECIOUS: $(BUILD)/board/obj-gadget/%.o

$(GADGET_BIN): $(GADGET_OBJS) $(GADGET_LIBS)
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^
$(GADGET_TCP_BIN): $(GADGET_TCP_OBJS) $(GADGET_LIBS)
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^

ALL_TARGETS += $(GADGET_BIN) $(GADGET_TCP_BIN)
