# bench/pm_quality.mk — `make bench-pm-quality` (issue 23): lumo's
# progressive-mesh levels against meshoptimizer (benchmark-only dependency,
# Debian libmeshoptimizer-dev) on scanned, CAD, holed and multi-component
# meshes. Writes build/bench/sections/61-pm-quality.md.
PM_QUALITY      := $(BIN)/pm-quality
PM_QUALITY_OBJS := $(BUILD)/host/bench/pm_quality.o $(BUILD)/host/bench/pm_surface.o
HOST_TOOLS      += $(PM_QUALITY)

$(PM_QUALITY): $(PM_QUALITY_OBJS) $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ -lmeshoptimizer $(SERVER_LIBS)

# Meshes lumo lacks, from CGAL's data set (Debian libcgal-demo): fandisk
# (CAD, sharp creases), mech-holes-shark (CAD with holes), elephant-with-holes
# (organic, open), blobby_3cc (three components).
CGAL_DATA   := /usr/share/doc/libcgal-dev/data.tar.gz
# camel, cow and homer (scanned, closed) are held out: never used to tune the
# simplifier's constants, they check that its gains are not fitted to the set.
CGAL_MESHES := fandisk mech-holes-shark elephant-with-holes blobby_3cc camel cow homer
$(BUILD)/data/cgal/%.off: $(CGAL_DATA)
	@mkdir -p $(@D)
	tar -xzOf $(CGAL_DATA) data/meshes/$*.off > $@.tmp && mv $@.tmp $@

PM_QUALITY_SET := scanned:$(BUILD)/data/models/bunny.obj scanned:$(BUILD)/data/models/dragon_11k.ply \
                  scanned:$(BUILD)/data/models/dragon_48k.ply CAD:$(BUILD)/data/cgal/fandisk.off \
                  CAD-holed:$(BUILD)/data/cgal/mech-holes-shark.off holed:$(BUILD)/data/cgal/elephant-with-holes.off \
                  components:$(BUILD)/data/cgal/blobby_3cc.off held-out:$(BUILD)/data/cgal/camel.off \
                  held-out:$(BUILD)/data/cgal/cow.off held-out:$(BUILD)/data/cgal/homer.off

BENCH_STEPS += bench-pm-quality
.PHONY: bench-pm-quality
bench-pm-quality: $(PM_QUALITY) $(patsubst %,$(BUILD)/data/cgal/%.off,$(CGAL_MESHES))
	@mkdir -p $(BUILD)/bench/sections
	$(PM_QUALITY) --out $(BUILD)/bench/sections/61-pm-quality.md \
	    --cmd "make bench-pm-quality ($(PM_QUALITY) $(PM_QUALITY_SET))" $(PM_QUALITY_SET)
