# tests/draco/draco.mk — Draco conformance: the libdraco oracle, the mesh
# generator, a sanitizer build of lumo-draco-decode, and the test steps.
#
#   make draco-conformance        full grid: levels x quantization bits x all
#                                 meshes (part of `make test`, ~1 min)
#   make draco-conformance-quick  a sampled grid for quick iteration
DRACO_ORACLE := $(BIN)/draco-oracle
DRACO_GEN    := $(BIN)/gen-meshes
DRACO_GEN_ATTR := $(BIN)/gen-attr-meshes
DRACO_SAN    := $(BIN)/lumo-draco-decode-san
DRACO_PLYCMP := $(BIN)/ply-compare
HOST_TOOLS   += $(DRACO_ORACLE) $(DRACO_GEN) $(DRACO_SAN) $(DRACO_PLYCMP)

$(DRACO_ORACLE): $(BUILD)/host/tests/draco/draco_oracle.o
	@mkdir -p $(@D)
	$(CXX) -o $@ $^ -ldraco -pthread

$(DRACO_GEN): $(BUILD)/host/tests/draco/gen_meshes.o
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lm

$(DRACO_PLYCMP): $(BUILD)/host/tests/draco/ply_compare.o
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lm

$(DRACO_SAN): $(BUILD)/tests/tools/lumo-draco-decode/main.o $(BUILD)/san/liblumo.a $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ -lm

# The decoder built with the lean mode only (LUMO_DRACO_MODES, as the
# ARMv7-M boards build it: boards/armv7m/draco_modes.mk), sanitizer build:
# its draco objects ahead of the rest of liblumo. Conformance decodes every
# case with it too, so the boards' choice is checked on every case.
DRACO_SAN_LEAN      := $(BIN)/lumo-draco-decode-lean-san
DRACO_LEAN_SAN_OBJS := $(patsubst %.c,$(BUILD)/san-lean/%.o,$(wildcard sdk/src/draco_*.c))
HOST_TOOLS          += $(DRACO_SAN_LEAN)
$(BUILD)/san-lean/%.o: %.c tests/draco/draco.mk
	@mkdir -p $(@D)
	$(CC) $(CLIENT_CFLAGS_san) -DLUMO_DRACO_MODES=LUMO_DRACO_MODES_LEAN -MMD -MP -c $< -o $@
-include $(DRACO_LEAN_SAN_OBJS:.o=.d)
$(DRACO_SAN_LEAN): $(BUILD)/tests/tools/lumo-draco-decode/main.o $(DRACO_LEAN_SAN_OBJS) \
                   $(BUILD)/san/liblumo.a $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ -lm

DRACO_CONF_DEPS := $(DRACO_ORACLE) $(DRACO_GEN) $(DRACO_GEN_ATTR) $(DRACO_SAN) $(DRACO_SAN_LEAN) \
                   $(DRACO_PLYCMP) $(BIN)/lumo-draco-decode

.PHONY: draco-conformance draco-conformance-quick draco-conformance-full
draco-conformance: $(DRACO_CONF_DEPS)
	@DRACO_JOBS=4 sh tests/draco/conformance.sh $(BUILD) full
draco-conformance-full: draco-conformance
draco-conformance-quick: $(DRACO_CONF_DEPS)
	@sh tests/draco/conformance.sh $(BUILD) quick

TEST_STEPS += draco-conformance

# arena / output of the 48k dragon at -cl 0, 7, 10 under fixed limits
.PHONY: draco-arena
draco-arena: $(BIN)/lumo-draco-decode $(DRACO_GEN_ATTR)
	@sh tests/draco/arena_check.sh $(BUILD)
TEST_STEPS += draco-arena

# refusal conformance (issue 24): mutated streams libdraco refuses, lumo
# refuses too; libdraco in-process against the sanitizer build of liblumo
DRACO_REFUSAL := $(BIN)/draco-refusal
HOST_TOOLS    += $(DRACO_REFUSAL)
$(BUILD)/tests/tests/draco/draco_refusal.o: tests/draco/draco_refusal.cc
	@mkdir -p $(@D)
	$(CXX) -std=c++17 -Wall -Wextra -Werror -Isdk/include -O1 -g $(SAN_FLAGS) -MMD -MP -c $< -o $@
$(DRACO_REFUSAL): $(BUILD)/tests/tests/draco/draco_refusal.o $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CXX) $(SAN_FLAGS) -o $@ $^ -ldraco -pthread

.PHONY: draco-refusal
draco-refusal: $(DRACO_REFUSAL) $(DRACO_GEN)
	@sh tests/draco/refusal.sh $(BUILD)
TEST_STEPS += draco-refusal

# the attribute set of issue 25 (normals from assimp, colours synthesised)
HOST_TOOLS     += $(DRACO_GEN_ATTR)
$(DRACO_GEN_ATTR): $(BUILD)/host/tests/draco/gen_attr_meshes.o
	@mkdir -p $(@D)
	$(CXX) -o $@ $^ -lassimp
