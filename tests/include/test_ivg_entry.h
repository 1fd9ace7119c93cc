/*
 * test_ivg_entry.h — tests read a grid's entries through pointers; the grid
 * keeps them packed (lumo_ivg_entry_get unpacks one), so IVG_ENTRY(g, v, a)
 * unpacks into a compound literal of the enclosing block and gives its
 * address, or NULL when lumo_ivg_entry_get refuses (out of range).
 */
#ifndef TEST_IVG_ENTRY_H
#define TEST_IVG_ENTRY_H

#include <string.h>
#include "lumo/ivg.h"

static inline const lumo_ivg_entry *test_ivg_entry(const lumo_ivg *g, uint32_t v, int a, lumo_ivg_entry *room)
{
    return lumo_ivg_entry_get(g, v, (lumo_ivg_axis)a, room) == LUMO_OK ? room : NULL;
}

#define IVG_ENTRY(g, v, a) test_ivg_entry((g), (v), (int)(a), &(lumo_ivg_entry){{0, 0, 0}, {0, 0, 0}, 0})

/* Whether two grids hold the same six entries at vertex v (and w). */
static inline int test_ivg_vertex_equal(const lumo_ivg *a, uint32_t v, const lumo_ivg *b, uint32_t w)
{
    int h;

    for (h = 0; h < LUMO_IVG_AXES; h++) {
        lumo_ivg_entry x, y;
        if (lumo_ivg_entry_get(a, v, (lumo_ivg_axis)h, &x) || lumo_ivg_entry_get(b, w, (lumo_ivg_axis)h, &y))
            return 0;
        if (memcmp(&x, &y, sizeof x) != 0)
            return 0;
    }
    return 1;
}

#endif /* TEST_IVG_ENTRY_H */
