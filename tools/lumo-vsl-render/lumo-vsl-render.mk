# tools/lumo-vsl-render/lumo-vsl-render.mk — seed 004's renderer driven by
# the dynamic engine (docs/dynamic.md §8): rasterizer/gl/raster_gl_vsl.c on
# the OSMesa or EGL backend (build/host/libraster_gl.a, rasterizer/gl/gl.mk),
# the engine from the server library. Other fragments' outputs are named
# literally (any include order).
VSL_RENDER_OBJS := $(BUILD)/host/tools/lumo-vsl-render/lumo_vsl_render.o $(BUILD)/host/libraster_gl.a

HOST_TOOLS += $(BIN)/lumo-vsl-render
$(BIN)/lumo-vsl-render: $(VSL_RENDER_OBJS) $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a \
                        $(BUILD)/rel/liblumo_net.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ -lOSMesa -lEGL $(SERVER_LIBS)
