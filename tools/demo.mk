# tools/demo.mk — make demo: tools/demo.sh bakes the default scene, serves
# it with lumo-server on loopback behind an emulated slow link, streams it to
# lumo-client (interleaved, geometry first, lighting first), and writes
# progress.png (the scene after growing amounts of bytes), error-vs-bytes.png
# and side-by-side.png against the path-traced reference. Output in
# build/demo/; settings (GRID, SPP, REF_SPP, SIZE, RATE, LATENCY, FRAMES_AT, SHADOWS)
# from the environment.
.PHONY: demo
demo: $(BUILD)/.setup-done all
	@sh tools/demo.sh $(BUILD)
