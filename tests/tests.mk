# tests/tests.mk — unit tests (cmocka, host, ASan/UBSan).
#
# Every tests/unit/test_*.c becomes one binary linked with the sanitizer build
# of the client library. Tests may use floating point: they compare the
# fixed-point client against double-precision references.
UNIT_TEST_SRCS := $(sort $(wildcard tests/unit/test_*.c))
UNIT_TESTS     += $(patsubst tests/unit/%.c,$(BUILD)/tests/bin/%,$(UNIT_TEST_SRCS))

$(BUILD)/tests/bin/%: $(BUILD)/tests/tests/unit/%.o $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(TEST_LDLIBS)
