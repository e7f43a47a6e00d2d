// The rows of the input and size options (option_rows.h): what each takes,
// its help, and where its value goes in the job's options.
#include "core/pipeline/option_rows.h"
#include "core/pipeline/option_values.h"
#include "core/util/portable_math.h"

namespace vm::option_rows {
namespace {

constexpr std::string_view kLargestAliases[] = {"largest-component"};

// GCC 12 warns about every member a designated initializer leaves to its
// default member initializer; that is the point of the syntax here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

const OptionSpec kRows[] = {
    // ---- input (info and mesh)
    {.key = "json",
     .type = T::kFlag,
     .commands = kCommandInfo,
     .faces = kFaceCli,
     .group = "output",
     .doc = "print the analysis as JSON"},
    {.key = "sizeField",
     .type = T::kText,
     .commands = kCommandInfo,
     .faces = kFaceCli,
     .group = "output",
     .metavar = "OUT.vtp",
     .needs = "a file name",
     .doc = "write the surface with the local vessel radius R and the edge length h the size "
            "options ask for, before meshing, as point data `radius` and `size` (VTK PolyData, "
            "the model's unit; the JS API: sizeField())"},
    {.key = "largestComponentOnly",
     .type = T::kFlag,
     .commands = kInfoMesh,
     .group = "input",
     .doc = "keep only the largest connected component instead of refusing several",
     .cli_aliases = kLargestAliases,
     .set =
         [](O& o, const V& v) {
           o.prepare.largest_component_only = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.prepare.largest_component_only); }},
    {.key = "repair",
     .type = T::kChoice,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "auto|off",
     .choices = kOffAuto,
     .needs = "auto or off",
     .doc = "auto: split non-manifold edges and vertices into manifold sheets and close holes "
            "smaller than the hole fraction of the local radius; off: only the safe repairs "
            "(non-manifold surfaces are refused, holes stay openings)",
     .set =
         [](O& o, const V& v) {
           o.prepare.repair = v.text == "auto";
           return true;
         },
     .read = [](const O& o) -> std::string { return o.prepare.repair ? "auto" : "off"; }},
    {.key = "holeFraction",
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .unit = "fraction of R",
     .needs = "a fraction of the local vessel radius in [0, 1] (0: close no hole)",
     .doc = "a boundary loop whose equivalent radius sqrt(area/pi) is below F local vessel radii "
            "is a hole (closed by repair auto), else an opening",
     .set =
         [](O& o, const V& v) {
           o.prepare.hole_fraction = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.prepare.hole_fraction); }},
    {.key = "units",
     .type = T::kChoice,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "U",
     .choices = kUnits,
     .needs = "mm, cm or m",
     .doc = "the unit of the file's numbers (default: guessed from the vessel radii and the "
            "model's size weighed against human anatomy, face labels hinting at cm; said "
            "certain, likely or unsure)",
     .set =
         [](O& o, const V& v) {
           o.prepare.units = parse_unit(v.text);
           return true;
         },
     .read = [](const O& o) -> std::string { return std::string(unit_symbol(o.prepare.units)); }},
    {.key = "flowExtension",
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "L",
     .min = 0,
     .max = 100,
     .unit = "local radii",
     .needs = "a length in local radii from 0 (none) to 100, or K=L for opening K",
     .doc = "extend the openings (K=L: opening K) straight along their normals by L local radii",
     .repeatable = true,
     .per_opening = PerOpening::kOptional,
     .set =
         [](O& o, const V& v) {
           if (v.opening > 0)
             o.prepare.flow_extensions.emplace_back(v.opening - 1, v.number);
           else
             o.prepare.flow_extension = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.prepare.flow_extension); }},
    {.key = "keepCaps",
     .type = T::kFlag,
     .commands = kInfoMesh,
     .group = "input",
     .doc = "keep planar caps as wall (else each recognised cap is removed and its rim becomes "
            "an opening)",
     .set =
         [](O& o, const V& v) {
           o.prepare.keep_caps = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.prepare.keep_caps); }},
    {.key = "smooth",
     .type = T::kText,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "auto|off|N",
     .needs = "auto, off or a number of smoothing passes from 1 to 1000",
     .doc = "smooth the surface before meshing (volume-preserving, within half a voxel): auto "
            "smooths voxel staircases only; N passes on any surface",
     .set =
         [](O& o, const V& v) {
           const auto mode = parse_smoothing(v.text);
           if (!mode) return false;
           o.prepare.smoothing = *mode;
           return true;
         },
     .read = [](const O& o) -> std::string { return smoothing_text(o.prepare.smoothing); }},
    {.key = "clip",
     .type = T::kChoice,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "off|auto",
     .choices = kOffAuto,
     .needs = "off or auto",
     .doc = "auto: cut each blind vessel end open (closed or not, after the cuts given), "
            "perpendicular to the vessel; off: keep the blind ends (they are proposed)",
     .set =
         [](O& o, const V& v) {
           o.prepare.clip_auto = v.text == "auto";
           return true;
         },
     .read = [](const O& o) -> std::string { return o.prepare.clip_auto ? "auto" : "off"; }},
    {.key = "clipDistance",
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "D",
     .min = 0,
     .min_exclusive = true,
     .unit = "local radii",
     .needs = "a positive number of local vessel radii",
     .doc = "with clip auto: cut D local radii in from each vessel end's tip",
     .set =
         [](O& o, const V& v) {
           o.prepare.clip_distance = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.prepare.clip_distance); }},
    {.key = "clipPlanes",
     .type = T::kNumbers,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "X,Y,Z,NX,NY,NZ",
     .list_size = 6,
     .unit = "length",
     .needs = "6 numbers X,Y,Z,NX,NY,NZ: a point of the cut and the normal pointing out of the "
              "part to keep",
     .doc = "cut the surface open with this plane (the side the normal points to is removed)",
     .repeatable = true,
     .set =
         [](O& o, const V& v) {
           const std::vector<double>& x = v.numbers;
           const double n = pm::hypot(x[3], x[4], x[5]);
           if (!(n > 0)) return false;
           o.prepare.clip_planes.push_back({{x[0], x[1], x[2]}, {x[3] / n, x[4] / n, x[5] / n}});
           return true;
         },
     .read = [](const O&) { return std::string(); }},
    {.key = "clipAt",
     .type = T::kNumbers,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "X,Y,Z",
     .list_size = 3,
     .unit = "length",
     .needs = "3 numbers X,Y,Z: a point on or near the vessel to cut across",
     .doc = "cut across the vessel at the surface point nearest X,Y,Z, perpendicular to the "
            "vessel, removing the side with less surface",
     .repeatable = true,
     .set =
         [](O& o, const V& v) {
           o.prepare.clip_at.push_back({v.numbers[0], v.numbers[1], v.numbers[2]});
           return true;
         },
     .read = [](const O&) { return std::string(); }},
    // ---- size
    {.key = "size",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "H",
     .min = 0,
     .min_exclusive = true,
     .unit = "length",
     .needs = "a positive length",
     .doc = "uniform target edge length",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.size.mode = SizeMode::kUniform;
           o.remesh_options.size.size = v.number;
           o.size_given = true;
           return true;
         },
     .read = [](const O& o) -> std::string {
       return o.remesh_options.size.mode == SizeMode::kUniform ? num(o.remesh_options.size.size)
                                                               : "";
     }},
    {.key = "perCircumference",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "N",
     .min = 3,
     .needs = "a number of edges per circumference >= 3",
     .doc = "h = 2 pi R(x) / N, R the local vessel radius (the default size mode)",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.size.mode = SizeMode::kPerCircumference;
           o.remesh_options.size.per_circumference = v.number;
           o.size_given = true;
           return true;
         },
     .read = [](const O& o) -> std::string {
       return o.remesh_options.size.mode == SizeMode::kPerCircumference
                  ? num(o.remesh_options.size.per_circumference)
                  : "";
     }},
    {.key = "sizeMin",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "H",
     .min = 0,
     .unit = "length",
     .needs = "a length >= 0",
     .doc = "smallest edge length",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.size.size_min = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.remesh_options.size.size_min); }},
    {.key = "sizeMax",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "H",
     .min = 0,
     .min_exclusive = true,
     .unit = "length",
     .needs = "a positive length",
     .doc = "largest edge length",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.size.size_max = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string {
       return std::isinf(o.remesh_options.size.size_max) ? "" : num(o.remesh_options.size.size_max);
     }},
    {.key = "refine",
     .type = T::kNumbers,
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "X,Y,Z,R,H",
     .list_size = 5,
     .unit = "length",
     .needs = "5 numbers X,Y,Z,R,H: a centre, a radius R > 0 and a size H > 0",
     .doc = "local refinement: edges of at most H within R of (X,Y,Z), graded out of it (wall "
            "and volume)",
     .repeatable = true,
     .set =
         [](O& o, const V& v) {
           const std::vector<double>& x = v.numbers;
           if (!(x[3] > 0) || !(x[4] > 0)) return false;
           o.remesh_options.size.spheres.push_back({{x[0], x[1], x[2]}, x[3], x[4]});
           return true;
         },
     .read = [](const O&) { return std::string(); }},
    {.key = "gradation",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "G",
     .min = 0,
     .needs = "a number >= 0 (size growth per unit length)",
     .doc = "the size grows at most G per unit length",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.size.gradation = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.remesh_options.size.gradation); }},
    {.key = "curvature",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "P",
     .min = 0,
     .needs = "a number of points per radian >= 0",
     .doc = "at least P edges per radian of curvature (0: off)",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.size.curvature_points = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.remesh_options.size.curvature_points); }},
    {.key = "featureAngle",
     .group = "size",
     .metavar = "A",
     .min = 0,
     .max = 180,
     .min_exclusive = true,
     .unit = "degrees",
     .needs = "an angle in degrees in (0, 180] (180: no sharp features)",
     .doc = "keep creases sharper than A degrees (180: none)",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.feature_angle_degrees = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.remesh_options.feature_angle_degrees); }},
    {.key = "fidelity",
     .group = "size",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .needs = "a fraction of h in [0, 1] (0: the wall may smooth over the input)",
     .doc = "input vertices farther than F h from the wall get a wall vertex pinned on them "
            "(0: bumps are smoothed over)",
     .set =
         [](O& o, const V& v) {
           RemeshOptions& r = o.remesh_options;
           r.fidelity = v.number;
           r.fidelity_rounds = v.number > 0 ? RemeshOptions{}.fidelity_rounds : 0;
           r.fidelity_size_rounds = v.number > 0 ? RemeshOptions{}.fidelity_size_rounds : 0;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.remesh_options.fidelity); }},
};

#pragma GCC diagnostic pop

}  // namespace

std::span<const OptionSpec> input_and_size() { return kRows; }

}  // namespace vm::option_rows
