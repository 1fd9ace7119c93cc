# net/net.mk — the stream protocol's codec (net/src/, docs/protocol.md;
# client rules: C99, no heap, no float), built into liblumo_net.a by the top
# Makefile (clients that stream link it before liblumo.a). Through
# CLIENT_SRCS it is also proven by `make check-embedded` (boards/armv7m/)
# and compiled into every fuzz target (tests/fuzz/fuzz_net.c fuzzes it).
CLIENT_SRCS += $(sort $(wildcard net/src/*.c))

# Unit tests of the codec (tests/unit/test_net*.c) link its sanitizer build
# before liblumo.a (the CRC). Libraries are named literally: fragments are
# included in any order.
NET_UNIT_TESTS := $(patsubst tests/unit/%.c,$(BUILD)/tests/bin/%,$(wildcard tests/unit/test_net*.c))
$(NET_UNIT_TESTS): $(BUILD)/tests/bin/%: $(BUILD)/tests/tests/unit/%.o $(BUILD)/san/liblumo_net.a \
                   $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(TEST_LDLIBS)
