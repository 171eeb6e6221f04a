/*
 * text.h - what every reader of a text file shares (scene files, OBJ
 * files, CSV tables): the UTF-8 byte-order mark some editors write at the
 * start of a file. U+FEFF there is a signature, not content (The Unicode
 * Standard, sec. 23.8), so each reader skips it; read as text it would
 * glue itself to the first word ("\xEF\xBB\xBFcamera", "\xEF\xBB\xBFv").
 * Tests: tests/core/test_text.c
 */
#ifndef SVET_TEXT_H
#define SVET_TEXT_H

#include <stddef.h>

/* The bytes of the UTF-8 byte-order mark, EF BB BF. */
#define TEXT_BOM "\xEF\xBB\xBF"
#define TEXT_BOM_LEN 3

/* How many bytes of the n at s are a byte-order mark at their start: 3 or
 * 0. s may be NULL when n is 0. This function can't fail. */
static inline size_t text_bom_length(const char *s, size_t n)
{
    return n >= TEXT_BOM_LEN && (unsigned char)s[0] == 0xEF &&
                   (unsigned char)s[1] == 0xBB && (unsigned char)s[2] == 0xBF
               ? TEXT_BOM_LEN
               : 0;
}

#endif
