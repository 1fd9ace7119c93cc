# lumo — the one build entry point.
#
#   make            libraries and tools into build/
#   make test       every test (host under ASan/UBSan, Cortex-M3 under QEMU,
#                   check-embedded); ends with "N passed, N failed"
#   make demo       the main job on the built-in default scene
#   make bench      benchmarks -> docs/benchmarks.md
#   make fuzz       longer libFuzzer runs of every decoder
#   make check-embedded   prove the client rules on the Cortex-M3 objects
#
# Each part of the tree adds itself through its own fragment (sdk/sdk.mk,
# server/server.mk, ...); this file holds only the shared machinery.

.DEFAULT_GOAL := all
.SUFFIXES:
.DELETE_ON_ERROR:

BUILD   ?= build
BIN     := $(BUILD)/bin
CC      ?= cc
CXX     ?= c++
ARM_CC  ?= arm-none-eabi-gcc
ARM_NM  ?= arm-none-eabi-nm
CLANG   ?= clang

# ---- flags ------------------------------------------------------------------
WARN        := -Wall -Wextra -Wshadow -Wpointer-arith -Wvla -Wstrict-prototypes \
               -Wmissing-prototypes -Werror
CLIENT_INC  := -Isdk/include -Isdk/shared -Irasterizer/include -Inet/include
CLIENT_STD  := -std=c99 -pedantic
# Client code (sdk/, rasterizer/soft/, the net codec): C99, no float, no heap.
CLIENT_CFLAGS_rel := $(CLIENT_STD) $(WARN) $(CLIENT_INC) -O2 -g
SAN_FLAGS         := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
CLIENT_CFLAGS_san := $(CLIENT_STD) $(WARN) $(CLIENT_INC) -O1 -g $(SAN_FLAGS)
M3_ARCH           := -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
CLIENT_CFLAGS_m3  := $(CLIENT_STD) $(WARN) $(CLIENT_INC) $(M3_ARCH) -Os -g \
                     -ffunction-sections -fdata-sections
# Desktop code (server/, tools/, GL backends, tests): C11, POSIX.
HOST_CFLAGS   := -std=c11 -D_GNU_SOURCE $(WARN) -Wno-missing-prototypes $(CLIENT_INC) -Iserver -Itools/lib/include -O2 -g -pthread
HOST_CXXFLAGS := -std=c++17 -Wall -Wextra -Werror -Iserver -O2 -g -pthread
TEST_CFLAGS   := -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror $(CLIENT_INC) -Iserver -Itools/lib/include -Itests/include \
                 -O1 -g $(SAN_FLAGS) -pthread
TEST_LDLIBS   := -lcmocka -lm

# ---- what the fragments fill in ---------------------------------------------
CLIENT_SRCS :=      # client-side C99 sources (sdk, rasterizer/soft, net codec)
HOST_TOOLS  :=      # binaries in $(BIN)
UNIT_TESTS  :=      # cmocka test binaries, built with sanitizers
TEST_STEPS  :=      # phony targets run by `make test` after the unit tests
BENCH_STEPS :=      # phony targets run by `make bench`
FUZZ_STEPS  :=      # phony targets run by `make fuzz`
ALL_TARGETS :=

# Fragments: every part of the tree owns one (sdk/sdk.mk, server/server.mk,
# tools/lumo-render/lumo-render.mk, tests/draco/draco.mk, ...).
include sdk/sdk.mk
include $(sort $(filter-out sdk/sdk.mk,$(wildcard sdk/*.mk rasterizer/*.mk rasterizer/*/*.mk \
        net/*.mk server/*.mk boards/*/*.mk tests/*.mk tests/*/*.mk bench/*.mk tools/*.mk tools/*/*.mk)))

# ---- client libraries, each in three variants --------------------------------
# liblumo.a: the SDK (sdk/), every client; decode-only builds link only it.
# liblumo_raster.a: the soft rasterizer (rasterizer/soft/), linked before
# liblumo.a by clients that draw.
# liblumo_net.a: the protocol codec (net/src/), linked before liblumo.a by
# clients that stream.
# rel: host -O2 (tools, benchmarks); san: host ASan/UBSan (tests);
# m3: Cortex-M3 soft-float (check-embedded, the QEMU board).
LUMO_SRCS   := $(filter sdk/%,$(CLIENT_SRCS))
RASTER_SRCS := $(filter rasterizer/soft/%,$(CLIENT_SRCS))
NET_SRCS    := $(filter net/src/%,$(CLIENT_SRCS))
CLIENT_OBJS_rel := $(patsubst %.c,$(BUILD)/rel/%.o,$(CLIENT_SRCS))
CLIENT_OBJS_san := $(patsubst %.c,$(BUILD)/san/%.o,$(CLIENT_SRCS))
CLIENT_OBJS_m3  := $(patsubst %.c,$(BUILD)/m3/%.o,$(CLIENT_SRCS))

$(BUILD)/rel/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(CLIENT_CFLAGS_rel) -MMD -MP -c $< -o $@
$(BUILD)/san/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(CLIENT_CFLAGS_san) -MMD -MP -c $< -o $@
$(BUILD)/m3/%.o: %.c
	@mkdir -p $(@D)
	$(ARM_CC) $(CLIENT_CFLAGS_m3) -MMD -MP -c $< -o $@

$(BUILD)/rel/liblumo.a: $(patsubst %.c,$(BUILD)/rel/%.o,$(LUMO_SRCS))
	rm -f $@ && ar rcs $@ $^
$(BUILD)/san/liblumo.a: $(patsubst %.c,$(BUILD)/san/%.o,$(LUMO_SRCS))
	rm -f $@ && ar rcs $@ $^
