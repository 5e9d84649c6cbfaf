/* SPDX-License-Identifier: MIT */
/* Deflate decompression (RFC 1951) of a zip entry, for the 3MF reader (io/threemf.c). */
#ifndef TTD_IO_INFLATE_H
#define TTD_IO_INFLATE_H

#include <stddef.h>

/// Decompresses the raw deflate stream in[0..n) into out (cap bytes): 0 with *out_len the bytes
/// written, or -1 for malformed data or an output longer than cap.
int ttd_io_inflate(const unsigned char *in, size_t n, unsigned char *out, size_t cap, size_t *out_len);

#endif
