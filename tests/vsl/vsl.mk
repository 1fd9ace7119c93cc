# tests/vsl/vsl.mk — the dynamic-lighting engine (server/vsl/, seed 004,
# docs/dynamic.md): cmocka binaries under ASan/UBSan linked with the server
# library. test_vsl_place: Algorithm 1 against a brute-force O(n^2)
# removal; test_vsl_pool: Algorithm 2's flux bookkeeping, the photon
# tracer with one Embree instance per object, convergence to the path
# tracer; test_vsl_ivg: the localized IVG update against a full evaluation;
# test_vsl_engine: the engine, its thread, latency, motion scripts;
# test_vsl_updates: the update log served to the client's poller.
VSL_TEST_SRCS := $(sort $(wildcard tests/vsl/test_*.c))
VSL_TESTS     := $(patsubst tests/vsl/%.c,$(BUILD)/tests/bin/%,$(VSL_TEST_SRCS))
UNIT_TESTS    += $(VSL_TESTS)

$(VSL_TESTS): $(BUILD)/tests/bin/%: $(BUILD)/tests/tests/vsl/%.o $(BUILD)/host/libserver.a \
              $(BUILD)/san/liblumo_net.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $< $(SERVER_LIB) $(BUILD)/san/liblumo_net.a $(BUILD)/san/liblumo.a \
	    $(SERVER_LIBS) $(TEST_LDLIBS)

.PHONY: test-vsl
test-vsl: $(VSL_TESTS)
	@for t in $(VSL_TESTS); do $$t || exit 1; done

# lumo-server --dynamic and lumo-client --updates end to end.
TEST_STEPS += test-dynamic
.PHONY: test-dynamic
test-dynamic: $(BIN)/lumo-server $(BIN)/lumo-client $(BIN)/lumo-bake
	@sh tests/vsl/dynamic_test.sh $(BIN) $(BUILD)/tests/dynamic

# seed 004's GL renderer (lumo-vsl-render) on OSMesa.
TEST_STEPS += test-vsl-render
.PHONY: test-vsl-render
test-vsl-render: $(BIN)/lumo-vsl-render
	@sh tests/vsl/vsl_render_test.sh $(BIN) $(BUILD)/tests/vsl-render
