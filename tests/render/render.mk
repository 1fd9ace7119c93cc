# tests/render/render.mk — rendering tests beyond the unit tests: the three
# backends against each other, and the client against the path tracer.
.PHONY: raster-cross-backend raster-truth raster-cli
TEST_STEPS += raster-cross-backend raster-truth raster-cli

raster-cross-backend: $(BIN)/lumo-render $(BIN)/lumo-compare $(BIN)/lumo-bake
	sh tests/render/cross_backend.sh $(BUILD)

raster-truth: $(BIN)/lumo-render $(BIN)/lumo-compare $(BIN)/lumo-bake
	sh tests/render/truth.sh $(BUILD)

raster-cli: $(BIN)/lumo-render $(BIN)/lumo-compare $(BIN)/lumo-bake
	sh tests/render/cli.sh $(BUILD)
