/* meshtopod's store of built meshes: mesh id -> versions, each version an
 * immutable, reference-counted entry (the built mesh, its source, utime,
 * content hash and memory size). A query acquires an entry and may keep using
 * it while newer versions are added or the entry is removed; the mesh is freed
 * on the last release. Thread safe; meshes are built before they are added,
 * never under the store's lock.
 *
 * The store is the one way in and out of held versions. Two hooks are
 * installed into it and only called by it, never calling its add back: an
 * archiving policy (mtd_store_policy), told of every new version (before it
 * is visible, to make it durable; after, to queue it), and a backing
 * (mtd_store_backing), which hands over a version it keeps for the store to
 * add under its own rules (the memory budget, memory_budget.h). */
#ifndef MESHTOPOD_MESH_STORE_H
#define MESHTOPOD_MESH_STORE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "memory_budget.h"
#include "meshtopo/face_list.h"
#include "meshtopo/mesh.h"
#include "meshtopo/protocol.h"
#include "meshtopo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What is known about one stored version; every string is NUL-terminated. */
typedef struct mtd_mesh_info {
    const char *id;
    uint32_t version;              /* 1, 2, ... per id, in the order they were added */
    const char *source;            /* who sent it (the node's source name), "" if none */
    int64_t utime;                 /* microseconds since the epoch, from the submission */
    uint64_t content_hash;         /* opaque, from the caller */
    size_t memory_bytes;           /* mesh + report + entry bookkeeping; 0 when not held */
    uint32_t num_verts, num_faces; /* the built mesh's counts */
    uint64_t num_defects;          /* its report's defects */
} mtd_mesh_info;

/* One immutable stored version. Valid from mtd_store_add (out_entry) or
 * mtd_store_acquire until the matching mtd_entry_release, whatever happens to
 * the store meanwhile (removal, newer versions, mtd_store_destroy). */
typedef struct mtd_mesh_entry mtd_mesh_entry;

/* Called once per entry when its last reference is dropped, just before the
 * mesh is freed, on whichever thread dropped it and outside the store's lock.
 * It may read the mesh and info but must not keep them. */
typedef void (*mtd_entry_free_fn)(void *ctx, const mt_mesh *mesh, const mtd_mesh_info *info);

/* Takes over a mesh whose last reference was dropped (after on_entry_free),
 * on that same thread, in place of mt_mesh_destroy: meshtopod recycles its
 * arrays into a build workspace. */
typedef void (*mtd_mesh_dispose_fn)(void *ctx, mt_mesh *mesh);

/* Store options; a zeroed struct (or NULL) gives the defaults. */
typedef struct mtd_store_options {
    /* Versions kept per id: adding one more drops the oldest (0 = keep all). */
    uint32_t max_versions_per_id;
    /* Total memory_bytes of the versions held; an add that would exceed it
     * (after dropping versions per max_versions_per_id) fails with
     * MT_ERR_TOO_LARGE (0 = no limit). Removed entries still referenced by a
     * query do not count. */
    size_t max_bytes;
    mtd_entry_free_fn on_entry_free; /* optional */
    void *on_entry_free_ctx;
    mtd_mesh_dispose_fn dispose_mesh; /* optional; NULL: mt_mesh_destroy */
    void *dispose_mesh_ctx;
    /* Optional, not owned: versions the backing keeps are dropped from
     * memory, least recently used first, while the store holds more than it
     * (mtd_store_trim); a query loads them again through the backing. */
    mtd_budget *budget;
} mtd_store_options;

typedef struct mtd_store mtd_store;

/* Creates an empty store. Returns MT_OK or MT_ERR_NOMEM (*out_store NULL). */
mt_status mtd_store_create(const mtd_store_options *options, mtd_store **out_store);

/* Drops the store's reference to every entry and frees the store. Entries a
 * caller still holds stay valid until released. NULL-safe. Must not race with
 * other calls on the same store. */
void mtd_store_destroy(mtd_store *store);

/* Per-submission details for mtd_store_add; a zeroed struct is valid. */
typedef struct mtd_mesh_meta {
    const char *source; /* copied; NULL means "" */
    int64_t utime;
    uint64_t content_hash;
    /* 0: the next version of the id (one more than the highest it ever had).
     * Otherwise exactly this version, which must exceed every version the id
     * has had: used when reloading an archive, so numbers stay what clients
     * were told. */
    uint32_t version;
    /* With a non-zero version: that version was reserved with
     * mtd_store_reserve_version or is archived, so it may be at or below the
     * id's highest; it must not be held. Versions beyond max_versions_per_id
     * are then dropped only among those below it (a reloaded old version
     * never pushes out newer ones). */
    bool reserved;
} mtd_mesh_meta;

