# bench/model_check.mk — `make bench-model-check`: what lumo's model checks
# (server/scene/model_check.h, issue 24) cost against assimp's import of the
# same file (bench/model_check_bench.c), for the models of build/data and
# assimp's exports of them as binary STL, glTF and GLB.
MODEL_CHECK_BENCH  := $(BUILD)/host/bench/lumo-bench-model-check
MODEL_CHECK_MODELS := $(BUILD)/data/models/bunny.obj $(BUILD)/data/models/dragon_48k.ply \
                      $(BUILD)/data/models/dragon_871k.ply

$(MODEL_CHECK_BENCH): $(BUILD)/host/bench/model_check_bench.o $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a \
                      $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $< $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a $(SERVER_LIBS)

BENCH_STEPS += bench-model-check
.PHONY: bench-model-check
bench-model-check: $(MODEL_CHECK_BENCH)
	@mkdir -p $(BUILD)/bench/model-check $(BUILD)/bench/sections
	@{ echo "## Model checks before assimp (issue 24)"; echo; \
	   echo "Command: \`make bench-model-check\` ($(MODEL_CHECK_BENCH) 5 TMP $(notdir $(MODEL_CHECK_MODELS))):"; \
	   echo "lumo's checks of each file (srv_model_check_file) against assimp's import of it with lumo's"; \
	   echo "flags, medians of 5 runs on a shared host; the STL, glTF and GLB files are assimp's exports of"; \
	   echo "the model above them."; echo; \
	   $(MODEL_CHECK_BENCH) 5 $(BUILD)/bench/model-check $(MODEL_CHECK_MODELS); } \
	    >$(BUILD)/bench/sections/95-model-check.md
	@cat $(BUILD)/bench/sections/95-model-check.md
