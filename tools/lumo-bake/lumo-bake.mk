# tools/lumo-bake/lumo-bake.mk — lumo-bake: a scene in, its .lumo package
# (IVG bake, progressive meshes) or a path-traced reference PNG out.
# Archives are named literally (server/server.mk, tools/lib/hostlib.mk).
#
# MPI is a build option (docs/server.md "Bakes on a cluster"): when
# pkg-config finds Open MPI (LUMO_MPI_PC, default ompi-c; the set-up
# installs libopenmpi-dev), lumo-bake links server/bake/cluster/cluster_mpi.c
# and can run under mpirun; otherwise cluster_single.c, and no MPI at all.
# `make LUMO_MPI=0` forces the single-process build.
HOST_TOOLS += $(BIN)/lumo-bake

LUMO_MPI_PC ?= ompi-c
ifndef LUMO_MPI
LUMO_MPI := $(if $(shell pkg-config --exists $(LUMO_MPI_PC) 2>/dev/null && echo 1),1,0)
endif
ifeq ($(LUMO_MPI),1)
BAKE_CLUSTER_OBJ := $(BUILD)/host/server/bake/cluster/cluster_mpi.o
BAKE_CLUSTER_LIBS := $(shell pkg-config --libs $(LUMO_MPI_PC))
$(BAKE_CLUSTER_OBJ): HOST_CFLAGS += $(shell pkg-config --cflags $(LUMO_MPI_PC))
else
BAKE_CLUSTER_OBJ := $(BUILD)/host/server/bake/cluster/cluster_single.o
BAKE_CLUSTER_LIBS :=
endif

# lumo-bake's own objects (tests/mpi links them with the single-process cluster too)
LUMO_BAKE_OBJS := $(BUILD)/host/tools/lumo-bake/main.o $(BUILD)/host/tools/lumo-bake/bake_prt.o
$(BIN)/lumo-bake: $(LUMO_BAKE_OBJS) $(BAKE_CLUSTER_OBJ) $(BUILD)/host/libserver.a \
                  $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS) $(BAKE_CLUSTER_LIBS)
