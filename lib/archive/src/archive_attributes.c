/* A mesh's attributes (meshtopo/attributes.h) in an archive file: group
 * /meshtopo/attributes holds one group per element kind that has any
 * ("vertex", "edge", "half_edge", "face"), and in it one uint8 dataset per
 * attribute, named after it, of shape (elements, value bytes). Edge and
 * half-edge ids are those of the stored half-edge arrays, so those values
 * are loaded only onto a mesh restored from them; a mesh rebuilt from the
 * face list gets its vertex and face values only. */
#include <stdlib.h>
#include <string.h>

#include "archive_internal.h"
#include "meshtopo/attributes.h"

static const char description[] =
    "User attributes of the mesh's elements: one group per element kind (vertex, edge, "
    "half_edge, face: caller vertex and face ids, internal edge and half-edge ids of "
    "/meshtopo/halfedge), one uint8 dataset per attribute of shape (elements, bytes per "
    "value). The attribute 'hidden' holds the hidden flags (1 = hidden).";

static bool has_any(const mt_mesh *mesh)
{
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++)
        if (mt_attribute_count(mesh, (mt_element_kind)k) > 0) return true;
    return false;
}

mt_status mt__attributes_write(hid_t g, const mt_mesh *mesh, const mt__h5_layout *layout,
                               const char *file, mt_diag *diag)
{
    if (!has_any(mesh)) return MT_OK;
    /* Links listed in creation order, so a load adds them in the mesh's order. */
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
    if (gcpl < 0 ||
        H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0) {
        if (gcpl >= 0) H5Pclose(gcpl);
        return mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot make a group property list", file);
    }
    hid_t ag = H5Gcreate2(g, "attributes", H5P_DEFAULT, gcpl, H5P_DEFAULT);
    if (ag < 0) {
        H5Pclose(gcpl);
        return mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot create group attributes", file);
    }
    mt_status st = mt__h5_write_attr_string(ag, "description", description, file, diag);
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT && st == MT_OK; k++) {
        const mt_element_kind kind = (mt_element_kind)k;
        const size_t count = mt_attribute_count(mesh, kind);
        if (count == 0) continue;
        hid_t kg = H5Gcreate2(ag, mt_element_kind_name(kind), H5P_DEFAULT, gcpl, H5P_DEFAULT);
        if (kg < 0) {
            st = mt__h5_fail(diag, MT_ERR_IO, file, "%s: cannot create group attributes/%s", file,
                             mt_element_kind_name(kind));
            break;
        }
        for (size_t i = 0; i < count && st == MT_OK; i++) {
            const char *name = NULL;
            uint8_t *values = NULL;
            uint32_t bytes = 0, elements = 0;
            mt_attribute_info(mesh, kind, i, &name, &bytes);
            /* Read-only use: the values are written, never changed. */
            mt_attribute_values((mt_mesh *)mesh, kind, name, &values, &bytes, &elements, NULL);
            const hsize_t dims[2] = {elements, bytes};
            st = mt__h5_write_dataset_layout(kg, name, H5T_STD_U8LE, H5T_NATIVE_UINT8, 2, dims,
                                             values, layout, file, diag);
        }
        H5Gclose(kg);
    }
    H5Gclose(ag);
    H5Pclose(gcpl);
    return st;
}

typedef struct read_ctx {
    mt_mesh *mesh;
    mt_element_kind kind;
    const char *file;
    mt_diag *diag;    /* gets the first failure */
    mt_status status; /* the first failure; the other attributes are still read */
} read_ctx;

/* Rows and columns of a 2-D dataset of single bytes; MT_ERR_PARSE otherwise. */
static mt_status byte_matrix(hid_t kg, const char *name, const read_ctx *c, hsize_t dims[2],
                             mt_diag *diag)
{
    hid_t d = H5Dopen2(kg, name, H5P_DEFAULT);
    if (d < 0)
        return mt__archive_fail(diag, MT_ERR_PARSE, "%s: attributes/%s/%s is not a dataset",
                                c->file, mt_element_kind_name(c->kind), name);
    hid_t space = H5Dget_space(d), type = H5Dget_type(d);
    const bool ok = space >= 0 && type >= 0 && H5Sget_simple_extent_ndims(space) == 2 &&
                    H5Sget_simple_extent_dims(space, dims, NULL) == 2 &&
                    H5Tget_class(type) == H5T_INTEGER && H5Tget_size(type) == 1;
    if (type >= 0) H5Tclose(type);
    if (space >= 0) H5Sclose(space);
    H5Dclose(d);
    if (!ok)
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: attributes/%s/%s is not a 2-D dataset of bytes", c->file,
                                mt_element_kind_name(c->kind), name);
    return MT_OK;
}

