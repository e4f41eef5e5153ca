/* Per-element attributes and hidden flags (meshtopo/attributes.h). Each
 * attribute is one array of value_bytes-sized values, sized to the element
 * capacity of the mesh's arrays for its kind (edits grow both together), so
 * an element an edit adds finds its value already zero: values past the
 * element count are never written. */
#include <string.h>

#include "mesh/mesh_internal.h"
#include "meshtopo/attributes.h"

typedef struct mt__attribute {
    char name[MT_ATTRIBUTE_NAME_MAX + 1];
    uint32_t value_bytes;
    uint8_t *values; /* [capacity of its kind * value_bytes] */
} mt__attribute;

typedef struct mt__attribute_set {
    mt__attribute list[MT_ELEMENT_KIND_COUNT][MT_ATTRIBUTES_PER_KIND];
    uint32_t count[MT_ELEMENT_KIND_COUNT];
    uint32_t capacity[MT_ELEMENT_KIND_COUNT]; /* elements each array of the kind holds */
} mt__attribute_set;

void mt__attribute_set_free(mt__attribute_set *set)
{
    if (!set) return;
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++)
        for (uint32_t i = 0; i < set->count[k]; i++) mt__free(set->list[k][i].values);
    mt__free(set);
}

const char *mt_element_kind_name(mt_element_kind kind)
{
    switch (kind) {
        case MT_ELEMENT_VERTEX:
            return "vertex";
        case MT_ELEMENT_EDGE:
            return "edge";
        case MT_ELEMENT_HALF_EDGE:
            return "half_edge";
        case MT_ELEMENT_FACE:
            return "face";
    }
    return "unknown";
}

static bool kind_ok(mt_element_kind kind)
{
    return (unsigned)kind < MT_ELEMENT_KIND_COUNT;
}

uint32_t mt_mesh_num_elements(const mt_mesh *m, mt_element_kind kind)
{
    if (!m) return 0;
    switch (kind) {
        case MT_ELEMENT_VERTEX:
            return m->num_verts;
        case MT_ELEMENT_EDGE:
            return m->num_half_edges / 2;
        case MT_ELEMENT_HALF_EDGE:
            return m->num_half_edges;
        case MT_ELEMENT_FACE:
            return m->num_faces;
    }
    return 0;
}

/* Elements the mesh's arrays of a kind have room for. */
static uint32_t mesh_capacity(const mt_mesh *m, mt_element_kind kind)
{
    uint32_t n = mt_mesh_num_elements(m, kind), cap = 0;
    switch (kind) {
        case MT_ELEMENT_VERTEX:
            cap = m->cap_verts;
            break;
        case MT_ELEMENT_EDGE:
            cap = m->cap_half_edges / 2;
            break;
        case MT_ELEMENT_HALF_EDGE:
            cap = m->cap_half_edges;
            break;
        case MT_ELEMENT_FACE:
            cap = m->cap_faces;
            break;
    }
    return cap > n ? cap : n;
}

static mt__attribute *find(const mt_mesh *m, mt_element_kind kind, const char *name)
{
    if (!m || !m->attributes || !kind_ok(kind) || !name) return NULL;
    mt__attribute_set *set = m->attributes;
    for (uint32_t i = 0; i < set->count[kind]; i++)
        if (strcmp(set->list[kind][i].name, name) == 0) return &set->list[kind][i];
    return NULL;
}

/* Grows one array from `from` to `to` elements, the new ones zero. */
static mt_status grow_values(mt__attribute *a, uint32_t from, uint32_t to)
{
    if (to <= from) return MT_OK;
    uint8_t *v = mt__realloc(a->values, (size_t)to * a->value_bytes);
    if (!v) return MT_ERR_NOMEM;
    memset(v + (size_t)from * a->value_bytes, 0, (size_t)(to - from) * a->value_bytes);
    a->values = v;
    return MT_OK;
}

