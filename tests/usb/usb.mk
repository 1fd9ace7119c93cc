# tests/usb/usb.mk — the USB transport (docs/protocol.md §8 "USB"):
#
#   test_net_usb (tests/unit/, with the codec's tests): the bulk transfer
#       rule on a model of packets
#   test_usb_bridge: lumo-server's bridge pumps with a simulated device
#       (transfers cut by the rule; a device that goes away; a socket the
#       loop closes; the no-device start)
#   make test-usb: for real, in a QEMU x86-64 guest with Debian's kernel,
#       dummy_hcd, libcomposite and usb_f_fs: the gadget client of
#       boards/linux-gadget against lumo-server --usb, clean, unplugged
#       mid-stream and resumed, and the throughput against TCP loopback
#       (tests/usb/usb-test.sh); the kernel is fetched once into
#       $(BUILD)/usb/kernel (tests/usb/kernel.sh).
# Files of other fragments are named literally: fragments are included in
# any order.
USB_DIR := $(BUILD)/usb

USB_BRIDGE_TEST := $(BUILD)/tests/bin/test_usb_bridge
UNIT_TESTS += $(USB_BRIDGE_TEST)
$(USB_BRIDGE_TEST): $(BUILD)/tests/tests/usb/test_usb_bridge.o $(BUILD)/tests/server/serve/usb_bridge.o \
                    $(BUILD)/tests/server/serve/usb.o $(BUILD)/tests/server/common/status_msg.o \
                    $(BUILD)/san/liblumo_net.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $^ $(TEST_LDLIBS) -lusb-1.0

TEST_STEPS += test-usb
.PHONY: test-usb
test-usb: $(BIN)/lumo-server $(BUILD)/board/linux-gadget/lumo-gadget $(BUILD)/board/linux-gadget/lumo-client-tcp \
          $(BUILD)/board/host/client $(BUILD)/board/client/default.lumo
	@sh tests/usb/usb-test.sh $(USB_DIR) $(BUILD)/board/client/default.lumo $(BIN)/lumo-server \
	    $(BUILD)/board/linux-gadget/lumo-gadget $(BUILD)/board/linux-gadget/lumo-client-tcp $(BUILD)/board/host/client
