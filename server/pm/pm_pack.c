/* pm_pack.c — one mesh into a package as a progressive stream (PMSH chunk):
 * the call lumo-bake makes instead of writing the raw MESH chunk. */
#include <stdio.h>
#include <stdlib.h>
#include "lumo/package.h"
#include "package/package_write.h"
#include "pm/pm_stream.h"

lumo_status srv_pm_pack(struct srv_pkg_writer *w, const float *xyz, const uint8_t *albedo,
                        uint32_t nv, const uint32_t *tris, uint32_t nf,
                        const srv_pm_stream_options *o, char *err, size_t errlen)
{
    srv_pm pm;
    uint8_t *s = NULL;
    size_t len = 0;
    lumo_status rc = srv_pm_build_albedo(xyz, albedo, nv, tris, nf, NULL, &pm);
    if (rc) {
        snprintf(err, errlen, "progressive mesh: cannot simplify (bad index or out of memory)");
        return rc;
    }
    rc = srv_pm_stream_build(&pm, o, &s, &len, NULL, NULL);
    if (rc)
        snprintf(err, errlen, "progressive mesh: cannot encode the stream");
    else if ((rc = srv_pkgw_add(w, LUMO_PKG_PMSH, s, len)))
        snprintf(err, errlen, "progressive mesh: out of memory");
    free(s);
    srv_pm_free(&pm);
    return rc;
}
