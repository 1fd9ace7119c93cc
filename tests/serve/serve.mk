# tests/serve/serve.mk — lumo-server: the request mapping as a unit test
# (test_serve_plan.c), and end to end (tests/serve/serve_test.sh):
# whole fetches checked byte for byte, resume after cuts, hostile frames,
# idle and slow clients, the serial listener with loss, --max-clients, link
# emulation timing, 1000 clients at once with the server's memory per
# client, SIGTERM drain. The client (serve_client.c) is the codec as a
# minimal client; the servers are a sanitizer build of server/serve/ and
# tools/lumo-server/ (lumo-server-san) and, for the memory figures, the
# release build. Libraries are named literally.
SERVE_CLIENT   := $(BUILD)/tests/bin/serve_client
SERVE_SAN      := $(BUILD)/tests/bin/lumo-server-san
SERVE_SAN_OBJS := $(patsubst %.c,$(BUILD)/tests/%.o,$(sort $(wildcard server/serve/*.c)) server/common/status_msg.c \
                  tools/lumo-server/main.c)

$(SERVE_CLIENT): $(BUILD)/tests/tests/serve/serve_client.o $(BUILD)/san/liblumo_net.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^
$(SERVE_SAN): $(SERVE_SAN_OBJS) $(BUILD)/host/libhost.a $(BUILD)/san/liblumo_net.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ -lusb-1.0 -lm

# The request mapping on synthetic streams and round tables (cmocka).
SERVE_UNIT := $(BUILD)/tests/bin/test_serve_plan
UNIT_TESTS += $(SERVE_UNIT)
$(SERVE_UNIT): $(BUILD)/tests/tests/serve/test_serve_plan.o $(BUILD)/tests/server/serve/plan.o \
               $(BUILD)/tests/server/serve/index.o $(BUILD)/tests/server/common/status_msg.o $(BUILD)/host/libhost.a $(BUILD)/san/liblumo_net.a \
               $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(TEST_LDLIBS)

# docs/protocol.md §6, the worked example: a whole session on
# tests/fuzz/seeds/fuzz_package/example.lumo, checked against the doc
# (run from the top of the tree; --markdown prints the section).
EXAMPLE_UNIT := $(BUILD)/tests/bin/test_protocol_example
UNIT_TESTS += $(EXAMPLE_UNIT)
$(EXAMPLE_UNIT): $(BUILD)/tests/tests/serve/test_protocol_example.o $(BUILD)/tests/server/serve/plan.o \
                 $(BUILD)/tests/server/serve/index.o $(BUILD)/tests/server/common/status_msg.o $(BUILD)/host/libhost.a \
                 $(BUILD)/san/liblumo_net.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(TEST_LDLIBS)

TEST_STEPS += test-serve
.PHONY: test-serve
test-serve: $(BIN)/lumo-server $(BIN)/lumo-bake $(SERVE_SAN) $(SERVE_CLIENT)
	@sh tests/serve/serve_test.sh $(BIN) $(BUILD)/tests/bin $(BUILD)/tests/serve $(BUILD)/data/models
