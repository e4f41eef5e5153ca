/* meshtopo core: one include for the whole half-edge library. */
#ifndef MESHTOPO_CORE_H
#define MESHTOPO_CORE_H

#include "meshtopo/attributes.h"
#include "meshtopo/defect_record.h"
#include "meshtopo/edit.h"
#include "meshtopo/face_list.h"
#include "meshtopo/generate.h"
#include "meshtopo/geometry.h"
#include "meshtopo/map.h"
#include "meshtopo/mesh.h"
#include "meshtopo/mesh_parts.h"
#include "meshtopo/predicates.h"
#include "meshtopo/query.h"
#include "meshtopo/report.h"
#include "meshtopo/status.h"
#include "meshtopo/validate.h"

#endif
