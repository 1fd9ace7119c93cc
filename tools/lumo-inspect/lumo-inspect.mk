# tools/lumo-inspect/lumo-inspect.mk — lumo-inspect: read a .lumo package
# (or a raw progressive-mesh stream) with the client. Every
# tools/lumo-inspect/*.c is linked in; a subcommand registers itself with
# INSPECT_COMMAND (inspect.h). The objects are linked directly (not
# from an archive) so their registration constructors are kept; their link
# order (sorted names) is the order of --help and of the flag lookup.
# Archives are named literally (server/server.mk, tools/lib/hostlib.mk).
INSPECT_SRCS := $(sort $(wildcard tools/lumo-inspect/*.c))
INSPECT_OBJS := $(patsubst %.c,$(BUILD)/host/%.o,$(INSPECT_SRCS))

HOST_TOOLS += $(BIN)/lumo-inspect

$(BIN)/lumo-inspect: $(INSPECT_OBJS) $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS)
