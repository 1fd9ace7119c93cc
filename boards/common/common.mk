# boards/common/common.mk — what every board build shares: include paths.
#
# Board code (the ports: boards/*/board.c, the family code of boards/armv7m/,
# boards/common/) sees the board contract boards/board.h and the console
# boards/common/console.h, never tests/: a board port links no test code.
# Board programs (tests/board/: tests, golden programs, facts, benchmarks)
# also see the test harness in tests/board/ and the build directory their
# data lists are in. Object rules: boards/armv7m/armv7m.mk (Cortex-M3) and
# boards/host/board.mk (the Linux board).
BOARD_CPPFLAGS := -Iboards -Iboards/common
$(BUILD)/board/obj-m3/tests/%.o $(BUILD)/board/obj-host/tests/%.o: \
    BOARD_PROG_CPPFLAGS := -Itests/board -DLUMO_BUILD_DIR='"$(BUILD)"'