/* Adds a built mesh under id as a new version. On MT_OK the store owns mesh,
 * *out_version (may be NULL) is its version and, when out_entry is not NULL,
 * *out_entry is an extra reference for the caller to release. Versions beyond
 * max_versions_per_id are dropped, oldest first.
 * Errors leave the store unchanged and the caller owning mesh:
 * MT_ERR_INVALID_ARG (bad id, see mt_msgs_mesh_id_check; NULL mesh; a requested
 * version not above the id's highest), MT_ERR_TOO_LARGE (max_bytes, or the
 * id ran out of version numbers), MT_ERR_NOMEM. diag (NULL-safe) says which. */
mt_status mtd_store_add(mtd_store *store, const char *id, mt_mesh *mesh, const mtd_mesh_meta *meta,
                        uint32_t *out_version, mtd_mesh_entry **out_entry, mt_diag *diag);

/* Raises the highest version id has had to at least `version` (0: one more
 * than now) and writes it to *out_version (may be NULL). Numbers reserved
 * this way are never handed out by a plain add; the caller then adds that
 * version with meta.reserved, or leaves a gap. MT_ERR_INVALID_ARG (bad id),
 * MT_ERR_TOO_LARGE (no version numbers left), MT_ERR_NOMEM. */
mt_status mtd_store_reserve_version(mtd_store *store, const char *id, uint32_t version,
                                    uint32_t *out_version, mt_diag *diag);

/* Acquires version `version` of id (0 = the latest held). On MT_OK the caller
 * holds *out_entry and must release it. MT_ERR_NOT_FOUND when the id or that
 * version is not held (*out_entry NULL), MT_ERR_INVALID_ARG for a bad id
 * (diag says which rule). Never waits for a build. */
mt_status mtd_store_acquire(mtd_store *store, const char *id, uint32_t version,
                            mtd_mesh_entry **out_entry, mt_diag *diag);

/* Removes version `version` (>= 1) of id from the store. A caller holding the
 * entry keeps it until its release. MT_ERR_NOT_FOUND if not held,
 * MT_ERR_INVALID_ARG for version 0 or a bad id. The id keeps counting: the
 * next add still gets a higher version. */
mt_status mtd_store_remove(mtd_store *store, const char *id, uint32_t version, mt_diag *diag);

/* Removes every version held of each id that keep(ctx, id) refuses (keep
 * runs under the store's lock: it must not call the store). The ids keep
 * their version numbers, as with mtd_store_remove. Returns the versions
 * removed (0 also when out of memory: nothing is then removed). */
size_t mtd_store_remove_unless(mtd_store *store, bool (*keep)(void *ctx, const char *id),
                               void *ctx);

/* Another reference to an entry the caller holds (for handing it to a
 * worker thread). Returns entry. */
mtd_mesh_entry *mtd_entry_retain(mtd_mesh_entry *entry);

/* Drops one reference; the last one frees the mesh. NULL-safe. */
void mtd_entry_release(mtd_mesh_entry *entry);

/* The entry's built mesh and its details; valid while the entry is held. */
const mt_mesh *mtd_entry_mesh(const mtd_mesh_entry *entry);
const mtd_mesh_info *mtd_entry_info(const mtd_mesh_entry *entry);

/* What the store holds right now. */
typedef struct mtd_store_totals {
    size_t ids;          /* ids with at least one version held */
    size_t versions;     /* versions held, all ids together */
    size_t memory_bytes; /* sum of their memory_bytes */
} mtd_store_totals;

void mtd_store_get_totals(mtd_store *store, mtd_store_totals *out_totals);

/* A snapshot of the store for `list`: ids in byte order, each with its
 * versions ascending. Owns all its strings; free with mtd_store_listing_free. */
typedef struct mtd_listed_id {
    const char *id;
    uint32_t num_versions;         /* versions held (>= 1) */
    const mtd_mesh_info *versions; /* [num_versions], ascending version */
} mtd_listed_id;

typedef struct mtd_store_listing {
    size_t num_ids;
    mtd_listed_id *ids; /* [num_ids] */
    mtd_store_totals totals;
} mtd_store_listing;

/* Takes a snapshot of the versions held and, with a backing, of the
 * versions it keeps (memory_bytes 0 for those not held). MT_OK or
 * MT_ERR_NOMEM (*out_listing NULL). */
mt_status mtd_store_list(mtd_store *store, mtd_store_listing **out_listing);

/* NULL-safe. */
void mtd_store_listing_free(mtd_store_listing *listing);

/* Where versions the store does not hold are kept (meshtopod: the archive's
 * catalog), so a query can be served from it. The store calls these outside
 * its lock, from whichever thread fetches; they never call the store: a
 * version is loaded by handing its mesh to the store, which adds it. */