$(BUILD)/m3/liblumo.a: $(patsubst %.c,$(BUILD)/m3/%.o,$(LUMO_SRCS))
	rm -f $@ && arm-none-eabi-ar rcs $@ $^
$(BUILD)/rel/liblumo_raster.a: $(patsubst %.c,$(BUILD)/rel/%.o,$(RASTER_SRCS))
	rm -f $@ && ar rcs $@ $^
$(BUILD)/san/liblumo_raster.a: $(patsubst %.c,$(BUILD)/san/%.o,$(RASTER_SRCS))
	rm -f $@ && ar rcs $@ $^
$(BUILD)/m3/liblumo_raster.a: $(patsubst %.c,$(BUILD)/m3/%.o,$(RASTER_SRCS))
	rm -f $@ && arm-none-eabi-ar rcs $@ $^
$(BUILD)/rel/liblumo_net.a: $(patsubst %.c,$(BUILD)/rel/%.o,$(NET_SRCS))
	rm -f $@ && ar rcs $@ $^
$(BUILD)/san/liblumo_net.a: $(patsubst %.c,$(BUILD)/san/%.o,$(NET_SRCS))
	rm -f $@ && ar rcs $@ $^
$(BUILD)/m3/liblumo_net.a: $(patsubst %.c,$(BUILD)/m3/%.o,$(NET_SRCS))
	rm -f $@ && arm-none-eabi-ar rcs $@ $^

# Desktop objects (server, host board, tests) keep their own trees.
$(BUILD)/host/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -MMD -MP -c $< -o $@
$(BUILD)/host/%.o: %.cc
	@mkdir -p $(@D)
	$(CXX) $(HOST_CXXFLAGS) -MMD -MP -c $< -o $@
$(BUILD)/tests/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -MMD -MP -c $< -o $@

# ---- fuzz targets -------------------------------------------------------------
# Every tests/fuzz/fuzz_NAME.c (LLVMFuzzerTestOneInput) is built with clang's
# libFuzzer against a clang build of the client code, compiled once into
# build/fuzz/liblumo.a (coverage-instrumented, ASan/UBSan; each target takes
# only the objects it calls). `make test` runs each for FUZZ_SMOKE_SECONDS;
# `make fuzz` for FUZZ_SECONDS.
FUZZ_SRCS   := $(sort $(wildcard tests/fuzz/fuzz_*.c))
FUZZ_BINS   := $(patsubst tests/fuzz/%.c,$(BUILD)/fuzz/bin/%,$(FUZZ_SRCS))
FUZZ_COMMON := -std=c99 -g -O1 $(CLIENT_INC) -Itests/include -fno-sanitize-recover=all
FUZZ_CFLAGS := $(FUZZ_COMMON) -fsanitize=fuzzer,address,undefined
FUZZ_LIB    := $(BUILD)/fuzz/liblumo.a
FUZZ_SMOKE_SECONDS ?= 8
FUZZ_SECONDS       ?= 300

$(BUILD)/fuzz/obj/%.o: %.c
	@mkdir -p $(@D)
	$(CLANG) $(FUZZ_COMMON) -fsanitize=fuzzer-no-link,address,undefined -MMD -MP -c $< -o $@
$(FUZZ_LIB): $(patsubst %.c,$(BUILD)/fuzz/obj/%.o,$(CLIENT_SRCS))
	rm -f $@ && ar rcs $@ $^

$(BUILD)/fuzz/bin/%: tests/fuzz/%.c $(FUZZ_LIB)
	@mkdir -p $(@D) $(BUILD)/fuzz/corpus/$*
	$(CLANG) $(FUZZ_CFLAGS) -o $@ $< $(FUZZ_LIB)

.PHONY: fuzz-smoke
fuzz-smoke: $(FUZZ_BINS)
	@sh tests/fuzz/run.sh $(BUILD) $(FUZZ_SMOKE_SECONDS) $(FUZZ_BINS)
FUZZ_STEPS += fuzz-long
.PHONY: fuzz-long
fuzz-long: $(FUZZ_BINS)
	@sh tests/fuzz/run.sh $(BUILD) $(FUZZ_SECONDS) $(FUZZ_BINS)
TEST_STEPS += fuzz-smoke

# ---- top-level targets -------------------------------------------------------
.PHONY: all setup test unit-tests bench fuzz demo clean check-embedded

SETUP_STAMP := $(BUILD)/.setup-done
setup: $(SETUP_STAMP)
$(SETUP_STAMP): tools/setup.sh
	@mkdir -p $(BUILD)
	sh tools/setup.sh
	@touch $@

all: $(SETUP_STAMP) $(BUILD)/rel/liblumo.a $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo_net.a \
     $(ALL_TARGETS) $(HOST_TOOLS)

test: $(SETUP_STAMP)
	@$(MAKE) --no-print-directory all $(UNIT_TESTS) $(BUILD)/m3/liblumo.a $(BUILD)/m3/liblumo_raster.a \
	    $(BUILD)/m3/liblumo_net.a
	+@sh tests/run.sh $(BUILD) "$(UNIT_TESTS)" "$(TEST_STEPS)"

bench: $(SETUP_STAMP) all
	+@sh bench/run.sh $(BUILD) "$(BENCH_STEPS)"

fuzz: $(SETUP_STAMP) $(FUZZ_STEPS)

clean:
	rm -rf $(BUILD)/rel $(BUILD)/san $(BUILD)/m3 $(BUILD)/host $(BUILD)/tests $(BIN) $(BUILD)/fuzz $(BUILD)/board

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