mt_status mt__attributes_fit(mt_mesh *m)
{
    mt__attribute_set *set = m->attributes;
    if (!set) return MT_OK;
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT; k++) {
        const uint32_t need = mesh_capacity(m, (mt_element_kind)k);
        if (need <= set->capacity[k]) continue;
        for (uint32_t i = 0; i < set->count[k]; i++)
            if (grow_values(&set->list[k][i], set->capacity[k], need) != MT_OK)
                return MT_ERR_NOMEM; /* those grown keep their larger arrays, zero past the count */
        set->capacity[k] = need;
    }
    return MT_OK;
}

static bool name_ok(const char *name)
{
    size_t n = name ? strlen(name) : 0;
    if (n == 0 || n > MT_ATTRIBUTE_NAME_MAX) return false;
    for (size_t i = 0; i < n; i++) {
        const char c = name[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-' || c == '.'))
            return false;
    }
    return true;
}

mt_status mt_attribute_add(mt_mesh *mesh, mt_element_kind kind, const char *name,
                           uint32_t value_bytes, mt_diag *diag)
{
    static const char what[] = "mt_attribute_add";
    mt_diag_clear(diag);
    if (!mesh) return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: mesh is NULL", what);
    if (!kind_ok(kind))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: unknown element kind %d", what,
                        (int)kind);
    if (!name_ok(name))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "%s: name '%.80s' is not 1 to %d letters, digits, '_', '-' or '.'", what,
                        name ? name : "(null)", MT_ATTRIBUTE_NAME_MAX);
    if (value_bytes == 0 || value_bytes > MT_ATTRIBUTE_VALUE_MAX)
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE,
                        "%s: %s attribute '%s': values of %u bytes (1 to %d)", what,
                        mt_element_kind_name(kind), name, value_bytes, MT_ATTRIBUTE_VALUE_MAX);
    if (find(mesh, kind, name))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "%s: %s attribute '%s' already exists",
                        what, mt_element_kind_name(kind), name);
    if (!mesh->attributes) {
        mesh->attributes = mt__calloc(1, sizeof *mesh->attributes);
        if (!mesh->attributes)
            return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "%s: out of memory", what);
    }
    mt__attribute_set *set = mesh->attributes;
    if (set->count[kind] == MT_ATTRIBUTES_PER_KIND)
        return mt__fail(diag, MT_ERR_TOO_LARGE, MT_NONE,
                        "%s: %d %s attributes already, the most a kind has", what,
                        MT_ATTRIBUTES_PER_KIND, mt_element_kind_name(kind));
    const uint32_t cap = mesh_capacity(mesh, kind);
    if (cap > set->capacity[kind]) set->capacity[kind] = cap;
    mt__attribute a;
    memset(&a, 0, sizeof a);
    strcpy(a.name, name);
    a.value_bytes = value_bytes;
    a.values = mt__calloc(set->capacity[kind] ? set->capacity[kind] : 1, value_bytes);
    if (!a.values)
        return mt__fail(diag, MT_ERR_NOMEM, MT_NONE, "%s: no memory for %u values of %u bytes",
                        what, set->capacity[kind], value_bytes);
    set->list[kind][set->count[kind]++] = a;
    return MT_OK;
}

mt_status mt_attribute_remove(mt_mesh *mesh, mt_element_kind kind, const char *name, mt_diag *diag)
{
    mt_diag_clear(diag);
    mt__attribute *a = find(mesh, kind, name);
    if (!a)
        return mt__fail(diag, MT_ERR_NOT_FOUND, MT_NONE,
                        "mt_attribute_remove: no %s attribute '%.80s'", mt_element_kind_name(kind),
                        name ? name : "(null)");
    mt__attribute_set *set = mesh->attributes;
    mt__free(a->values);
    const size_t index = (size_t)(a - set->list[kind]);
    memmove(a, a + 1, (set->count[kind] - index - 1) * sizeof *a);
    set->count[kind]--;
    return MT_OK;
}

