/*
 * cluster.h — running a srv_work (work.h) across the ranks of an MPI job
 * (`mpirun -np N lumo-bake ...`, docs/server.md "Bakes on a cluster"), the
 * cluster architecture seed 000 names as future work for precomputation.
 *
 * Rank 0 hands out chunks on demand (dynamic load balancing: grid vertices
 * inside solids and in open space cost very different amounts), computes
 * chunks itself meanwhile, collects every result, keeps the checkpoint and
 * alone writes the output. Each rank traces with its own threads. The
 * output is byte-identical to one process's for any rank count (work.h).
 *
 * Two implementations, one linked into lumo-bake (tools/lumo-bake/
 * lumo-bake.mk): server/bake/cluster/cluster_mpi.c when the build finds
 * Open MPI, cluster_single.c otherwise. Started without an MPI launcher,
 * both are one process of rank 0, exactly the bake of before.
 */
#ifndef SRV_CLUSTER_H
#define SRV_CLUSTER_H

#include <stdlib.h>
#include "bake/work.h"
#include "lumo/status.h"

typedef struct srv_cluster {
    int rank, size;   /* this process's rank, the number of ranks (1 without MPI) */
    int mpi;          /* MPI was initialised */
} srv_cluster;

/* 0 when not started by an MPI launcher, else the rank count it announced
 * in the environment (Open MPI's mpirun, Hydra, Slurm with PMI), or for a
 * PMIx launch that gives only the rank, a lower bound of it (rank + 1). */
static inline int srv_cluster_launched(void)
{
    const char *size = getenv("OMPI_COMM_WORLD_SIZE") ? getenv("OMPI_COMM_WORLD_SIZE") : getenv("PMI_SIZE");
    const char *rank = getenv("PMIX_RANK");
    if (size)
        return atoi(size) > 1 ? atoi(size) : 1;
    return rank ? (atoi(rank) > 0 ? atoi(rank) + 1 : 1) : 0;
}

/* Join the job: under a launcher, initialise MPI (threads: funnelled
 * through the main thread); otherwise be rank 0 of 1. LUMO_OK, or
 * LUMO_ERR_UNSUPPORTED with err set (started by mpirun with more than one
 * rank, but built without MPI; MPI failed to start). */
lumo_status srv_cluster_init(srv_cluster *c, int *argc, char ***argv, char *err, size_t errlen);

/* Every rank calls this with the same work (rank 0 checks each rank's key
 * and refuses a rank whose scene or options differ). On rank 0, out gets
 * all items * item_bytes bytes, rep the report, and ckpt_dir (NULL: none)
 * is resumed and extended; other ranks pass out NULL and get only their
 * status. LUMO_OK once every chunk arrived; otherwise an error with err
 * set, and the caller ends the job with srv_cluster_end(c, 1). */
lumo_status srv_cluster_run(const srv_cluster *c, const srv_work *w, const char *ckpt_dir, uint8_t *out,
                            srv_work_report *rep, char *err, size_t errlen);

/* Leave the job, returning status as the exit status: 0 waits (without
 * spinning a core) until rank 0 has written the output, then finalises;
 * non-zero aborts every rank (MPI_Abort), so a failed rank never leaves
 * the others waiting and never lets rank 0 write a partial result. */
int srv_cluster_end(srv_cluster *c, int status);

#endif
