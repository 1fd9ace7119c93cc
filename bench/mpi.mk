# bench/mpi.mk — `make bench-mpi`: lumo-bake's strong scaling under mpirun on
# this machine (ranks x threads), the bytes each rank sends, and the
# projection to 64 nodes from measured per-vertex costs and volumes
# (bench/mpi_scaling.sh, bench/mpi_model.c; docs/server.md "Bakes on a cluster").
BENCH_STEPS += bench-mpi
.PHONY: bench-mpi
$(BUILD)/host/bench/lumo-bench-mpi-model: $(BUILD)/host/bench/mpi_model.o $(BUILD)/host/libserver.a \
                                          $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $< $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a \
	    $(SERVER_LIBS)
bench-mpi: $(BIN)/lumo-bake $(BUILD)/host/bench/lumo-bench-mpi-model
	@mkdir -p $(BUILD)/bench/sections
	sh bench/mpi_scaling.sh $(BIN)/lumo-bake $(BUILD)/host/bench/lumo-bench-mpi-model $(BUILD)/bench/mpi \
	    > $(BUILD)/bench/sections/31-mpi.md.tmp
	mv $(BUILD)/bench/sections/31-mpi.md.tmp $(BUILD)/bench/sections/31-mpi.md
