// Reflection over the generated message types: the static tables (type_info.h), the registry,
// JSON conversion, dotted-path assignment from text and freeing. See each header for details.
#pragma once

#include "hubrt/msgs/json.h"           // IWYU pragma: export
#include "hubrt/msgs/registry.h"       // IWYU pragma: export
#include "hubrt/msgs/sample_memory.h"  // IWYU pragma: export
#include "hubrt/msgs/set_field.h"      // IWYU pragma: export
#include "hubrt/msgs/type_info.h"      // IWYU pragma: export