typedef struct mtd_store_backing {
    void *ctx;
    /* The highest version of id it keeps, 0 if none: new versions of id are
     * numbered after it. */
    uint32_t (*highest)(void *ctx, const char *id);
    /* Whether it keeps (id, version). */
    bool (*keeps)(void *ctx, const char *id, uint32_t version);
    /* Reads (id, version): *out_mesh (the caller's), and *out_meta's source
     * (malloc'd: the caller frees it), utime and content hash. Otherwise
     * diag says why, as the query that asked is answered. */
    mt_status (*load)(void *ctx, const char *id, uint32_t version, mt_mesh **out_mesh,
                      mtd_mesh_meta *out_meta, mt_diag *diag);
    /* What became of a version load read: MT_OK (held now), or the store's
     * refusal (diag, which it may reword for the query). */
    void (*loaded)(void *ctx, const char *id, uint32_t version, mt_status status, mt_diag *diag);
    /* *out: `held` (the store's snapshot) merged with what it keeps, as one
     * listing in the same order; free with mtd_store_listing_free. */
    mt_status (*list)(void *ctx, const mtd_store_listing *held, mtd_store_listing **out);
} mtd_store_backing;

/* Installs a backing (copied; every member set). Call before other threads
 * use the store. */
void mtd_store_set_backing(mtd_store *store, const mtd_store_backing *backing);

/* How new versions are archived (meshtopod: the archive writer). The store
 * notifies it; it never calls the store. Every member may be NULL. */
typedef struct mtd_store_policy {
    void *ctx;
    /* Before a new version is visible (sync archiving): makes it durable.
     * info->version is the number the store reserved; *io_version may be
     * raised to the one it was kept under (a shared directory numbers it).
     * MT_OK: kept by the backing from now on, so the memory budget may drop
     * it. Otherwise the version is not added and diag says why. */
    mt_status (*admit)(void *ctx, const mtd_mesh_info *info, const mt_face_list *list,
                       const mt_mesh *mesh, uint32_t *io_version, mt_diag *diag);
    /* An admitted version the store then refused: undo what admit kept. */
    void (*withdraw)(void *ctx, const char *id, uint32_t version);
    /* Once per new version, after it is visible (async archiving queues it
     * here; it may retain the entry). May wait (a full queue). */
    void (*on_added)(void *ctx, mtd_mesh_entry *entry, const mt_face_list *list);
} mtd_store_policy;

/* Installs an archiving policy (copied). Call before other threads use the
 * store. */
void mtd_store_set_policy(mtd_store *store, const mtd_store_policy *policy);

/* Adds a freshly built mesh as the next version of id (numbered after every
 * version held or kept by the backing), through the archiving policy: its
 * admit before the version is visible, its on_added after, each handed
 * `list` (the face list mesh was built from; not kept). meta->version and
 * meta->reserved are ignored. Then keeps the store within its memory
 * budget. On MT_OK as mtd_store_add. Otherwise nothing is added (the caller
 * keeps mesh) and *out_by_policy (may be NULL) tells whether the policy's
 * admit refused it (diag says why) rather than the store. */
mt_status mtd_store_put(mtd_store *store, const char *id, mt_mesh *mesh, const mtd_mesh_meta *meta,
                        const mt_face_list *list, uint32_t *out_version, mtd_mesh_entry **out_entry,
                        bool *out_by_policy, mt_diag *diag);

/* Drops versions the budget lets go (least recently used first) until the
 * store holds no more than the budget or none is left to drop. Returns how
 * many were dropped. Nothing without a budget. */
size_t mtd_store_trim(mtd_store *store);

/* What mtd_store_fetch found. */
typedef enum mtd_fetch_result {
    MTD_FETCH_OK,          /* *out_entry is held: release it */
    MTD_FETCH_BAD_ID,      /* the id breaks mt_msgs_mesh_id_check (diag says) */
    MTD_FETCH_NOT_HELD,    /* neither held nor kept by the backing */
    MTD_FETCH_NEEDS_LOAD,  /* kept by the backing: fetch again with may_load */
    MTD_FETCH_LOAD_FAILED, /* kept, but the backing could not load it (diag) */
} mtd_fetch_result;

/* Acquires version `version` of id for a query (it counts as used for the
 * memory budget). Version 0 means the highest version held or kept by the
 * backing. A version the backing keeps but the store does not hold is read
 * through the backing's load and added when may_load (on this thread: it can
 * take as long as reading a file), then the store is trimmed to its budget;
 * else MTD_FETCH_NEEDS_LOAD. Without a backing, mtd_store_acquire. */
mtd_fetch_result mtd_store_fetch(mtd_store *store, const char *id, uint32_t version, bool may_load,
                                 mtd_mesh_entry **out_entry, mt_diag *diag);

#ifdef __cplusplus
}
#endif

#endif
