# bench/bench.mk — benchmark steps are added by each part's fragment (BENCH_STEPS).
