# tests/prt/prt.mk — PRT's server-side tests (seed 003, docs/prt.md): SH
# projection and rotation against known answers, transfer of an unoccluded
# convex object, CPCA (alpha = 0 is plain LBG, null clusters, PCA),
# super-clusters; cmocka binaries linked with the server library.
PRT_TEST_SRCS := $(sort $(wildcard tests/prt/test_*.c))
PRT_TESTS     := $(patsubst tests/prt/%.c,$(BUILD)/tests/bin/%,$(PRT_TEST_SRCS))
UNIT_TESTS    += $(PRT_TESTS)

$(PRT_TESTS): $(BUILD)/tests/bin/%: $(BUILD)/tests/tests/prt/%.o $(BUILD)/host/libserver.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $< $(SERVER_LIB) $(BUILD)/san/liblumo.a $(SERVER_LIBS) $(TEST_LDLIBS)

TEST_STEPS += test-prt-cli
.PHONY: test-prt-cli
test-prt-cli: $(BIN)/lumo-bake $(BIN)/lumo-render $(BIN)/lumo-inspect $(BIN)/prt-demo
	@sh tests/prt/prt_cli.sh $(BIN) $(BUILD)/tests/prt-cli

# PRT over the protocol (docs/protocol.md §10): lumo-server to lumo-client
# --prt, the streamed picture equal to lumo-render --prt's byte for byte,
# cut and resumed, recorded and replayed (tests/prt/prt_stream.sh).
TEST_STEPS += test-prt-stream
.PHONY: test-prt-stream
test-prt-stream: $(BIN)/lumo-bake $(BIN)/lumo-render $(BIN)/lumo-client $(BIN)/lumo-server $(BIN)/prt-demo \
                 $(BUILD)/tests/bin/cut_proxy
	@sh tests/prt/prt_stream.sh $(BIN) $(BUILD)/tests/bin $(BUILD)/tests/prt-stream
