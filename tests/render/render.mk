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

# Progressive meshes in lumo-render (issue 5): pm vs raw package (mean
# Delta E <= 1), --lod levels, a damaged stream (tests/render/lod.sh).
.PHONY: raster-lod
TEST_STEPS += raster-lod
raster-lod: $(BIN)/lumo-render $(BIN)/lumo-compare $(BIN)/lumo-bake $(BIN)/lumo-inspect
	sh tests/render/lod.sh $(BUILD)

# A scene without a camera is framed: random models baked with no camera,
# drawn by lumo-render (package camera, --fit) and lumo-client --fit
# (tests/render/fit.sh; tests/render/framed.c checks each picture).
FRAMED := $(BUILD)/tests/bin/framed
$(FRAMED): $(BUILD)/host/tests/render/framed.o $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lpng -lm
.PHONY: raster-fit
TEST_STEPS += raster-fit
raster-fit: $(BIN)/lumo-render $(BIN)/lumo-bake $(BIN)/lumo-client $(BIN)/lumo-server $(FRAMED)
	sh tests/render/fit.sh $(BUILD) $(BUILD)/tests/bin

# lumo-client --shadows N: streamed and drawn with shadow maps, soft == lumo-render,
# GL ~ soft, the shadows show (tests/render/client_shadows.sh).
.PHONY: raster-client-shadows
TEST_STEPS += raster-client-shadows
raster-client-shadows: $(BIN)/lumo-render $(BIN)/lumo-compare $(BIN)/lumo-bake $(BIN)/lumo-client $(BIN)/lumo-server
	sh tests/render/client_shadows.sh $(BUILD)
