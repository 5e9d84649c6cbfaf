/* SPDX-License-Identifier: MIT */
/* Input of `ttd dist` (and the poses of `ttd mesh`): a line reader with bounded memory, and the parser of one line. Kept
 * apart from the command so that a fuzz target can drive the parser alone. */
#ifndef TTD_CLI_PARSE_H
#define TTD_CLI_PARSE_H

#include <stddef.h>
#include <stdio.h>

/// Longest accepted line in bytes (without its newline); 18 numbers at full precision need
/// about 450, so this leaves room for wide padding and long comments.
#define TTD_CLI_MAX_LINE 4096

/// Reads lines of any length from a FILE in bounded memory: a line longer than
/// TTD_CLI_MAX_LINE is reported as overlong (its start kept, the rest skipped), unless all it
/// has beyond the limit is blanks (padding, or a line of blanks alone), which are dropped. A UTF-8
/// byte-order mark at the start of the input is dropped (and does not count to the limit).
typedef struct ttd_line_reader {
    FILE *f;
    size_t pos, len;                       ///< unread bytes of buf are [pos, len)
    int eof;
    int error;                             ///< errno of a read error (ferror), else 0
    unsigned long long line_no;            ///< number of the line last returned, from 1
    char buf[1 << 16];
    char line[TTD_CLI_MAX_LINE + 4];       ///< the line last returned, NUL-terminated (+3: a first line's byte-order mark)
} ttd_line_reader;

/// Starts reading f.
void ttd_reader_init(ttd_line_reader *r, FILE *f);
/// Next line (without "\n" or "\r\n") in r->line, its length in *len (NUL bytes may occur
/// inside); *overlong set when the line was cut. Returns 0 at the end of input (a missing final
/// newline still gives the last line), 1 otherwise.
int ttd_reader_next(ttd_line_reader *r, size_t *len, int *overlong);

/// What one line holds.
typedef enum ttd_line_kind {
    TTD_LINE_SKIP = 0,  ///< blank, or a comment (first non-blank character '#')
    TTD_LINE_PAIR = 1,  ///< the numbers asked for (18 for a pair), all finite, in out
    TTD_LINE_ERROR = 2  ///< anything else; err says what
} ttd_line_kind;

/// Parses line[0..len) (line[len] must be '\0'): 18 numbers separated by blanks (space, tab,
/// CR, VT, FF), in strtod's syntax, all finite, optionally followed by a comment ('#' to the
/// end of the line, with or without a blank before it). With as_float each number is parsed
/// by strtof (rounded once, decimal to float; beyond float range is an error) and out holds the
/// floats, exactly. On TTD_LINE_ERROR err holds a message.
ttd_line_kind ttd_parse_pair_line(const char *line, size_t len, int as_float, double out[18],
                                  char *err, size_t errsize);

/// ttd_parse_pair_line for want numbers (1..) instead of 18, into out[0..want): the same
/// syntax, limits and messages; TTD_LINE_PAIR when the line holds exactly want numbers. Used
/// for the poses of `ttd mesh` (12 numbers a line).
ttd_line_kind ttd_parse_numbers_line(const char *line, size_t len, int as_float, int want, double *out,
                                     char *err, size_t errsize);

/// A pose of `ttd mesh`: 12 numbers (the 3x4 matrix [R | t] row by row) or 16 (the 4x4
/// homogeneous matrix row by row, whose bottom row must be exactly 0 0 0 1), with the syntax
/// of ttd_parse_numbers_line; out receives the 12 numbers of [R | t]. Whether R is a rotation
/// is the caller's check.
ttd_line_kind ttd_parse_pose_line(const char *line, size_t len, int as_float, double out[12], char *err,
                                  size_t errsize);

/// The pose in the line r last returned (len and overlong as ttd_reader_next gave them): an
/// overlong line that is not a comment is an error, anything else ttd_parse_pose_line's. The
/// reading of poses files (`ttd mesh --poses`) and motion files (`ttd scene --motion`).
ttd_line_kind ttd_read_pose_line(const ttd_line_reader *r, size_t len, int overlong, int as_float, double out[12],
                                 char *err, size_t errsize);

#endif /* TTD_CLI_PARSE_H */
