/* The rule that splits mesh ids between the members of a cluster
 * (meshtopo/protocol.h): rendezvous hashing, a member's weight for an id
 * being XXH3 of the id seeded with XXH3 of the member's instance. */
#include <string.h>
#include <xxhash.h>

#include "meshtopo/protocol.h"

uint64_t mt_msgs_cluster_seed(const char *instance)
{
    return XXH3_64bits(instance, strlen(instance));
}

size_t mt_msgs_cluster_owner(const uint64_t *seeds, size_t num_members, const char *mesh_id)
{
    const size_t len = strlen(mesh_id);
    size_t best = 0;
    uint64_t best_weight = 0;
    for (size_t i = 0; i < num_members; i++) {
        uint64_t w = XXH3_64bits_withSeed(mesh_id, len, seeds[i]);
        /* Ties (never seen in practice) go to the lower seed, the same on
         * every member. */
        if (i == 0 || w > best_weight || (w == best_weight && seeds[i] < seeds[best])) {
            best = i;
            best_weight = w;
        }
    }
    return best;
}
