# tests/mpi/mpi.mk — lumo-bake across MPI ranks (docs/server.md "Bakes on a
# cluster"): the chunk/checkpoint unit test (sanitizers, one process), the
# end-to-end script under mpirun (byte-identical packages and references at
# 1, 2 and 4 ranks, a killed rank, a resumed checkpoint, the build without
# MPI), and a libFuzzer target for the checkpoint reader.
MPI_TEST_SRCS := $(sort $(wildcard tests/mpi/test_*.c))
MPI_TESTS     := $(patsubst tests/mpi/%.c,$(BUILD)/tests/bin/%,$(MPI_TEST_SRCS))
UNIT_TESTS    += $(MPI_TESTS)

$(MPI_TESTS): $(BUILD)/tests/bin/%: $(BUILD)/tests/tests/mpi/%.o $(BUILD)/host/libserver.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $< $(SERVER_LIB) $(BUILD)/san/liblumo.a $(SERVER_LIBS) $(TEST_LDLIBS)

# lumo-bake as a build without MPI makes it (the single-process cluster.h),
# to show it works as before and refuses to run as N copies under mpirun.
# (lumo-bake's objects are named by its own fragment, read after this one.)
.SECONDEXPANSION:
$(BUILD)/tests/bin/lumo-bake-nompi: $$(LUMO_BAKE_OBJS) \
        $(BUILD)/host/server/bake/cluster/cluster_single.o $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a \
        $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS)

# The end-to-end test needs mpirun (openmpi-bin) and an MPI lumo-bake; on a
# machine without them it says so and counts as failed, since the set-up
# installs both.
TEST_STEPS += test-mpi
.PHONY: test-mpi
test-mpi: $(BIN)/lumo-bake $(BIN)/lumo-inspect $(BUILD)/tests/bin/lumo-bake-nompi
	@sh tests/mpi/mpi_test.sh $(BIN) $(BUILD)/tests/bin/lumo-bake-nompi $(BUILD)/tests/mpi $(LUMO_MPI)

# The checkpoint reader is a decoder of outside bytes: its fuzz target,
# built with clang against the reader's sources.
FUZZ_CKPT     := $(BUILD)/fuzz/bin/fuzz_checkpoint
FUZZ_CKPT_SRC := tests/mpi/fuzz_checkpoint.c server/bake/checkpoint.c server/bake/work.c \
                 server/common/progress.c sdk/src/wire.c
$(FUZZ_CKPT): $(FUZZ_CKPT_SRC)
	@mkdir -p $(@D) $(BUILD)/fuzz/corpus/fuzz_checkpoint
	$(CLANG) -std=c11 -D_GNU_SOURCE -g -O1 $(CLIENT_INC) -Iserver -fsanitize=fuzzer,address,undefined \
	    -fno-sanitize-recover=all -o $@ $(FUZZ_CKPT_SRC)

TEST_STEPS += fuzz-smoke-checkpoint
FUZZ_STEPS += fuzz-long-checkpoint
.PHONY: fuzz-smoke-checkpoint fuzz-long-checkpoint
fuzz-smoke-checkpoint: $(FUZZ_CKPT)
	@sh tests/fuzz/run.sh $(BUILD) $(FUZZ_SMOKE_SECONDS) $(FUZZ_CKPT)
fuzz-long-checkpoint: $(FUZZ_CKPT)
	@sh tests/fuzz/run.sh $(BUILD) $(FUZZ_SECONDS) $(FUZZ_CKPT)
