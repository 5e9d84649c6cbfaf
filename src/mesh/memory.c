/* SPDX-License-Identifier: MIT */
/* ttd_big_alloc (mesh/memory.h). */
#define _DEFAULT_SOURCE /* MADV_HUGEPAGE */
#include "mesh/memory.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#if defined(__linux__)
#include <sys/mman.h>
#endif

/* Arrays this large go on huge pages: below it the rounding up to 2 MiB would waste more than
 * the faults cost. */
#define TTD_HUGE_MIN ((size_t)4 << 20)
#define TTD_HUGE_PAGE ((size_t)2 << 20)

void *ttd_big_alloc(size_t size)
{
    if (size == 0 || size > SIZE_MAX - TTD_HUGE_PAGE)
        return NULL;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (size >= TTD_HUGE_MIN) {
        const size_t rounded = (size + TTD_HUGE_PAGE - 1) / TTD_HUGE_PAGE * TTD_HUGE_PAGE;
        void *p = NULL;
        if (posix_memalign(&p, TTD_HUGE_PAGE, rounded) != 0)
            return NULL;
        (void)madvise(p, rounded, MADV_HUGEPAGE); /* a hint: refused, the pages are small */
        return p;
    }
#endif
    return aligned_alloc(64, (size + 63) / 64 * 64);
}

int ttd_big_grow(void **p, size_t used, size_t size)
{
    void *q = ttd_big_alloc(size);
    if (q == NULL)
        return -1;
    if (*p != NULL)
        memcpy(q, *p, used);
    free(*p);
    *p = q;
    return 0;
}
