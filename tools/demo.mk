# tools/demo.mk — make demo (issue 6): tools/demo.sh bakes the default scene,
# renders it on the client with and without the IVG, path-traces the
# server's reference and places the three side by side with the error
# printed; the progressive meshes at three levels of detail side by side
# (lod.png); plus an orbit of PNG frames. Output in build/demo/; settings
# (GRID, SPP, REF_SPP, SIZE, FRAMES, LODS) from the environment.
.PHONY: demo
demo: $(BUILD)/.setup-done all
	@sh tools/demo.sh $(BUILD)
