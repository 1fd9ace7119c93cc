# tools/prt-demo/prt-demo.mk — `make demo-prt` (issue 19, docs/prt.md): the
# dragon baked with PRT four ways (uncompressed: one cluster holding every
# component; CPCA; geometry coherence; super-clusters), relit by the soft
# rasterizer under a sky projected on SH, side by side with their errors
# (lumo-compare), the clusters and passes in false colour, a turning sky.
# Output: $(BUILD)/demo-prt/contact.png.
HOST_TOOLS += $(BIN)/prt-demo

$(BIN)/prt-demo: $(BUILD)/host/tools/prt-demo/prt_demo.o $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lpng -lm

PRT_DEMO_MODEL ?= $(BUILD)/data/models/dragon_48k.ply

.PHONY: demo-prt
demo-prt: $(BIN)/prt-demo $(BIN)/lumo-bake $(BIN)/lumo-render $(BIN)/lumo-compare
	@sh tools/prt-demo/demo_prt.sh $(BIN) $(BUILD)/demo-prt $(PRT_DEMO_MODEL)
