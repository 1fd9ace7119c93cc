# bench/usb.mk — make bench-usb: the USB link's session throughput against
# TCP loopback in the same QEMU guest (tests/usb/usb-test.sh with 7 pairs of
# runs; bench/usb.sh writes the section). Files of other fragments are
# named literally.
.PHONY: bench-usb
bench-usb: $(BIN)/lumo-server $(BUILD)/board/linux-gadget/lumo-gadget $(BUILD)/board/linux-gadget/lumo-client-tcp \
           $(BUILD)/board/host/client $(BUILD)/board/client/default.lumo
	@mkdir -p $(BUILD)/bench/sections
	USB_RUNS=7 sh tests/usb/usb-test.sh $(BUILD)/usb-bench $(BUILD)/board/client/default.lumo $(BIN)/lumo-server \
	    $(BUILD)/board/linux-gadget/lumo-gadget $(BUILD)/board/linux-gadget/lumo-client-tcp $(BUILD)/board/host/client
	sh bench/usb.sh $(BUILD)/usb-bench/bench.txt >$(BUILD)/bench/sections/75-usb.md
BENCH_STEPS += bench-usb
