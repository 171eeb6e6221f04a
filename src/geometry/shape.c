/*
 * shape.c - what the primitives of app. D share: allocation, input
 * checks, scale-safe cross products and the PATHPOINT frame (app. A).
 * Tests: tests/geometry/test_shape.c
 */
#include "geometry/shape.h"
#include "core/frame.h"

#include <stdalign.h>
#include <stdlib.h>

/* The shape data starts at the first offset after the COBJECT that is
 * aligned for any type. */
#define SHAPE_OFFSET                                                          \
    ((sizeof(COBJECT) + alignof(max_align_t) - 1) /                           \
     alignof(max_align_t) * alignof(max_align_t))

COBJECT *shape_alloc(const cobject_ops *ops, size_t size, svet_error *err)
{
    if (size > (size_t)-1 - SHAPE_OFFSET) {
        svet_error_set(err, SVET_ERR_NOMEM, "%s: shape size overflows",
                       ops->name);
        return NULL;
    }
    unsigned char *block = calloc(1, SHAPE_OFFSET + size);
    if (!block) {
        svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", ops->name);
        return NULL;
    }
    COBJECT *obj = (COBJECT *)(void *)block;
    cobject_init(obj, ops, size ? block + SHAPE_OFFSET : NULL);
    return obj;
}

svet_status shape_check_finite(const char *shape, const char *what,
                               const VECTOR3 p, svet_error *err)
{
    if (vec_is_finite(p))
        return SVET_OK;
    return svet_error_set(err, SVET_ERR_RANGE,
                          "%s: %s (%g, %g, %g) is not finite", shape, what,
                          (double)p[X], (double)p[Y], (double)p[Z]);
}

int shape_scale_exponent(VECTOR3 s, const VECTOR3 a)
{
    real m = shape_max_abs(a);
    if (m == 0 || !isfinite(m)) {
        vec_copy(s, a);
        return 0;
    }
    /* the bits' exponent and one exact product each: no libm call */
    int e = real_ilogb(m);
    for (int i = 0; i < 3; i++)
        s[i] = real_ldexp(a[i], -e);
    return e;
}

bool shape_unit_cross(VECTOR3 n, const VECTOR3 a, const VECTOR3 b)
{
    VECTOR3 sa, sb, c;
    shape_scale_exponent(sa, a);
    shape_scale_exponent(sb, b);
    VVECTOR3(c, sa, sb);
    return vec_normalize(n, c) > 0;
}

real shape_cross_length(const VECTOR3 a, const VECTOR3 b)
{
    VECTOR3 sa, sb, c;
    int ea = shape_scale_exponent(sa, a);
    int eb = shape_scale_exponent(sb, b);
    VVECTOR3(c, sa, sb);
    return real_ldexp(vec_length(c), ea + eb);
}

void shape_frame(VECTOR3 u, VECTOR3 v, const VECTOR3 n, const VECTOR3 dpds)
{
    /* Gram-Schmidt: t = dpds - (dpds . n) n, then v = unit(n x t) and
     * u = v x n, which is unit and perpendicular to n and v to rounding
     * even when t was short (dpds nearly along n). */
    VECTOR3 s, t, w;
    shape_scale_exponent(s, dpds);
    vec_add_scaled(t, s, -SVECTOR3(s, n), n);
    VVECTOR3(w, n, t);
    if (vec_normalize(v, w) == 0) {
        frame_from_normal(u, v, n);
        return;
    }
    VVECTOR3(u, v, n);
}

void shape_normal_change(const VECTOR3 g, const VECTOR3 dg, const VECTOR3 n,
                         VECTOR3 dn)
{
    real gn = SVECTOR3(g, n), k = SVECTOR3(dg, n);
    for (int i = 0; i < 3; i++)
        dn[i] = (dg[i] - k * n[i]) / gn;
    if (gn == 0 || !vec_is_finite(dn))
        vec_set(dn, 0, 0, 0);
}
