/* pm_bench.c — placeholder until the benchmark lands. */
#include <stdio.h>
int lumo_pm_bench_main(int argc, char **argv);
int lumo_pm_bench_main(int argc, char **argv)
{
    (void)argc, (void)argv;
    fprintf(stderr, "lumo-pm bench: not yet\n");
    return 1;
}
