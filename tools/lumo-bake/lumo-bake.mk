# tools/lumo-bake/lumo-bake.mk — lumo-bake: a scene in, its .lumo package
# (IVG bake, progressive meshes) or a path-traced reference PNG out.
# Archives are named literally (server/server.mk, tools/lib/hostlib.mk).
HOST_TOOLS += $(BIN)/lumo-bake

$(BIN)/lumo-bake: $(BUILD)/host/tools/lumo-bake/main.o $(BUILD)/host/tools/lumo-bake/bake_prt.o $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a \
                  $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS)
