# bench/draco.mk — `make bench-draco`: lumo's Draco decoder vs libdraco.
DRACO_BENCH     := $(BIN)/draco-bench
DRACO_BENCH_LIB := $(BIN)/draco-bench-libdraco
HOST_TOOLS      += $(DRACO_BENCH) $(DRACO_BENCH_LIB)

$(DRACO_BENCH): $(BUILD)/host/bench/draco_bench.o $(BUILD)/host/tools/lib/options.o $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^

# REPS through the strict option parser (C, lumo_host/options.h).
$(BUILD)/host/bench/draco_bench_libdraco.o: HOST_CXXFLAGS += -Itools/lib/include
$(DRACO_BENCH_LIB): $(BUILD)/host/bench/draco_bench_libdraco.o $(BUILD)/host/bench/heap_count.o \
                    $(BUILD)/host/tools/lib/options.o
	@mkdir -p $(@D)
	$(CXX) -o $@ $^ -ldraco -pthread

.PHONY: bench-draco bench-draco-attrs
bench-draco: $(DRACO_BENCH) $(DRACO_BENCH_LIB) $(BUILD)/m3/liblumo.a bench-draco-attrs
	@sh bench/draco_bench.sh $(BUILD)
BENCH_STEPS += bench-draco

# the attribute set of issue 25 (bench/draco_attrs.sh): many files a process
DRACO_SET_BENCH     := $(BIN)/draco-set-bench
DRACO_SET_BENCH_LIB := $(BIN)/draco-set-bench-libdraco
HOST_TOOLS          += $(DRACO_SET_BENCH) $(DRACO_SET_BENCH_LIB)
$(DRACO_SET_BENCH): $(BUILD)/host/bench/draco_set_bench.o $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^
$(DRACO_SET_BENCH_LIB): $(BUILD)/host/bench/draco_set_bench_libdraco.o $(BUILD)/host/bench/heap_count.o
	@mkdir -p $(@D)
	$(CXX) -o $@ $^ -ldraco -pthread
# the attribute set alone (section 41); DRACO_ATTRS=quick: 21 of its 126 rows
bench-draco-attrs: $(DRACO_SET_BENCH) $(DRACO_SET_BENCH_LIB) $(BIN)/gen-attr-meshes
	@sh bench/draco_attrs.sh $(BUILD) $(DRACO_ATTRS)
