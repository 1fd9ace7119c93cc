# tools/lumo-pm/lumo-pm.mk — lumo-pm: progressive-mesh streams from mesh
# files (build, clean, apply), and its bench subcommand (bench.c; run by
# bench/pm.mk). Archives are named literally (server/server.mk,
# tools/lib/hostlib.mk).
HOST_TOOLS += $(BIN)/lumo-pm

$(BIN)/lumo-pm: $(BUILD)/host/tools/lumo-pm/main.o $(BUILD)/host/tools/lumo-pm/bench.o \
                $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS)
