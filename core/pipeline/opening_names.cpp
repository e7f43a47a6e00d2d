// Opening names (opening_names.h).
#include "core/pipeline/opening_names.h"

#include <algorithm>

#include "core/pipeline/option_table.h"

namespace vm {

bool reserved_name(const std::string& name) {
  return name == "wall" || name == "lumen" || name == "outer_wall" || name == "boundary_layer" ||
         name == "vessel_wall" || name.rfind("wall_", 0) == 0;
}

Result<std::vector<std::string>> opening_names(
    const PreparedSurface& s, const std::vector<std::pair<int, std::string>>& given, int inlet) {
  const size_t n = s.topology.openings.size();
  const std::string count = std::to_string(n);
  if (inlet < 0 || (inlet > 0 && size_t(inlet) >= n))
    return Status::BadOption(
        "inlet", n == 0 ? "cannot be used: the surface has no opening"
                        : "must be between 1 and the number of openings (" + count + ")");
  std::vector<std::string> names(n);
  for (const auto& [k, name] : given) {
    if (k < 0 || size_t(k) >= n)
      return Status::BadOption("name",
                               "names opening " + std::to_string(k + 1) + ", but there " +
                                   (n == 1 ? "is 1 opening" : "are " + count + " openings"));
    if (reserved_name(name))
      return Status::BadOption("name", "cannot be '" + name +
                                           "': wall, lumen, outer_wall, boundary_layer, "
                                           "vessel_wall and wall_* name other groups");
    names[size_t(k)] = name;
  }
  for (size_t i = 0; i < n; ++i) {
    const std::string& file_name = s.opening_sources[i].name;
    if (names[i].empty() && valid_group_name(file_name) && !reserved_name(file_name) &&
        std::find(names.begin(), names.end(), file_name) == names.end())
      names[i] = file_name;
  }
  int outlet = 0;
  for (size_t i = 0; i < n; ++i) {
    if (i == size_t(inlet)) {
      if (names[i].empty()) names[i] = "inlet";
    } else if (names[i].empty()) {
      names[i] = "outlet_" + std::to_string(++outlet);
    }
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < i; ++j)
      if (names[i] == names[j])
        return Status::BadOption("name", "gives '" + names[i] + "' to openings " +
                                             std::to_string(j + 1) + " and " +
                                             std::to_string(i + 1) + ": each name once");
  return names;
}

}  // namespace vm
