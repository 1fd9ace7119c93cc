# tools/lumo-server/lumo-server.mk — lumo-server: streams .lumo packages to
# thin clients (docs/protocol.md, docs/server.md "lumo-server"). Its code is
# server/serve/ (in libserver.a); it links the net codec, the SDK and the
# desktop helper library (package messages), libusb for --usb
# (server/serve/usb.c), and for --dynamic (dynamic.c, docs/dynamic.md) the
# lighting engine of server/vsl/ with Embree (assimp and Draco come along
# with libserver.a's scene loader). Archives are named literally.
HOST_TOOLS += $(BIN)/lumo-server

$(BIN)/lumo-server: $(BUILD)/host/tools/lumo-server/main.o $(BUILD)/host/tools/lumo-server/dynamic.o \
                    $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo_net.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ -lusb-1.0 $(SERVER_LIBS)
