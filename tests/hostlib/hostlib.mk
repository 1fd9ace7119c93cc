# tests/hostlib/hostlib.mk — the desktop library tools/lib against closed
# forms. Its sources are compiled again with the test flags (ASan/UBSan)
# rather than linked from build/host/libhost.a, so the library itself runs
# under the sanitizers.
HOSTLIB_TEST     := $(BUILD)/tests/bin/test_hostlib
HOSTLIB_TEST_OBJS := $(BUILD)/tests/tests/hostlib/test_hostlib.o \
                     $(patsubst %,$(BUILD)/tests/tools/lib/%.o,file_io png_io tonemap image_diff)
UNIT_TESTS += $(HOSTLIB_TEST)

$(HOSTLIB_TEST): $(HOSTLIB_TEST_OBJS)
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ -lpng $(TEST_LDLIBS)