size_t mt_attribute_count(const mt_mesh *mesh, mt_element_kind kind)
{
    return mesh && mesh->attributes && kind_ok(kind) ? mesh->attributes->count[kind] : 0;
}

mt_status mt_attribute_info(const mt_mesh *mesh, mt_element_kind kind, size_t index,
                            const char **out_name, uint32_t *out_value_bytes)
{
    if (index >= mt_attribute_count(mesh, kind)) return MT_ERR_OUT_OF_RANGE;
    const mt__attribute *a = &mesh->attributes->list[kind][index];
    if (out_name) *out_name = a->name;
    if (out_value_bytes) *out_value_bytes = a->value_bytes;
    return MT_OK;
}

/* The attribute and the address of element id's value, or a status. */
static mt_status locate(const mt_mesh *mesh, mt_element_kind kind, const char *name, uint32_t id,
                        size_t size, uint8_t **out_value, mt_diag *diag, const char *what)
{
    mt_diag_clear(diag);
    mt__attribute *a = find(mesh, kind, name);
    if (!a)
        return mt__fail(diag, MT_ERR_NOT_FOUND, MT_NONE, "%s: no %s attribute '%.80s'", what,
                        mt_element_kind_name(kind), name ? name : "(null)");
    const uint32_t count = mt_mesh_num_elements(mesh, kind);
    if (id >= count)
        return mt__fail(diag, MT_ERR_OUT_OF_RANGE, id, "%s: %s %u out of range (%u)", what,
                        mt_element_kind_name(kind), id, count);
    if (size != a->value_bytes)
        return mt__fail(diag, MT_ERR_INVALID_ARG, id, "%s: '%s' holds %u bytes per %s, not %zu",
                        what, a->name, a->value_bytes, mt_element_kind_name(kind), size);
    *out_value = a->values + (size_t)id * a->value_bytes;
    return MT_OK;
}

mt_status mt_attribute_get(const mt_mesh *mesh, mt_element_kind kind, const char *name, uint32_t id,
                           void *value, size_t size, mt_diag *diag)
{
    uint8_t *at = NULL;
    mt_status s = locate(mesh, kind, name, id, size, &at, diag, "mt_attribute_get");
    if (s == MT_OK && !value)
        s = mt__fail(diag, MT_ERR_INVALID_ARG, id, "mt_attribute_get: value is NULL");
    if (s == MT_OK) memcpy(value, at, size);
    return s;
}

mt_status mt_attribute_set(mt_mesh *mesh, mt_element_kind kind, const char *name, uint32_t id,
                           const void *value, size_t size, mt_diag *diag)
{
    uint8_t *at = NULL;
    mt_status s = locate(mesh, kind, name, id, size, &at, diag, "mt_attribute_set");
    if (s == MT_OK && !value)
        s = mt__fail(diag, MT_ERR_INVALID_ARG, id, "mt_attribute_set: value is NULL");
    if (s == MT_OK) memcpy(at, value, size);
    return s;
}

mt_status mt_attribute_values(mt_mesh *mesh, mt_element_kind kind, const char *name,
                              uint8_t **out_values, uint32_t *out_value_bytes, uint32_t *out_count,
                              mt_diag *diag)
{
    mt_diag_clear(diag);
    mt__attribute *a = find(mesh, kind, name);
    if (!a)
        return mt__fail(diag, MT_ERR_NOT_FOUND, MT_NONE,
                        "mt_attribute_values: no %s attribute '%.80s'", mt_element_kind_name(kind),
                        name ? name : "(null)");
    if (out_values) *out_values = a->values;
    if (out_value_bytes) *out_value_bytes = a->value_bytes;
    if (out_count) *out_count = mt_mesh_num_elements(mesh, kind);
    return MT_OK;
}

