# tools/lumo-server/lumo-server.mk — lumo-server: streams .lumo packages to
# thin clients (docs/protocol.md, docs/server.md "lumo-server"). Its code is
# server/serve/ (in libserver.a); it links the net codec, the SDK and the
# desktop helper library (package messages) only: no Embree, assimp or
# Draco; libusb for --usb (server/serve/usb.c). Archives are named literally.
HOST_TOOLS += $(BIN)/lumo-server

$(BIN)/lumo-server: $(BUILD)/host/tools/lumo-server/main.o $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a \
                    $(BUILD)/rel/liblumo_net.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ -lusb-1.0 -lm
