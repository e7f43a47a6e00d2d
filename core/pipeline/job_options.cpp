// Mesh-job options by name (see job_options.h).
#include "core/pipeline/job_options.h"

#include <cmath>
#include <string>

namespace vm {
namespace {

bool parse_number(std::string_view text, double& out) {
  std::string s(
      text);  // strtod needs a terminated string; from_chars(double) is missing in libc++14
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

Status need(std::string_view name, std::string_view what) {
  return Status::Error("--" + std::string(name) + " needs " + std::string(what));
}

}  // namespace

const std::vector<std::string_view>& job_option_names() {
  static const std::vector<std::string_view> names = {
      "size",           "per-circumference", "size-min",    "size-max",
      "gradation",      "curvature",         "param",       "mesher2d",
      "msh-version",    "feature-angle",     "inlet",       "core-size",
      "layers",         "layer-thickness",   "first-layer", "growth",
      "wall-thickness", "wall-layers",       "fidelity"};
  return names;
}

Status set_job_option(MeshJobOptions& o, std::string_view name, std::string_view value) {
  SizeOptions& size = o.remesh_options.size;
  double x = 0;
  const bool number = parse_number(value, x);
  if (name == "size") {
    if (!number || x <= 0) return need(name, "a positive length (model units)");
    size.mode = SizeMode::kUniform;
    size.size = x;
  } else if (name == "per-circumference") {
    if (!number || x < 3) return need(name, "a number of edges per circumference >= 3");
    size.mode = SizeMode::kPerCircumference;
    size.per_circumference = x;
  } else if (name == "size-min") {
    if (!number || x < 0) return need(name, "a length >= 0");
    size.size_min = x;
  } else if (name == "size-max") {
    if (!number || x <= 0) return need(name, "a positive length");
    size.size_max = x;
  } else if (name == "gradation") {
    if (!number || x < 0) return need(name, "a number >= 0 (size growth per unit length)");
    size.gradation = x;
  } else if (name == "curvature") {
    if (!number || x < 0) return need(name, "a number of points per radian >= 0");
    size.curvature_points = x;
  } else if (name == "inlet") {
    if (!number || x < 1 || x != std::floor(x))
      return need(name, "an opening number >= 1 (as `vesselmesh info` lists them)");
    o.inlet = int(x) - 1;
  } else if (name == "core-size") {
    if (!number || x < 0) return need(name, "a length >= 0 (0: grow from the wall size)");
    o.core_size = x;
  } else if (name == "layers" || name == "wall-layers") {
    if (!number || x < 0 || x > 100 || x != std::floor(x))
      return need(name, "a number of layers from 0 (none) to 100");
    (name == "layers" ? o.viscous : o.vessel).layers = int(x);
  } else if (name == "layer-thickness" || name == "wall-thickness") {
    if (!number || x <= 0 || x >= 1)
      return need(name, "a fraction of the local vessel radius in (0, 1)");
    LayerSpec& spec = name == "layer-thickness" ? o.viscous : o.vessel;
    spec.thickness_fraction = x;
    if (name == "wall-thickness" && spec.layers == 0) spec.layers = 4;
  } else if (name == "first-layer") {
    if (!number || x <= 0) return need(name, "a positive height (model units)");
    o.viscous.first_height = x;
  } else if (name == "growth") {
    if (!number || x < 1 || x > 3) return need(name, "a growth ratio from 1 to 3");
    o.viscous.growth = x;
  } else if (name == "feature-angle") {
    if (!number || x <= 0 || x > 180)
      return need(name, "an angle in degrees in (0, 180] (180: no sharp features)");
    o.remesh_options.feature_angle_degrees = x;
  } else if (name == "fidelity") {
    if (!number || x < 0 || x > 1)
      return need(name, "a fraction of h in [0, 1] (0: the wall may smooth over the input)");
    o.remesh_options.fidelity = x;
    o.remesh_options.fidelity_rounds = x > 0 ? RemeshOptions{}.fidelity_rounds : 0;
    o.remesh_options.fidelity_size_rounds = x > 0 ? RemeshOptions{}.fidelity_size_rounds : 0;
  } else if (name == "param") {
    if (value == "lscm")
      o.remesh_options.param = ParamMethod::kLscm;
    else if (value == "harmonic")
      o.remesh_options.param = ParamMethod::kHarmonic;
    else if (value == "floater")
      o.remesh_options.param = ParamMethod::kFloater;
    else
      return need(name, "lscm, harmonic or floater");
  } else if (name == "mesher2d") {
    if (value == "frontal")
      o.remesh_options.patch.mesher = Mesher2D::kFrontal;
    else if (value == "delaunay")
      o.remesh_options.patch.mesher = Mesher2D::kDelaunay;
    else if (value == "adapt")
      o.remesh_options.patch.mesher = Mesher2D::kAdapt;
    else
      return need(name, "frontal, delaunay or adapt");
  } else if (name == "msh-version") {
    auto v = parse_msh_version(std::string(value));
    if (!v.ok()) return v.status();
    o.msh_version = v.value();
  } else {
    return Status::Error("unknown option --" + std::string(name));
  }
  return Status::Ok();
}

}  // namespace vm