mt_status mt_set_hidden(mt_mesh *mesh, mt_element_kind kind, uint32_t id, bool hidden,
                        mt_diag *diag)
{
    mt_diag_clear(diag);
    if (!mesh || !kind_ok(kind))
        return mt__fail(diag, MT_ERR_INVALID_ARG, MT_NONE, "mt_set_hidden: %s",
                        mesh ? "unknown element kind" : "mesh is NULL");
    const uint32_t count = mt_mesh_num_elements(mesh, kind);
    if (id >= count)
        return mt__fail(diag, MT_ERR_OUT_OF_RANGE, id, "mt_set_hidden: %s %u out of range (%u)",
                        mt_element_kind_name(kind), id, count);
    if (!find(mesh, kind, MT_ATTRIBUTE_HIDDEN)) {
        mt_status s = mt_attribute_add(mesh, kind, MT_ATTRIBUTE_HIDDEN, 1, diag);
        if (s != MT_OK) return s;
    }
    const uint8_t flag = hidden ? 1 : 0;
    return mt_attribute_set(mesh, kind, MT_ATTRIBUTE_HIDDEN, id, &flag, 1, diag);
}

mt_status mt_mesh_skip_hidden(mt_mesh *mesh, bool skip)
{
    if (!mesh) return MT_ERR_INVALID_ARG;
    mesh->skip_hidden = skip;
    return MT_OK;
}

const uint8_t *mt__skipped_flags(const mt_mesh *m, int kind)
{
    if (!m->skip_hidden) return NULL;
    const mt__attribute *a = find(m, (mt_element_kind)kind, MT_ATTRIBUTE_HIDDEN);
    return a && a->value_bytes == 1 ? a->values : NULL;
}

bool mt_is_hidden(const mt_mesh *mesh, mt_element_kind kind, uint32_t id)
{
    const mt__attribute *a = find(mesh, kind, MT_ATTRIBUTE_HIDDEN);
    return a && a->value_bytes == 1 && id < mt_mesh_num_elements(mesh, kind) && a->values[id] != 0;
}

mt_status mt__attributes_remap(const mt_mesh *old, mt_mesh *fresh, const uint32_t *vmap,
                               const uint32_t *fmap, const uint32_t *hemap)
{
    const mt__attribute_set *from = old->attributes;
    if (!from) return MT_OK;
    mt__attribute_set *to = mt__calloc(1, sizeof *to);
    if (!to) return MT_ERR_NOMEM;
    mt_status s = MT_OK;
    for (int k = 0; k < MT_ELEMENT_KIND_COUNT && s == MT_OK; k++) {
        const mt_element_kind kind = (mt_element_kind)k;
        const uint32_t old_count = mt_mesh_num_elements(old, kind);
        to->capacity[k] = mesh_capacity(fresh, kind);
        for (uint32_t i = 0; i < from->count[k] && s == MT_OK; i++) {
            const mt__attribute *a = &from->list[k][i];
            mt__attribute b = *a;
            b.values = mt__calloc(to->capacity[k] ? to->capacity[k] : 1, a->value_bytes);
            if (!b.values) {
                s = MT_ERR_NOMEM;
                break;
            }
            for (uint32_t e = 0; e < old_count; e++) {
                uint32_t target = MT_NONE;
                if (kind == MT_ELEMENT_VERTEX) target = vmap[e];
                if (kind == MT_ELEMENT_FACE) target = fmap[e];
                if (kind == MT_ELEMENT_HALF_EDGE) target = hemap[e];
                if (kind == MT_ELEMENT_EDGE)
                    target = hemap[2 * e] == MT_NONE ? MT_NONE : hemap[2 * e] / 2;
                if (target == MT_NONE || target >= to->capacity[k]) continue;
                memcpy(b.values + (size_t)target * a->value_bytes,
                       a->values + (size_t)e * a->value_bytes, a->value_bytes);
            }
            to->list[k][to->count[k]++] = b;
        }
    }
    if (s != MT_OK) {
        mt__attribute_set_free(to);
        return s;
    }
    mt__attribute_set_free(fresh->attributes);
    fresh->attributes = to;
    return MT_OK;
}
