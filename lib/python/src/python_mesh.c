/* Mesh helpers of the Python package (python_api.h): status names from the
 * status table, record sizes for the package's layout check (LCM's
 * lcm_field_t too), and every
 * face's component in one call. */
#include <string.h>

#include "meshtopo/defect_record.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "python_api.h"

const char *mt_py_status_name(mt_status status)
{
    switch (status) {
#define MT__STATUS_NAME(name, text) \
    case name:                      \
        return #name;
        MT_STATUS_TABLE(MT__STATUS_NAME)
#undef MT__STATUS_NAME
        default:
            return "MT_UNKNOWN_STATUS";
    }
}

size_t mt_py_sizeof(const char *type_name)
{
    static const struct {
        const char *name;
        size_t size;
    } sizes[] = {
        {"mt_build_options", sizeof(mt_build_options)},
        {"mt_component_info", sizeof(mt_component_info)},
        {"mt_defect", sizeof(mt_defect)},
        {"mt_defect_record", sizeof(mt_defect_record)},
        {"mt_diag", sizeof(mt_diag)},
        {"mt_face_list", sizeof(mt_face_list)},
        {"mt_fan", sizeof(mt_fan)},
        {"mt_histogram_bin", sizeof(mt_histogram_bin)},
        {"mt_mesh_view", sizeof(mt_mesh_view)},
        {"mt_report", sizeof(mt_report)},
        {"mt_ring", sizeof(mt_ring)},
        {"mt_msgs_query_kind", sizeof(mt_msgs_query_kind)},
        {"lcm_field_t", sizeof(lcm_field_t)},
    };
    if (!type_name) return 0;
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
        if (strcmp(sizes[i].name, type_name) == 0) return sizes[i].size;
    return 0;
}

size_t mt_py_face_components(const mt_mesh *mesh, uint32_t *out_components, size_t capacity)
{
    if (!mesh) return 0;
    const size_t num_faces = mt_mesh_num_faces(mesh);
    const size_t n = capacity < num_faces ? capacity : num_faces;
    for (size_t f = 0; f < n; f++) {
        uint32_t component = MT_NONE;
        if (mt_face_component(mesh, (uint32_t)f, &component) != MT_OK) component = MT_NONE;
        out_components[f] = component;
    }
    return num_faces;
}
