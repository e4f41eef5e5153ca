/* `meshtopo inspect --blocks SIZE FILE`: the file split into grid blocks as
 * a mapper sends them (block_split.h), put one by one into an mt_map (exact
 * weld), and the map's report. The map keeps only counts so far, so the
 * full report (loops, components, defect ids, queries) comes from a build of
 * mt_map_face_list's union; the map's incremental counts must equal that
 * build's, else the command fails. Ids are map ids (dense: nothing removed). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "block_split.h"
#include "inspect.h"
#include "meshtopo/map.h"
#include "meshtopo/report.h"

static const char *diag_text(const mt_diag *diag, mt_status status)
{
    return diag->message[0] ? diag->message : mt_strerror(status);
}

/* The blocks end to end, unwelded (out-of-range entries as they are). */
static mt_status concat_blocks(const cli_block_set *set, mt_face_list *out, mt_diag *diag)
{
    uint64_t nv = 0, nf = 0, ni = 0;
    for (size_t b = 0; b < set->count; b++) {
        nv += set->blocks[b].list.num_verts;
        nf += set->blocks[b].list.num_faces;
        ni += set->blocks[b].list.num_indices;
    }
    if (nv >= MT_NONE || nf >= MT_NONE) {
        mt_diag_clear(diag);
        snprintf(diag->message, sizeof diag->message, "the blocks hold too many vertices");
        return MT_ERR_TOO_LARGE;
    }
    mt_status st = mt_face_list_alloc(out, (uint32_t)nv, (uint32_t)nf, ni, diag);
    if (st != MT_OK) return st;
    uint32_t voff = 0, foff = 0;
    uint64_t at = 0;
    for (size_t b = 0; b < set->count; b++) {
        const mt_face_list *l = &set->blocks[b].list;
        if (l->num_verts)
            memcpy(&out->positions[3 * (size_t)voff], l->positions,
                   (size_t)l->num_verts * 3 * sizeof(double));
        if (l->num_faces)
            memcpy(&out->face_sizes[foff], l->face_sizes, (size_t)l->num_faces * sizeof(uint32_t));
        for (uint64_t i = 0; i < l->num_indices; i++) {
            const uint32_t x = l->face_indices[i];
            out->face_indices[at + i] = x < l->num_verts ? voff + x : x;
        }
        voff += l->num_verts;
        foff += l->num_faces;
        at += l->num_indices;
    }
    return MT_OK;
}

/* out->weld.nonmanifold: the map's non-manifold vertices none of whose
 * block copies was non-manifold in the blocks end to end, unwelded (what
 * --weld reports, with the blocks as the unwelded input). vids: the map id
 * of each list vertex. */
static mt_status weld_news(const cli_block_set *set, const mt_map *map, const uint32_t *vids,
                           cli_mesh *out, mt_diag *diag)
{
    mt_face_list cat;
    mt_status st = concat_blocks(set, &cat, diag);
    if (st != MT_OK) return st;
    mt_build_options plain;
    memset(&plain, 0, sizeof plain);
    mt_mesh *before = NULL;
    st = mt_mesh_build(&cat, &plain, &before, diag);
    mt_face_list_free(&cat);
    if (st != MT_OK) return st;
    uint32_t vend = 0, fend = 0;
    mt_map_id_ends(map, &vend, &fend);
    const uint32_t n = out->list.num_verts;
    uint32_t *row = malloc((vend ? vend : 1) * sizeof *row); /* map id -> list vertex */
    unsigned char *flags = calloc(n ? n : 1, 1);
    uint32_t *ids = NULL;
    if (!row || !flags) {
        st = MT_ERR_NOMEM;
        goto done;
    }
    for (uint32_t i = 0; i < n; i++) row[vids[i]] = i;
    /* bit 2: a block copy was non-manifold unwelded; bit 1: non-manifold now. */
    const mt_report *r = mt_mesh_report(before);
    uint32_t base = 0;
    size_t b = 0;
    for (size_t i = 0; i < r->num_defects; i++) {
        const mt_defect *d = &r->defects[i];
        if (d->kind != MT_DEFECT_NONMANIFOLD_VERTEX) continue;
        /* Defects come by first id: walk the blocks forward. */
        if (d->a < base) b = 0, base = 0;
        while (b < set->count && d->a >= base + set->blocks[b].list.num_verts)
            base += set->blocks[b++].list.num_verts;
        if (b == set->count) continue;
        uint32_t v = 0;
        if (mt_map_block_vert(map, set->blocks[b].key, d->a - base, &v) == MT_OK && v < vend)
            flags[row[v]] |= 2;
    }
    r = mt_mesh_report(out->mesh);
    for (size_t i = 0; i < r->num_defects; i++)
        if (r->defects[i].kind == MT_DEFECT_NONMANIFOLD_VERTEX && r->defects[i].a < n)
            flags[r->defects[i].a] |= 1;
    size_t count = 0;
    for (uint32_t v = 0; v < n; v++) count += flags[v] == 1;
    ids = malloc((count ? count : 1) * sizeof *ids);
    if (!ids) {
        st = MT_ERR_NOMEM;
        goto done;
    }
    count = 0;
    for (uint32_t v = 0; v < n; v++)
        if (flags[v] == 1) ids[count++] = v;
    out->weld.nonmanifold = ids;
    out->weld.num_nonmanifold = count;
done:
    if (st == MT_ERR_NOMEM) snprintf(diag->message, sizeof diag->message, "out of memory");
    mt_mesh_destroy(before);
    free(row);
    free(flags);
    return st;
}