/* Adds attribute `name` of c's kind to c's mesh with the dataset's values;
 * on failure the mesh is left without it. */
static mt_status read_attribute(hid_t kg, const char *name, const read_ctx *c, mt_diag *diag)
{
    const char *kind = mt_element_kind_name(c->kind);
    hsize_t dims[2];
    mt_status st = byte_matrix(kg, name, c, dims, diag);
    if (st != MT_OK) return st;
    const uint32_t elements = mt_mesh_num_elements(c->mesh, c->kind);
    if (dims[0] != elements || dims[1] == 0 || dims[1] > MT_ATTRIBUTE_VALUE_MAX)
        return mt__archive_fail(diag, MT_ERR_PARSE,
                                "%s: attributes/%s/%s has shape (%llu, %llu); the mesh has %u "
                                "elements of kind %s and values hold 1 to %d bytes",
                                c->file, kind, name, (unsigned long long)dims[0],
                                (unsigned long long)dims[1], elements, kind,
                                MT_ATTRIBUTE_VALUE_MAX);
    mt_diag why;
    st = mt_attribute_add(c->mesh, c->kind, name, (uint32_t)dims[1], &why);
    if (st != MT_OK)
        return mt__archive_fail(diag, st == MT_ERR_NOMEM ? MT_ERR_NOMEM : MT_ERR_PARSE,
                                "%s: attributes/%s/%s: %s", c->file, kind, name, why.message);
    uint8_t *values = NULL;
    mt_attribute_values(c->mesh, c->kind, name, &values, NULL, NULL, NULL);
    if (elements > 0)
        st = mt__h5_read_dataset_into(kg, name, c->file, 2, dims[1], MT__H5_UINT, 1,
                                      H5T_NATIVE_UINT8, values, elements, diag);
    if (st != MT_OK) mt_attribute_remove(c->mesh, c->kind, name, NULL);
    return st;
}

static herr_t read_one(hid_t kg, const char *name, const H5L_info_t *info, void *data)
{
    (void)info;
    read_ctx *c = data;
    mt_diag why;
    mt_status st = read_attribute(kg, name, c, &why);
    if (st != MT_OK && c->status == MT_OK) {
        c->status = st;
        *c->diag = why;
    }
    return 0; /* the others are still read */
}

mt_status mt__attributes_read(hid_t g, const char *file, mt_mesh *mesh, bool restored,
                              mt_diag *diag)
{
    if (H5Lexists(g, "attributes", H5P_DEFAULT) <= 0) return MT_OK;
    hid_t ag = mt__archive_group_open(g, "attributes", file, diag);
    if (ag < 0) return MT_ERR_PARSE;
    mt_status st = MT_OK;
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++) {
        const mt_element_kind kind = (mt_element_kind)k;
        const char *name = mt_element_kind_name(kind);
        if (H5Lexists(ag, name, H5P_DEFAULT) <= 0) continue;
        if (!restored && (kind == MT_ELEMENT_EDGE || kind == MT_ELEMENT_HALF_EDGE)) continue;
        mt_diag why;
        hid_t kg = mt__archive_group_open(ag, name, file, &why);
        if (kg < 0) {
            if (st == MT_OK && diag) *diag = why;
            st = MT_ERR_PARSE;
            continue;
        }
        read_ctx c = {mesh, kind, file, &why, MT_OK};
        /* Creation order as written; a group without that index fails at
         * once (nothing read) and is listed by name. */
        herr_t listed = H5Literate(kg, H5_INDEX_CRT_ORDER, H5_ITER_INC, NULL, read_one, &c);
        if (listed < 0 && c.status == MT_OK)
            listed = H5Literate(kg, H5_INDEX_NAME, H5_ITER_INC, NULL, read_one, &c);
        if (listed < 0 && c.status == MT_OK)
            c.status = mt__archive_fail(&why, MT_ERR_PARSE, "%s: attributes/%s cannot be listed",
                                        file, name);
        if (c.status != MT_OK && st == MT_OK) {
            st = c.status;
            if (diag) *diag = why;
        }
        H5Gclose(kg);
    }
    H5Gclose(ag);
    return st;
}
