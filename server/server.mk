# server/server.mk — the desktop server library build/host/libserver.a,
# built from every room of server/ (docs/architecture.md): common/ (vectors,
# random numbers, progress bars, thread pool), scene/ (import, scene files,
# default scene, shapes, cameras), bake/ (Embree ray queries, path tracer,
# IVG bake, reference renderer), pm/ (progressive meshes, stream writer,
# the libdraco shim, the client driver pm_client), package/ (.lumo packages,
# IVG encoding). Every server/ROOM/*.c and *.cc is in the archive.
#
# Programs (tools/<program>/<program>.mk), tests and benchmarks link
#   $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a $(SERVER_LIBS)
# naming the archives literally in their prerequisites, so no fragment
# depends on the order the top Makefile includes them in (SERVER_LIB and
# SERVER_LIBS may be used in recipes, which make expands late).
SERVER_SRCS := $(sort $(wildcard server/*/*.c server/*/*.cc))
SERVER_OBJS := $(patsubst %,$(BUILD)/host/%.o,$(basename $(SERVER_SRCS)))
SERVER_LIB  := $(BUILD)/host/libserver.a
SERVER_LIBS := -lembree3 -lassimp -ljansson -ldraco -lstdc++ -lpng -llapacke -lm -pthread

$(BUILD)/host/libserver.a: $(SERVER_OBJS)
	rm -f $@ && ar rcs $@ $^

# The libdraco shim (C++) returns lumo_status (lumo/status.h).
$(BUILD)/host/server/pm/draco_shim.o: HOST_CXXFLAGS += -Isdk/include