int inspect_blocks_load(const char *path, const char *format_name, uint64_t max_input, double size,
                        cli_mesh *out)
{
    memset(out, 0, sizeof *out);
    double t0 = cli_now_ms();
    mt_face_list file;
    int code = cli_face_list_read_bounded("inspect", path, format_name, max_input, &file);
    out->read_ms = cli_now_ms() - t0;
    if (code != CLI_EXIT_OK) return code;
    if (file.num_verts > 0 && !file.positions) {
        cli_error("inspect",
                  "--blocks: %s has %u vertices but no positions; blocks are cut by "
                  "position",
                  path, (unsigned)file.num_verts);
        mt_face_list_free(&file);
        return CLI_EXIT_BUILD;
    }
    mt_diag diag;
    mt_diag_clear(&diag);
    cli_block_set set;
    mt_status st = cli_blocks_split(&file, size, &set, &diag);
    mt_face_list_free(&file);
    if (st != MT_OK) {
        cli_error("inspect", "--blocks: cannot split %s into blocks: %s", path,
                  diag_text(&diag, st));
        return CLI_EXIT_BUILD;
    }

    /* The map, block by block, as a mapper would send them. */
    t0 = cli_now_ms();
    mt_map *map = NULL;
    uint32_t *vids = NULL, *fids = NULL;
    st = mt_map_create(NULL, &map, &diag);
    uint64_t sent = 0;
    for (size_t b = 0; st == MT_OK && b < set.count; b++) {
        st = mt_map_put(map, set.blocks[b].key, &set.blocks[b].list, NULL, NULL, &diag);
        sent += set.blocks[b].list.num_verts;
    }
    out->build_ms = cli_now_ms() - t0;
    if (st != MT_OK) {
        cli_error("inspect", "--blocks: cannot put %s's blocks into a map: %s", path,
                  diag_text(&diag, st));
        code = CLI_EXIT_BUILD;
        goto done;
    }

    /* The full report: a build of the map's welded union. */
    mt_map_counts c;
    mt_map_get_counts(map, &c);
    vids = malloc((c.num_verts ? c.num_verts : 1) * sizeof *vids);
    fids = malloc((c.num_faces ? c.num_faces : 1) * sizeof *fids);
    if (!vids || !fids) {
        st = MT_ERR_NOMEM;
        mt_diag_clear(&diag);
    } else {
        st = mt_map_face_list(map, &out->list, vids, c.num_verts, fids, c.num_faces, &diag);
    }
    if (st == MT_OK) {
        mt_build_options build;
        memset(&build, 0, sizeof build);
        st = mt_mesh_build(&out->list, &build, &out->mesh, &diag);
    }
    if (st != MT_OK) {
        cli_error("inspect", "--blocks: cannot build the union of the map of %s: %s", path,
                  diag_text(&diag, st));
        code = CLI_EXIT_BUILD;
        goto done;
    }
    if (mt_map_compare_report(map, mt_mesh_report(out->mesh), &diag) != MT_OK) {
        cli_error("inspect",
                  "--blocks: the map's incremental counts of %s differ from a full build of "
                  "its union (a bug in meshtopo's map): %s",
                  path, diag.message);
        code = CLI_EXIT_BUILD;
        goto done;
    }
    out->weld.enabled = true;
    out->weld.eps = 0;
    out->weld.vertices_before = sent > UINT32_MAX ? UINT32_MAX : (uint32_t)sent;
    out->weld.vertices_after = c.num_verts;
    out->weld.merged = out->weld.vertices_before - c.num_verts;
    out->weld.blocks = set.count;
    out->weld.block_size = size;
    st = weld_news(&set, map, vids, out, &diag);
    if (st != MT_OK) {
        cli_error("inspect", "--blocks: cannot tell what the weld made non-manifold in %s: %s",
                  path, diag_text(&diag, st));
        code = CLI_EXIT_BUILD;
    }
done:
    if (code != CLI_EXIT_OK) cli_mesh_free(out);
    free(vids);
    free(fids);
    mt_map_destroy(map);
    cli_block_set_free(&set);
    return code;
}
