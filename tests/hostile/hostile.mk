# tests/hostile/hostile.mk — models, bakes and packages from hostile hands
# (issue 24, part B): the generated-corpus suite tests/hostile/hostile.sh in
# `make test`, the model front end's unit test, and the two host-side fuzz
# targets (lumo's model checks, the scene-file parser) whose sources sit
# with the others in tests/fuzz/ but link server code, so they get their
# own rules here (the top Makefile's fuzz-smoke and fuzz-long run them
# with every other target).

# ---- fuzz targets over server code -----------------------------------------------
FUZZ_HOST_CFLAGS := -std=c11 -D_GNU_SOURCE -g -O1 $(CLIENT_INC) -Iserver -Itools/lib/include \
                    -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
# lumo's model checks: one file per format family (model_check.c: OBJ,
# PLY, OFF; stl_check.c; gltf_check.c, over jansson).
MODEL_CHECK_SRCS := server/scene/model_check.c server/scene/stl_check.c server/scene/gltf_check.c
FUZZ_SCENE_SRCS  := server/scene/scene_file.c server/scene/scene.c server/scene/light_parse.c \
                    server/scene/shapes.c server/scene/camera.c server/scene/import.c \
                    server/scene/import_io.c $(MODEL_CHECK_SRCS)

$(BUILD)/fuzz/bin/fuzz_model_check: tests/fuzz/fuzz_model_check.c $(MODEL_CHECK_SRCS) \
                                    server/scene/model_check.h server/scene/model_check_internal.h
	@mkdir -p $(@D) $(BUILD)/fuzz/corpus/fuzz_model_check
	$(CLANG) $(FUZZ_HOST_CFLAGS) -o $@ tests/fuzz/fuzz_model_check.c $(MODEL_CHECK_SRCS) -ljansson -lm

$(BUILD)/fuzz/bin/fuzz_light_parse: tests/fuzz/fuzz_light_parse.c server/scene/light_parse.c server/scene/scene.h
	@mkdir -p $(@D) $(BUILD)/fuzz/corpus/fuzz_light_parse
	$(CLANG) $(FUZZ_HOST_CFLAGS) -o $@ tests/fuzz/fuzz_light_parse.c server/scene/light_parse.c -lm

# The motion parser (motion lines, lumo-server --dynamic's move commands).
$(BUILD)/fuzz/bin/fuzz_motion: tests/fuzz/fuzz_motion.c server/vsl/vsl_motion.c server/scene/scene.c \
                               server/scene/camera.c $(wildcard server/scene/*.h) $(BUILD)/fuzz/liblumo.a
	@mkdir -p $(@D) $(BUILD)/fuzz/corpus/fuzz_motion
	$(CLANG) $(FUZZ_HOST_CFLAGS) -o $@ tests/fuzz/fuzz_motion.c server/vsl/vsl_motion.c server/scene/scene.c \
	    server/scene/camera.c $(BUILD)/fuzz/liblumo.a -lm

# The scene room calls the SDK (the camera fit): the fuzz build of the
# client code (build/fuzz/liblumo.a, the top Makefile's).
$(BUILD)/fuzz/bin/fuzz_scene_file: tests/fuzz/fuzz_scene_file.c $(FUZZ_SCENE_SRCS) $(wildcard server/scene/*.h) \
                                   $(BUILD)/fuzz/liblumo.a
	@mkdir -p $(@D) $(BUILD)/fuzz/corpus/fuzz_scene_file
	$(CLANG) $(FUZZ_HOST_CFLAGS) -o $@ tests/fuzz/fuzz_scene_file.c $(FUZZ_SCENE_SRCS) \
	    $(BUILD)/fuzz/liblumo.a -lassimp -ljansson -lm

# ---- the generated corpus ------------------------------------------------------------
# tests/hostile/gen_hostile writes every case (models, scene files, packages
# rewritten from a real bake with valid checksums) into a fresh directory
# at test time, through corpus.c as gen_formats does; hostile.sh runs each
# under a memory and time limit.
HOSTILE_GEN := $(BUILD)/tests/bin/gen_hostile

$(HOSTILE_GEN): $(BUILD)/tests/tests/hostile/gen_hostile.o $(BUILD)/tests/tests/hostile/corpus.o $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ -lm

# tests/hostile/gen_formats adds STL, glTF, GLB, the formats refused by
# name and the scene files' lights (round three) to the same corpus.
HOSTILE_GEN_FORMATS := $(BUILD)/tests/bin/gen_formats

$(HOSTILE_GEN_FORMATS): $(BUILD)/tests/tests/hostile/gen_formats.o $(BUILD)/tests/tests/hostile/corpus.o \
                        $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^ -lz

TEST_STEPS += test-hostile-input
.PHONY: test-hostile-input
test-hostile-input: $(HOSTILE_GEN) $(HOSTILE_GEN_FORMATS) $(BIN)/lumo-bake $(BIN)/lumo-pm $(BIN)/lumo-render \
                    $(BIN)/lumo-inspect $(BIN)/lumo-server $(BIN)/lumo-client $(BIN)/lumo-compare
	@sh tests/hostile/hostile.sh $(BIN) $(HOSTILE_GEN) $(BUILD)/tests/hostile-input $(HOSTILE_GEN_FORMATS)
