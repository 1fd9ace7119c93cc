# tests/hostile/cli.mk — the tools' command lines against hostile values
# (issue 24, part A): the one option parser (tools/lib/options.c) under
# cmocka, compiled again with the test flags so it runs under ASan/UBSan;
# tests/hostile/cli.sh, bad command lines generated at test time for every
# tool, each with its expected refusal; and the parser's fuzz target.
CLI_OPTIONS_TEST := $(BUILD)/tests/bin/test_cli_options
CLI_OPTIONS_TEST_OBJS := $(BUILD)/tests/tests/hostile/test_cli_options.o $(BUILD)/tests/tools/lib/options.o
UNIT_TESTS += $(CLI_OPTIONS_TEST)

$(CLI_OPTIONS_TEST): $(CLI_OPTIONS_TEST_OBJS)
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ $(TEST_LDLIBS)
