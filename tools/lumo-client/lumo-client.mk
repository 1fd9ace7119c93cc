# tools/lumo-client/lumo-client.mk — lumo-client, the Linux thin client
# (docs/protocol.md): the protocol driver and codec (liblumo_net.a), the
# session (liblumo.a), the renderers of lumo-render (its backend and scene
# objects, named literally: fragments are included in any order), the
# desktop transports of net/host/, the server's request mapping
# (libserver.a: --http answers its own requests) and libcurl (--http).
CLIENT_TOOL_OBJS := $(patsubst %.c,$(BUILD)/host/%.o,$(sort $(wildcard tools/lumo-client/*.c))) \
                    $(BUILD)/host/net/host/net_socket.o \
                    $(BUILD)/host/tools/lumo-render/session_scene.o \
                    $(BUILD)/host/tools/lumo-render/render_backend.o \
                    $(BUILD)/host/tools/lumo-render/prt_render.o

HOST_TOOLS += $(BIN)/lumo-client

$(BIN)/lumo-client: $(CLIENT_TOOL_OBJS) $(BUILD)/host/libraster_gl.a \
                    $(BUILD)/host/libmesh_build.a $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a \
                    $(BUILD)/rel/liblumo_net.a $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ -lOSMesa -lEGL -lcurl $(SERVER_LIBS)
