// The group name of each opening: the user's, the file's face name, or
// inlet / outlet_k (the physical group names of the written mesh).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/pipeline/prepare_surface.h"
#include "core/util/result.h"

namespace vm {

/// Whether an opening may not take `name`: it names another group (wall,
/// lumen, outer_wall, boundary_layer, vessel_wall, and wall_* for the vessel
/// wall's rings).
bool reserved_name(const std::string& name);

/// The group name of each opening of `surface` (its analysis order): the
/// one in `names` (pairs of opening index, name; names valid as
/// valid_group_name says), else the file's face name when valid and free,
/// else `inlet` for opening `inlet` (an index) and outlet_1..k for the
/// others in analysis order. Errors (kBadOption): an opening number out of
/// range (option `name` or `inlet`), a reserved name, a name given twice.
Result<std::vector<std::string>> opening_names(
    const PreparedSurface& surface, const std::vector<std::pair<int, std::string>>& names,
    int inlet);

}  // namespace vm
