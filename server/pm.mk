# server/pm.mk — progressive meshes (issue 5): the server build (half-edge
# collapse, stream writer, libdraco shim), the lumo-pm tool, the pm tests
# and the pm benchmark. Included before server/server.mk, whose tools link
# LUMO_SERVER_EXTRA_OBJS/LIBS (lumo-inspect gets server/inspect_pm.c).
PM_SERVER_SRCS := server/pm/pm_clean.c server/pm/pm_simplify.c server/pm/pm_build.c server/pm/pm_stream.c \
                  server/pm/pm_client.c server/pm/pm_load.c server/pm/pm_pack.c
PM_OBJS        := $(patsubst %.c,$(BUILD)/host/%.o,$(PM_SERVER_SRCS)) $(BUILD)/host/server/pm/draco_shim.o
PM_LIBS        := -ldraco -lstdc++ -lm

LUMO_SERVER_EXTRA_OBJS += $(PM_OBJS)
LUMO_SERVER_EXTRA_LIBS += $(PM_LIBS)

HOST_TOOLS += $(BIN)/lumo-pm
PM_TOOL_OBJS := $(BUILD)/host/server/pm_tool.o $(BUILD)/host/server/pm_bench.o

$(BIN)/lumo-pm: $(PM_TOOL_OBJS) $(PM_OBJS) $(BUILD)/host/libserver.a $(BUILD)/rel/liblumo.a $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $(PM_TOOL_OBJS) $(PM_OBJS) $(BUILD)/host/libserver.a $(BUILD)/rel/liblumo.a $(BUILD)/host/libhost.a \
	    -lembree3 -lassimp -lpng $(PM_LIBS)
