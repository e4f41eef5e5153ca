/* A perception node's first lines against an installed meshtopo::client,
 * used by the install test: the content hash of a cube (as meshtopod will
 * acknowledge it) and a client over in-process LCM (memq://, no network and
 * no daemon), created and destroyed. Prints "client ok" and the hash. */
#include <stdio.h>

#include "meshtopo/client.h"
#include "meshtopo/core.h"

int main(void)
{
    mt_face_list cube;
    mt_diag diag;
    if (mt_gen_platonic(MT_CUBE, &cube) != MT_OK) return 1;
    uint64_t hash = 0;
    if (mt_client_content_hash(&cube, &hash, &diag) != MT_OK) {
        fprintf(stderr, "content hash: %s\n", diag.message);
        return 1;
    }
    mt_client_options options = {0};
    options.lcm_url = "memq://";
    options.source = "install-test";
    mt_client *client = NULL;
    if (mt_client_create(&options, &client, &diag) != MT_OK) {
        fprintf(stderr, "client: %s\n", diag.message);
        return 1;
    }
    printf("client ok: cube content hash %016llx\n", (unsigned long long)hash);
    mt_client_destroy(client);
    mt_face_list_free(&cube);
    return 0;
}
