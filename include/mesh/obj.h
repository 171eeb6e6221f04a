/*
 * obj.h - reading Wavefront OBJ files into a triangle mesh (ch. 7): the
 * statements v, vt, vn, f, g, o, usemtl; polygons fanned into triangles;
 * errors with file:line:col; bounded memory and time on any input (fuzzed:
 * fuzz/fuzz_obj.c, `make fuzz-obj`).
 * Tests: tests/mesh/test_obj.c (inputs in tests/data/obj/)
 *
 * What is read (everything else as listed):
 *   v x y z [w] [r g b]  a position; w and vertex colours are ignored
 *   vt s [t [w]]         a texture coordinate (t defaults to 0)
 *   vn x y z             a normal (normalised; a zero vector is "none")
 *   f a b c ...          a polygon of >= 3 vertices, each "v", "v/vt",
 *                        "v//vn" or "v/vt/vn"; 1-based indices into what
 *                        was defined above the line, negative ones counted
 *                        back from the last (-1 = the latest); fanned as
 *                        (a b c) (a c d) ..., right for convex polygons
 *   usemtl name          the material slot of the faces below (obj_t)
 *   g names, o name      the group of the faces below (obj_t)
 *   mtllib, s            skipped silently: svet takes materials from the
 *                        scene file and smoothing from vn
 *   l, p, and any other  skipped with a warning (lines and points have no
 *                        surface; curves and surfaces are not supported)
 * A UTF-8 byte-order mark at the start of the file is skipped (text.h).
 * '#' starts a comment; a backslash at the end of a line joins the next
 * line to it; \n and \r\n line ends both work; numbers are decimal (C
 * locale), and NaN, infinities and values beyond the range of real are
 * errors, as are index 0, an index beyond what is defined, and a face of
 * fewer than 3 vertices.
 */
#ifndef SVET_OBJ_H
#define SVET_OBJ_H

#include <stddef.h>
#include <stdint.h>
#include "materials/cobject.h"
#include "core/error.h"

#define OBJ_MAX_FILE_BYTES ((size_t)1 << 30) /* 1 GiB */
#define OBJ_MAX_NAME 1024                     /* bytes of a usemtl/g name */
#define OBJ_MAX_NAMES (1 << 20)               /* distinct materials, groups */
#define OBJ_MAX_WARNINGS 8                    /* warning messages kept */

/* Limits a caller may lower (a fuzzer, a service reading untrusted
 * files); obj_limits_default() gives the mesh limits of mesh.h. */
typedef struct {
    long max_vertices;  /* distinct v/vt/vn combinations used by faces */
    long max_triangles; /* after fanning */
    long max_elements;  /* v + vt + vn statements */
} obj_limits_t;

void obj_limits_default(obj_limits_t *lim);

/* A read OBJ file. */
typedef struct {
    COBJECT *mesh;      /* all faces as one mesh (mesh.h); its triangles are
                           in file order. Owned: obj_free() frees it unless
                           the caller took it (then set mesh = NULL) */
    int nmaterials;     /* usemtl names, in order of first use: triangle i
                           has slot mesh_get(mesh)->slot[i] (-1 before the
                           first usemtl); slot is NULL when the file has no
                           usemtl. mesh_new_subset() splits by slot */
    char **materials;
    int ngroups;        /* g/o names ("g a b" gives "a b"), in order of
                           first use; tri_group[i] is the group of triangle
                           i, -1 before the first g/o; NULL if none */
    char **groups;
    int32_t *tri_group;
    long nwarnings;     /* warnings issued; the first OBJ_MAX_WARNINGS are
                           kept as "file:line:col: message" */
    char warnings[OBJ_MAX_WARNINGS][SVET_ERROR_LEN];
} obj_t;

/* Read the OBJ file at path into o (zeroed first). Fails with SVET_ERR_IO
 * when the file cannot be read or is larger than OBJ_MAX_FILE_BYTES,
 * SVET_ERR_PARSE on a malformed line, SVET_ERR_RANGE on a value out of its
 * domain (NaN, infinite, an index out of range) or a limit exceeded,
 * SVET_ERR_NOMEM; the message starts with "path:line:col: ". On failure o
 * holds nothing to free (obj_free() is still safe). lim may be NULL. */
svet_status obj_read(const char *path, const obj_limits_t *lim, obj_t *o,
                     svet_error *err);

/* The same for the len bytes at text (need not end in NUL, may contain
 * NUL bytes), named `name` in messages. */
svet_status obj_parse(const char *name, const char *text, size_t len,
                      const obj_limits_t *lim, obj_t *o, svet_error *err);

/* Free what o holds and zero it. NULL is allowed. */
void obj_free(obj_t *o);

#endif
