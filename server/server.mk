# server/server.mk — the desktop server: scene import, Embree IVG bake,
# reference renderer, .lumo packages; tools lumo-bake and lumo-inspect.
#
# Hooks for other fragments (server/pm.mk is included before this file):
#   LUMO_SERVER_EXTRA_OBJS  objects every server tool links (e.g. pm_*.o, draco shim)
#   LUMO_SERVER_EXTRA_LIBS  libraries for them (e.g. -ldraco -lstdc++)
# lumo-inspect subcommands: any server/inspect_*.c is linked into lumo-inspect;
# it registers itself with LUMO_INSPECT_COMMAND (server/include/lumo_server/inspect.h).
# PNG files, tone mapping, Delta E and whole-file reads come from the desktop
# library build/host/libhost.a (tools/lib/hostlib.mk, included after this
# file, so named literally; it needs -lpng -lm from SERVER_LIBS).

SERVER_CORE := scene/camera scene/scene scene/shapes scene/import scene/scene_file scene/default_scene \
               bake/rt bake/pathtrace common/parallel common/progress bake/bake bake/reference \
               package/package_write package/pack package/ivg_encode
SERVER_OBJS := $(patsubst %,$(BUILD)/host/server/%.o,$(SERVER_CORE))
SERVER_LIB  := $(BUILD)/host/libserver.a
SERVER_LIBS := -lembree3 -lassimp -lpng -lm -pthread
INSPECT_SRCS := $(sort $(wildcard server/inspect*.c))
INSPECT_OBJS := $(patsubst %.c,$(BUILD)/host/%.o,$(INSPECT_SRCS))

HOST_TOOLS += $(BIN)/lumo-bake $(BIN)/lumo-inspect

$(SERVER_LIB): $(SERVER_OBJS)
	rm -f $@ && ar rcs $@ $^

$(BIN)/lumo-bake: $(BUILD)/host/server/bake_main.o $(SERVER_LIB) $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a \
                  $(LUMO_SERVER_EXTRA_OBJS)
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $(BUILD)/host/server/bake_main.o $(LUMO_SERVER_EXTRA_OBJS) $(SERVER_LIB) \
	    $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a $(SERVER_LIBS) $(LUMO_SERVER_EXTRA_LIBS)

# Inspect objects are linked directly (not from an archive), so their
# registration constructors are kept. Extra objects come before the server
# library because they may call into it.
$(BIN)/lumo-inspect: $(INSPECT_OBJS) $(SERVER_LIB) $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a \
                     $(LUMO_SERVER_EXTRA_OBJS)
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $(INSPECT_OBJS) $(LUMO_SERVER_EXTRA_OBJS) $(SERVER_LIB) \
	    $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a $(SERVER_LIBS) $(LUMO_SERVER_EXTRA_LIBS)
