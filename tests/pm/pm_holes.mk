# tests/pm/pm_holes.mk — holes close (issue 23): a sphere with 40 small holes
# simplifies to a handful of vertices when no error limit stops it (each
# hole left open would keep three), and the 106-hole elephant of CGAL's data
# set reaches its 2% / 100-vertex base with the default options; every level
# valid and the client's levels identical to the server's (pm_check).
TEST_STEPS += test-pm-holes
.PHONY: test-pm-holes
test-pm-holes: $(PM_CHECK) $(BUILD)/data/cgal/elephant-with-holes.off
	@st=0; $(PM_CHECK) --gen holes --batch 7 --max-error 0 --base-max 20 || st=1; \
	$(PM_CHECK) --gen holes --batch 30 || st=1; \
	$(PM_CHECK) $(BUILD)/data/cgal/elephant-with-holes.off --batch 60 --base-max 100 || st=1; exit $$st
