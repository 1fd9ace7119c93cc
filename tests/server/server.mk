# tests/server/server.mk — the server's tests: cmocka binaries linked with
# the server library (physics with known answers, scene sense, determinism,
# quantized vs float, packages) and a CLI script (bad input, same seed).
SERVER_TEST_SRCS := $(sort $(wildcard tests/server/test_*.c))
SERVER_TESTS     := $(patsubst tests/server/%.c,$(BUILD)/tests/bin/%,$(SERVER_TEST_SRCS))
UNIT_TESTS       += $(SERVER_TESTS)

$(SERVER_TESTS): $(BUILD)/tests/bin/%: $(BUILD)/tests/tests/server/%.o $(BUILD)/host/libserver.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $< $(SERVER_LIB) $(BUILD)/san/liblumo.a $(SERVER_LIBS) $(TEST_LDLIBS)

TEST_STEPS += test-server-cli
.PHONY: test-server-cli
test-server-cli: $(BIN)/lumo-bake $(BIN)/lumo-inspect
	@sh tests/server/cli_test.sh $(BIN) $(BUILD)/tests/server-cli
