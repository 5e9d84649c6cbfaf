/* Links an installed ttd and checks one known distance: two unit triangles in parallel
 * planes 2 apart, one above the other, are 2 apart. */
#include <stdio.h>
#include <ttd/ttd.h>

int main(void)
{
    const double s[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const double t[9] = {0, 0, 2, 1, 0, 2, 0, 1, 2};
    ttd_result_d r;
    ttd_status st = ttd_distance_d(NULL, s, t, &r);
    if (st != TTD_OK || r.distance != 2.0) {
        fprintf(stderr, "consumer: status %d (%s), distance %.17g, expected 2\n", (int)st,
                ttd_status_string(st), r.distance);
        return 1;
    }
    printf("consumer: ttd %s, distance %.17g\n", ttd_version_string(), r.distance);
    return 0;
}
