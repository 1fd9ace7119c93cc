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

# The parser's fuzz target: tests/fuzz/fuzz_cli_options.c is picked up by
# the top Makefile's fuzz wildcard (run by `make test` and `make fuzz`), but
# it links the desktop parser rather than the client sources, so it has this
# rule of its own (an explicit rule wins over the pattern rule).
$(BUILD)/fuzz/bin/fuzz_cli_options: tests/fuzz/fuzz_cli_options.c tools/lib/options.c \
                                    tools/lib/include/lumo_host/options.h
	@mkdir -p $(@D) $(BUILD)/fuzz/corpus/fuzz_cli_options
	$(CLANG) $(FUZZ_CFLAGS) -D_GNU_SOURCE -Itools/lib/include -o $@ tests/fuzz/fuzz_cli_options.c tools/lib/options.c
