/* cluster_single.c — cluster.h for a build without MPI: one process, the
 * work run here (work.c). Linked into lumo-bake when Open MPI is absent. */
#include <stdio.h>
#include "bake/cluster.h"

lumo_status srv_cluster_init(srv_cluster *c, int *argc, char ***argv, char *err, size_t errlen)
{
    (void)argc, (void)argv;
    *c = (srv_cluster){.rank = 0, .size = 1, .mpi = 0};
    /* N copies that each bake everything and write the same file would
     * race; say why instead. */
    if (srv_cluster_launched() > 1) {
        snprintf(err, errlen, "started by an MPI launcher with %d ranks, but this lumo-bake was built "
                 "without MPI (install libopenmpi-dev and rebuild)", srv_cluster_launched());
        return LUMO_ERR_UNSUPPORTED;
    }
    return LUMO_OK;
}

lumo_status srv_cluster_run(const srv_cluster *c, const srv_work *w, const char *ckpt_dir, uint8_t *out,
                            srv_work_report *rep, char *err, size_t errlen)
{
    (void)c;
    return srv_work_run_local(w, ckpt_dir, out, rep, err, errlen);
}

int srv_cluster_end(srv_cluster *c, int status)
{
    (void)c;
    return status;
}
