/* The Moebius strip (generate.h): `segments` quads around a circle of radius
 * 1, the strip (half-width 0.25) turning half a revolution on the way round.
 * Position s has vertices 2s and 2s+1 on either edge of the strip; quad s is
 * (2s, 2s+2, 2s+3, 2s+1). The last quad closes the strip with the twist,
 * (2s, 1, 0, 2s+1), so it crosses edge 0-1 in the same direction as quad 0:
 * every other interior edge is crossed once each way. */
#include <math.h>
#include <string.h>

#include "meshtopo/generate.h"

mt_status mt_gen_moebius(uint32_t segments, mt_face_list *out)
{
    if (!out) return MT_ERR_INVALID_ARG;
    memset(out, 0, sizeof *out);
    if (segments < 3) return MT_ERR_INVALID_ARG; /* segments >= 3 */
    if (2 * (uint64_t)segments > UINT32_MAX) return MT_ERR_TOO_LARGE;
    mt_status status =
        mt_face_list_alloc(out, 2 * segments, segments, 4 * (uint64_t)segments, NULL);
    if (status != MT_OK) return status;
    const double radius = 1.0, half_width = 0.25;
    const double two_pi = 6.283185307179586476925286766559;
    for (uint32_t s = 0; s < segments; s++) {
        double theta = two_pi * s / segments;
        /* across the strip: the radial direction turned by theta/2 towards +z */
        double across[3] = {cos(theta / 2) * cos(theta), cos(theta / 2) * sin(theta),
                            sin(theta / 2)};
        double centre[3] = {radius * cos(theta), radius * sin(theta), 0.0};
        for (int k = 0; k < 3; k++) {
            out->positions[6 * (size_t)s + k] = centre[k] + half_width * across[k];
            out->positions[6 * (size_t)s + 3 + k] = centre[k] - half_width * across[k];
        }
    }
    for (uint32_t s = 0; s < segments; s++) {
        uint32_t *q = out->face_indices + 4 * (size_t)s;
        bool last = s + 1 == segments;
        q[0] = 2 * s;
        q[1] = last ? 1 : 2 * s + 2; /* past the seam the strip's two edges swap */
        q[2] = last ? 0 : 2 * s + 3;
        q[3] = 2 * s + 1;
        out->face_sizes[s] = 4;
    }
    return MT_OK;
}
