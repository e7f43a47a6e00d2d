// The rows of the volume and layer options (option_rows.h): what each takes,
// its help, and where its value goes in the job's options.
#include "core/pipeline/option_rows.h"

namespace vm::option_rows {
namespace {

// GCC 12 warns about every member a designated initializer leaves to its
// default member initializer; that is the point of the syntax here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

const OptionSpec kRows[] = {
    // ---- volume
    {.key = "surfaceOnly",
     .type = T::kFlag,
     .group = "volume",
     .doc = "write the remeshed wall alone (no caps, layers or volume)",
     .set =
         [](O& o, const V& v) {
           o.volume = !v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(!o.volume); }},
    {.key = "inlet",
     .type = T::kInteger,
     .group = "volume",
     .metavar = "K",
     .min = 1,
     .max = 1e6,
     .needs = "an opening number from 1 to 1000000 (as the analysis lists them)",
     .doc = "opening K (largest first) is `inlet` instead of the largest",
     .set =
         [](O& o, const V& v) {
           o.inlet = int(v.number) - 1;
           return true;
         },
     .read = [](const O& o) -> std::string {
       return o.inlet > 0 ? std::to_string(o.inlet + 1) : "";
     }},
    {.key = "coreSize",
     .group = "volume",
     .metavar = "H",
     .min = 0,
     .unit = "length",
     .needs = "a length >= 0 (0: grow from the wall size)",
     .doc = "target size in the core of the lumen (0: the uniform size, or grown from the wall's)",
     .set =
         [](O& o, const V& v) {
           o.core_size = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.core_size); }},
    {.key = "names",
     .type = T::kText,
     .group = "volume",
     .metavar = "NAME",
     .needs = "K=NAME with NAME 1-64 letters, digits, _ or -, starting with a letter",
     .doc = "the group name of opening K (default: the file's face name, else inlet / "
            "outlet_k)",
     .repeatable = true,
     .per_opening = PerOpening::kRequired,
     .set =
         [](O& o, const V& v) {
           if (!valid_group_name(v.text)) return false;
           o.opening_names.emplace_back(v.opening - 1, v.text);
           return true;
         },
     .read = [](const O&) { return std::string(); }},
    {.key = "maxElements",
     .type = T::kInteger,
     .group = "volume",
     .metavar = "N",
     .min = 1000,
     .max = kMostElements,
     .needs = "a number of elements from 1000 to 1000000000",
     .doc = "the element budget: sizes that would make more wall triangles or tetrahedra are "
            "refused before meshing, the default size coarsened to fit (in WebAssembly the "
            "module's memory caps the tetrahedra further, at 300 bytes each: about 14M in 4 GB)",
     .set =
         [](O& o, const V& v) {
           o.max_elements = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.max_elements); }},
    {.key = "maxVolumeChange",
     .group = "size",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .needs = "a fraction from 0 to 1",
     .doc = "the remeshed wall may enclose at most this fraction more or less volume than the "
            "input; beyond, the size is refused as too coarse for the vessels",
     .set =
         [](O& o, const V& v) {
           o.max_volume_change = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.max_volume_change); }},
    {.key = "verify",
     .type = T::kFlag,
     .group = "volume",
     .doc = "check conformity and the boundary before writing; measure the layer heights",
     .set =
         [](O& o, const V& v) {
           o.verify = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.verify); }},
    // ---- layers
    {.key = "layers",
     .type = T::kInteger,
     .group = "layers",
     .metavar = "N",
     .min = 0,
     .max = 100,
     .needs = "a number of layers from 0 (none) to 100",
     .doc = "viscous layers grown inward (0: none)",
     .set =
         [](O& o, const V& v) {
           o.viscous.layers = int(v.number);
           return true;
         },
     .read = [](const O& o) -> std::string { return std::to_string(o.viscous.layers); }},
    {.key = "layerThickness",
     .group = "layers",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .min_exclusive = true,
     .max_exclusive = true,
     .unit = "fraction of R",
     .needs = "a fraction of the local vessel radius in (0, 1)",
     .doc = "total thickness of the viscous layers, F R",
     .set =
         [](O& o, const V& v) {
           o.viscous.thickness_fraction = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.viscous.thickness_fraction); }},
    {.key = "firstLayer",
     .group = "layers",
     .metavar = "H1",
     .min = 0,
     .min_exclusive = true,
     .unit = "length",
     .needs = "a positive height",
     .doc = "first layer height instead of a total thickness",
     .set =
         [](O& o, const V& v) {
           o.viscous.first_height = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return positive(o.viscous.first_height); }},
    {.key = "growth",
     .group = "layers",
     .metavar = "G",
     .min = 1,
     .max = 3,
     .needs = "a growth ratio from 1 to 3",
     .doc = "height ratio of consecutive layers",
     .set =
         [](O& o, const V& v) {
           o.viscous.growth = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.viscous.growth); }},
    {.key = "wallThickness",
     .group = "layers",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .min_exclusive = true,
     .max_exclusive = true,
     .unit = "fraction of R",
     .needs = "a fraction of the local vessel radius in (0, 1)",
     .doc = "grow the vessel wall outward, F R thick (e.g. 0.1; 4 layers)",
     .set =
         [](O& o, const V& v) {
           o.vessel.thickness_fraction = v.number;
           o.wall_thickness_given = true;
           if (o.vessel.layers == 0) o.vessel.layers = 4;
           return true;
         },
     .read = [](const O& o) -> std::string {
       return o.wall_thickness_given ? num(o.vessel.thickness_fraction) : "";
     }},
    {.key = "wallLayers",
     .type = T::kInteger,
     .group = "layers",
     .metavar = "N",
     .min = 0,
     .max = 100,
     .needs = "a number of layers from 0 (none) to 100",
     .doc = "layers of the vessel wall (alone: a wall of 0.1 R; 0: no wall)",
     .set =
         [](O& o, const V& v) {
           o.vessel.layers = int(v.number);
           return true;
         },
     .read = [](const O& o) -> std::string {
       return o.vessel.layers > 0 ? std::to_string(o.vessel.layers) : "";
     }},
    {.key = "firstLayerYplus",
     .group = "layers",
     .metavar = "Y",
     .min = 0,
     .min_exclusive = true,
     .needs = "a positive target y+",
     .doc = "first layer height from this target y+ at the inlet, with the inlet velocity, "
            "density and viscosity (skin friction Cf = 0.026 Re^(-1/7), Re of the inlet's "
            "diameter); the height used is reported",
     .set =
         [](O& o, const V& v) {
           o.yplus.yplus = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return positive(o.yplus.yplus); }},
    {.key = "inletVelocity",
     .group = "layers",
     .metavar = "U",
     .min = 0,
     .min_exclusive = true,
     .unit = "m/s",
     .needs = "a positive velocity in m/s",
     .doc = "with a target y+: the mean velocity at the inlet, m/s",
     .set =
         [](O& o, const V& v) {
           o.yplus.velocity = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return positive(o.yplus.velocity); }},
    {.key = "density",
     .group = "layers",
     .metavar = "RHO",
     .min = 0,
     .min_exclusive = true,
     .unit = "kg/m^3",
     .needs = "a positive density in kg/m^3",
     .doc = "with a target y+: the fluid's density, kg/m^3 (blood)",
     .set =
         [](O& o, const V& v) {
           o.yplus.density = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.yplus.density); }},
    {.key = "viscosity",
     .group = "layers",
     .metavar = "MU",
     .min = 0,
     .min_exclusive = true,
     .unit = "Pa s",
     .needs = "a positive dynamic viscosity in Pa s",
     .doc = "with a target y+: the fluid's dynamic viscosity, Pa s (blood)",
     .set =
         [](O& o, const V& v) {
           o.yplus.viscosity = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.yplus.viscosity); }},
    {.key = "tagLayer",
     .type = T::kFlag,
     .group = "layers",
     .doc = "the viscous layer as its own volume group `boundary_layer`",
     .set =
         [](O& o, const V& v) {
           o.tag_layer = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.tag_layer); }},
    {.key = "prisms",
     .type = T::kFlag,
     .group = "layers",
     .doc = "keep the layers' prisms (MSH type 6) instead of 3 tetrahedra each",
     .set =
         [](O& o, const V& v) {
           o.keep_prisms = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.keep_prisms); }},
};

#pragma GCC diagnostic pop

}  // namespace

std::span<const OptionSpec> volume_and_layers() { return kRows; }

}  // namespace vm::option_rows
