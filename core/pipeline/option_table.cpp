// The option table and the conversions around it (option_table.h).
#include "core/pipeline/option_table.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/pipeline/element_budget.h"
#include "core/pipeline/write_outputs.h"
#include "core/util/json_writer.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

constexpr std::string_view kParams[] = {"lscm", "harmonic", "floater"};
constexpr std::string_view kMeshers[] = {"frontal", "delaunay", "adapt"};
constexpr std::string_view kMshVersions[] = {"4.1", "2.2"};
constexpr std::string_view kPhantomKinds[] = {"bifurcation", "tube", "aneurysm",
                                              "torus",       "tree", "crossing", "outlets",
                                              "root"};
constexpr std::string_view kCapShapes[] = {"flat", "fan", "dome"};
constexpr std::string_view kUnits[] = {"mm", "cm", "m"};
constexpr std::string_view kOffAuto[] = {"off", "auto"};
constexpr std::string_view kFormats[] = {"msh", "vtu", "vtp", "stl", "mesh-complete", "foam"};
constexpr std::string_view kSolvers[] = {"gmsh", "openfoam", "fenics", "svfsi"};
constexpr std::string_view kFamilyLayers[] = {"refine", "fixed"};

constexpr uint8_t kInfoMesh = kCommandInfo | kCommandMesh;

constexpr double kInf = 1e308;

using T = OptionType;

// GCC 12 warns about every member a designated initializer leaves to its
// default member initializer; that is the point of the syntax here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

// The table. Field order: id, cli, js, type, commands, faces, group, metavar,
// min, max, min_exclusive, max_exclusive, choices, list_size, default_on,
// default_text, unit, needs, doc.
const OptionSpec kOptions[] = {
    // ---- input (info and mesh)
    {.id = "json",
     .cli = "json",
     .js = "",
     .type = T::kFlag,
     .commands = kCommandInfo,
     .faces = kFaceCli,
     .group = "output",
     .doc = "print the analysis as JSON"},
    {.id = "size_field",
     .cli = "size-field",
     .js = "",
     .type = T::kText,
     .commands = kCommandInfo,
     .faces = kFaceCli,
     .group = "output",
     .metavar = "OUT.vtp",
     .needs = "a file name",
     .doc = "write the surface with the local vessel radius R and the edge length h the size "
            "options ask for, before meshing, as point data `radius` and `size` (VTK PolyData, "
            "the model's unit; the JS API: sizeField())"},
    {.id = "largest_component",
     .cli = "largest-component",
     .js = "largestComponentOnly",
     .type = T::kFlag,
     .commands = kInfoMesh,
     .group = "input",
     .doc = "keep only the largest connected component instead of refusing several"},
    {.id = "repair",
     .cli = "repair",
     .js = "repair",
     .type = T::kChoice,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "auto|off",
     .choices = kOffAuto,
     .default_text = "auto",
     .needs = "auto or off",
     .doc = "auto: split non-manifold edges and vertices into manifold sheets and close holes "
            "smaller than the hole fraction of the local radius; off: only the safe repairs "
            "(non-manifold surfaces are refused, holes stay openings)"},
    {.id = "hole_fraction",
     .cli = "hole-fraction",
     .js = "holeFraction",
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .default_text = "0.25",
     .unit = "fraction of R",
     .needs = "a fraction of the local vessel radius in [0, 1] (0: close no hole)",
     .doc = "a boundary loop whose equivalent radius sqrt(area/pi) is below F local vessel radii "
            "is a hole (closed by repair auto), else an opening"},
    {.id = "units",
     .cli = "units",
     .js = "units",
     .type = T::kChoice,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "U",
     .choices = kUnits,
     .needs = "mm, cm or m",
     .doc = "the unit of the file's numbers (default: guessed from the vessel radii and the "
            "model's size weighed against human anatomy, face labels hinting at cm; said "
            "certain, likely or unsure)"},
    {.id = "flow_extension",
     .cli = "flow-extension",
     .js = "flowExtension",
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "L",
     .min = 0,
     .max = 100,
     .default_text = "0",
     .unit = "local radii",
     .needs = "a length in local radii from 0 (none) to 100, or K=L for opening K",
     .doc = "extend the openings (K=L: opening K) straight along their normals by L local radii",
     .repeatable = true,
     .per_opening = PerOpening::kOptional},
    {.id = "keep_caps",
     .cli = "keep-caps",
     .js = "keepCaps",
     .type = T::kFlag,
     .commands = kInfoMesh,
     .group = "input",
     .doc = "keep planar caps as wall (else each recognised cap is removed and its rim becomes "
            "an opening)"},
    {.id = "smooth",
     .cli = "smooth",
     .js = "smooth",
     .type = T::kText,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "auto|off|N",
     .default_text = "auto",
     .needs = "auto, off or a number of smoothing passes from 1 to 1000",
     .doc = "smooth the surface before meshing (volume-preserving, within half a voxel): auto "
            "smooths voxel staircases only; N passes on any surface"},
    {.id = "clip",
     .cli = "clip",
     .js = "clip",
     .type = T::kChoice,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "off|auto",
     .choices = kOffAuto,
     .default_text = "auto",
     .needs = "off or auto",
     .doc = "auto: cut each blind vessel end open (closed or not, after the cuts given), "
            "perpendicular to the vessel; off: keep the blind ends (they are proposed)"},
    {.id = "clip_distance",
     .cli = "clip-distance",
     .js = "clipDistance",
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "D",
     .min = 0,
     .min_exclusive = true,
     .default_text = "1",
     .unit = "local radii",
     .needs = "a positive number of local vessel radii",
     .doc = "with clip auto: cut D local radii in from each vessel end's tip"},
    {.id = "clip_plane",
     .cli = "clip-plane",
     .js = "clipPlanes",
     .type = T::kNumbers,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "X,Y,Z,NX,NY,NZ",
     .list_size = 6,
     .unit = "length",
     .needs = "6 numbers X,Y,Z,NX,NY,NZ: a point of the cut and the normal pointing out of the "
              "part to keep",
     .doc = "cut the surface open with this plane (the side the normal points to is removed)",
     .repeatable = true},
    {.id = "clip_at",
     .cli = "clip-at",
     .js = "clipAt",
     .type = T::kNumbers,
     .commands = kInfoMesh,
     .group = "input",
     .metavar = "X,Y,Z",
     .list_size = 3,
     .unit = "length",
     .needs = "3 numbers X,Y,Z: a point on or near the vessel to cut across",
     .doc = "cut across the vessel at the surface point nearest X,Y,Z, perpendicular to the "
            "vessel, removing the side with less surface",
     .repeatable = true},
    // ---- size
    {.id = "size",
     .cli = "size",
     .js = "size",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "H",
     .min = 0,
     .min_exclusive = true,
     .unit = "length",
     .needs = "a positive length",
     .doc = "uniform target edge length"},
    {.id = "per_circumference",
     .cli = "per-circumference",
     .js = "perCircumference",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "N",
     .min = 3,
     .default_text = "20",
     .needs = "a number of edges per circumference >= 3",
     .doc = "h = 2 pi R(x) / N, R the local vessel radius (the default size mode)"},
    {.id = "size_min",
     .cli = "size-min",
     .js = "sizeMin",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "H",
     .min = 0,
     .default_text = "0",
     .unit = "length",
     .needs = "a length >= 0",
     .doc = "smallest edge length"},
    {.id = "size_max",
     .cli = "size-max",
     .js = "sizeMax",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "H",
     .min = 0,
     .min_exclusive = true,
     .unit = "length",
     .needs = "a positive length",
     .doc = "largest edge length"},
    {.id = "refine",
     .cli = "refine",
     .js = "refine",
     .type = T::kNumbers,
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "X,Y,Z,R,H",
     .list_size = 5,
     .unit = "length",
     .needs = "5 numbers X,Y,Z,R,H: a centre, a radius R > 0 and a size H > 0",
     .doc = "local refinement: edges of at most H within R of (X,Y,Z), graded out of it (wall "
            "and volume)",
     .repeatable = true},
    {.id = "gradation",
     .cli = "gradation",
     .js = "gradation",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "G",
     .min = 0,
     .default_text = "0.2",
     .needs = "a number >= 0 (size growth per unit length)",
     .doc = "the size grows at most G per unit length"},
    {.id = "curvature",
     .cli = "curvature",
     .js = "curvature",
     .commands = kInfoMesh,
     .group = "size",
     .metavar = "P",
     .min = 0,
     .default_text = "0",
     .needs = "a number of points per radian >= 0",
     .doc = "at least P edges per radian of curvature (0: off)"},
    {.id = "feature_angle",
     .cli = "feature-angle",
     .js = "featureAngle",
     .group = "size",
     .metavar = "A",
     .min = 0,
     .max = 180,
     .min_exclusive = true,
     .default_text = "60",
     .unit = "degrees",
     .needs = "an angle in degrees in (0, 180] (180: no sharp features)",
     .doc = "keep creases sharper than A degrees (180: none)"},
    {.id = "fidelity",
     .cli = "fidelity",
     .js = "fidelity",
     .group = "size",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .default_text = "0.1",
     .needs = "a fraction of h in [0, 1] (0: the wall may smooth over the input)",
     .doc = "input vertices farther than F h from the wall get a wall vertex pinned on them "
            "(0: bumps are smoothed over)"},
    // ---- volume
    {.id = "surface_only",
     .cli = "surface-only",
     .js = "surfaceOnly",
     .type = T::kFlag,
     .group = "volume",
     .doc = "write the remeshed wall alone (no caps, layers or volume)"},
    {.id = "inlet",
     .cli = "inlet",
     .js = "inlet",
     .type = T::kInteger,
     .group = "volume",
     .metavar = "K",
     .min = 1,
     .max = 1e6,
     .needs = "an opening number from 1 to 1000000 (as the analysis lists them)",
     .doc = "opening K (largest first) is `inlet` instead of the largest"},
    {.id = "core_size",
     .cli = "core-size",
     .js = "coreSize",
     .group = "volume",
     .metavar = "H",
     .min = 0,
     .default_text = "0",
     .unit = "length",
     .needs = "a length >= 0 (0: grow from the wall size)",
     .doc = "target size in the core of the lumen (0: the uniform size, or grown from the wall's)"},
    {.id = "name",
     .cli = "name",
     .js = "names",
     .type = T::kText,
     .group = "volume",
     .metavar = "NAME",
     .needs = "K=NAME with NAME 1-64 letters, digits, _ or -, starting with a letter",
     .doc = "the group name of opening K (default: the file's face name, else inlet / "
            "outlet_k)",
     .repeatable = true,
     .per_opening = PerOpening::kRequired},
    {.id = "max_elements",
     .cli = "max-elements",
     .js = "maxElements",
     .type = T::kInteger,
     .group = "volume",
     .metavar = "N",
     .min = 1000,
     .max = kMostElements,
     .default_text = "15000000",
     .needs = "a number of elements from 1000 to 1000000000",
     .doc = "the element budget: sizes that would make more wall triangles or tetrahedra are "
            "refused before meshing, the default size coarsened to fit (the default fits a 4 GB "
            "browser tab)"},
    {.id = "max_volume_change",
     .cli = "max-volume-change",
     .js = "maxVolumeChange",
     .group = "size",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .default_text = "0.05",
     .needs = "a fraction from 0 to 1",
     .doc = "the remeshed wall may enclose at most this fraction more or less volume than the "
            "input; beyond, the size is refused as too coarse for the vessels"},
    {.id = "verify",
     .cli = "verify",
     .js = "verify",
     .type = T::kFlag,
     .group = "volume",
     .doc = "check conformity and the boundary before writing; measure the layer heights"},
    // ---- layers
    {.id = "layers",
     .cli = "layers",
     .js = "layers",
     .type = T::kInteger,
     .group = "layers",
     .metavar = "N",
     .min = 0,
     .max = 100,
     .default_text = "4",
     .needs = "a number of layers from 0 (none) to 100",
     .doc = "viscous layers grown inward (0: none)"},
    {.id = "layer_thickness",
     .cli = "layer-thickness",
     .js = "layerThickness",
     .group = "layers",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .min_exclusive = true,
     .max_exclusive = true,
     .default_text = "0.2",
     .unit = "fraction of R",
     .needs = "a fraction of the local vessel radius in (0, 1)",
     .doc = "total thickness of the viscous layers, F R"},
    {.id = "first_layer",
     .cli = "first-layer",
     .js = "firstLayer",
     .group = "layers",
     .metavar = "H1",
     .min = 0,
     .min_exclusive = true,
     .unit = "length",
     .needs = "a positive height",
     .doc = "first layer height instead of a total thickness"},
    {.id = "growth",
     .cli = "growth",
     .js = "growth",
     .group = "layers",
     .metavar = "G",
     .min = 1,
     .max = 3,
     .default_text = "1",
     .needs = "a growth ratio from 1 to 3",
     .doc = "height ratio of consecutive layers"},
    {.id = "wall_thickness",
     .cli = "wall-thickness",
     .js = "wallThickness",
     .group = "layers",
     .metavar = "F",
     .min = 0,
     .max = 1,
     .min_exclusive = true,
     .max_exclusive = true,
     .unit = "fraction of R",
     .needs = "a fraction of the local vessel radius in (0, 1)",
     .doc = "grow the vessel wall outward, F R thick (e.g. 0.1; 4 layers)"},
    {.id = "wall_layers",
     .cli = "wall-layers",
     .js = "wallLayers",
     .type = T::kInteger,
     .group = "layers",
     .metavar = "N",
     .min = 0,
     .max = 100,
     .needs = "a number of layers from 0 (none) to 100",
     .doc = "layers of the vessel wall (alone: a wall of 0.1 R; 0: no wall)"},
    {.id = "first_layer_yplus",
     .cli = "first-layer-yplus",
     .js = "firstLayerYplus",
     .group = "layers",
     .metavar = "Y",
     .min = 0,
     .min_exclusive = true,
     .needs = "a positive target y+",
     .doc = "first layer height from this target y+ at the inlet, with the inlet velocity, "
            "density and viscosity (skin friction Cf = 0.026 Re^(-1/7), Re of the inlet's "
            "diameter); the height used is reported"},
    {.id = "inlet_velocity",
     .cli = "inlet-velocity",
     .js = "inletVelocity",
     .group = "layers",
     .metavar = "U",
     .min = 0,
     .min_exclusive = true,
     .unit = "m/s",
     .needs = "a positive velocity in m/s",
     .doc = "with a target y+: the mean velocity at the inlet, m/s"},
    {.id = "density",
     .cli = "density",
     .js = "density",
     .group = "layers",
     .metavar = "RHO",
     .min = 0,
     .min_exclusive = true,
     .default_text = "1060",
     .unit = "kg/m^3",
     .needs = "a positive density in kg/m^3",
     .doc = "with a target y+: the fluid's density, kg/m^3 (blood)"},
    {.id = "viscosity",
     .cli = "viscosity",
     .js = "viscosity",
     .group = "layers",
     .metavar = "MU",
     .min = 0,
     .min_exclusive = true,
     .default_text = "0.0035",
     .unit = "Pa s",
     .needs = "a positive dynamic viscosity in Pa s",
     .doc = "with a target y+: the fluid's dynamic viscosity, Pa s (blood)"},
    {.id = "tag_layer",
     .cli = "tag-layer",
     .js = "tagLayer",
     .type = T::kFlag,
     .group = "layers",
     .doc = "the viscous layer as its own volume group `boundary_layer`"},
    {.id = "prisms",
     .cli = "prisms",
     .js = "prisms",
     .type = T::kFlag,
     .group = "layers",
     .doc = "keep the layers' prisms (MSH type 6) instead of 3 tetrahedra each"},
    // ---- output
    {.id = "output",
     .cli = "output",
     .js = "",
     .type = T::kText,
     .faces = kFaceCli,
     .group = "output",
     .metavar = "OUT.msh",
     .needs = "a file name",
     .doc = "the file to write (also -o)"},
    {.id = "solver",
     .cli = "for",
     .js = "solver",
     .type = T::kChoice,
     .group = "output",
     .metavar = "SOLVER",
     .choices = kSolvers,
     .needs = "gmsh, openfoam, fenics or svfsi",
     .doc = "defaults for this solver: element types, format, MSH version, output unit "
            "(docs/outputs.md, Solver presets); options you give and the output's extension win"},
    {.id = "format",
     .cli = "format",
     .js = "format",
     .type = T::kChoice,
     .group = "output",
     .metavar = "F",
     .choices = kFormats,
     .needs = "msh, vtu, vtp, stl, mesh-complete or foam",
     .doc = "the file format (default: from the output's extension, .msh .vtu .vtp .stl, .zip "
            "or a folder for mesh-complete, .foam or a folder with system/controlDict for an "
            "OpenFOAM case; JS: msh); foam: constant/polyMesh in a folder (-o case/), around "
            "NAME.foam, or zipped (.zip)"},
    {.id = "output_units",
     .cli = "output-units",
     .js = "outputUnits",
     .type = T::kChoice,
     .group = "output",
     .metavar = "U",
     .choices = kUnits,
     .needs = "mm, cm or m",
     .doc = "convert the written mesh to this unit (default: the input's)"},
    {.id = "msh_version",
     .cli = "msh-version",
     .js = "mshVersion",
     .type = T::kChoice,
     .group = "output",
     .metavar = "V",
     .choices = kMshVersions,
     .default_text = "4.1",
     .needs = "4.1 or 2.2",
     .doc = "Gmsh MSH format version"},
    {.id = "family",
     .cli = "family",
     .js = "family",
     .type = T::kInteger,
     .group = "output",
     .metavar = "N",
     .min = 1,
     .max = 6,
     .default_text = "1",
     .needs = "a number of meshes from 1 (one mesh) to 6",
     .doc = "a mesh-independence family: N meshes, mesh k with every size divided by {ratio}^k "
            "(wall, core, refinements, gradation), all of one prepared surface; written as "
            "OUT_0 .. OUT_N-1 with a table OUT_family.csv and .json (JS: a zip) "
            "(docs/family.md)"},
    {.id = "ratio",
     .cli = "ratio",
     .js = "ratio",
     .group = "output",
     .metavar = "R",
     .min = 1.1,
     .max = 2,
     .default_text = "1.4",
     .needs = "a refinement ratio from 1.1 to 2 (1.3 or more for a grid convergence index)",
     .doc = "with {family}: the refinement ratio r between neighbouring meshes"},
    {.id = "family_layers",
     .cli = "family-layers",
     .js = "familyLayers",
     .type = T::kChoice,
     .group = "output",
     .metavar = "refine|fixed",
     .choices = kFamilyLayers,
     .default_text = "refine",
     .needs = "refine or fixed",
     .doc = "with {family}: refine: the boundary layer's first height divided by r^k with more "
            "layers of the same thickness; fixed: the first mesh's layers in every mesh (one "
            "first-layer height, the y+ choice)"},
    {.id = "report",
     .cli = "report",
     .js = "",
     .type = T::kText,
     .faces = kFaceCli,
     .group = "output",
     .metavar = "FILE.json",
     .needs = "a file name",
     .doc = "write the JSON report (the JS API returns it as `report`)"},
    {.id = "report_html",
     .cli = "report-html",
     .js = "",
     .type = T::kText,
     .faces = kFaceCli,
     .group = "output",
     .metavar = "FILE.html",
     .needs = "a file name",
     .doc = "write the methods report: one offline HTML page with pictures, quality "
            "histograms, parameters, openings, repairs, provenance, the family's table and a "
            "paragraph for a paper's methods section (JS: report())"},
    {.id = "quiet",
     .cli = "quiet",
     .js = "",
     .type = T::kFlag,
     .faces = kFaceCli,
     .group = "output",
     .doc = "print nothing but errors"},
    // ---- advanced
    {.id = "remesh",
     .cli = "no-remesh",
     .js = "remesh",
     .type = T::kFlag,
     .group = "advanced",
     .default_on = true,
     .doc = "remesh the surface (off: mesh the repaired input as it is)",
     .off_doc = "mesh the repaired input as it is, without remeshing"},
    {.id = "decimate",
     .cli = "decimate",
     .js = "decimate",
     .type = T::kChoice,
     .group = "advanced",
     .metavar = "auto|off",
     .choices = kOffAuto,
     .default_text = "auto",
     .needs = "auto or off",
     .doc = "auto: an input of 200,000 triangles or more, over 8 times the triangles the sizes "
            "ask for, is first decimated (edge collapses within 0.02 h of it, edges up to h/2), "
            "then remeshed; off: remeshed from the input as it is"},
    {.id = "threads",
     .cli = "threads",
     .js = "threads",
     .type = T::kInteger,
     .commands = kCommandInfo | kCommandMesh,
     .group = "advanced",
     .metavar = "N",
     .min = 0,
     .max = 256,
     .default_text = "0",
     .needs = "an integer from 0 (all cores) to 256",
     .doc = "threads for the preparation's loops, the vessel radius, the meshing of the wall's "
            "patches, the distance checks, the volume refinement (two slabs at once) and the "
            "volume optimizer's flips and smoothing (eight slabs) (0: all cores); the mesh is "
            "the same with any number; in the browser at most the threads the page's core has "
            "(api.threads: its cores on a cross-origin isolated page, else 1)"},
    {.id = "param",
     .cli = "param",
     .js = "param",
     .type = T::kChoice,
     .group = "advanced",
     .metavar = "MAP",
     .choices = kParams,
     .default_text = "lscm",
     .needs = "lscm, harmonic or floater",
     .doc = "the map of each patch to the plane"},
    {.id = "mesher2d",
     .cli = "mesher2d",
     .js = "mesher2d",
     .type = T::kChoice,
     .group = "advanced",
     .metavar = "M",
     .choices = kMeshers,
     .default_text = "frontal",
     .needs = "frontal, delaunay or adapt",
     .doc = "the planar mesher"},
    // ---- phantom
    {.id = "kind",
     .cli = "kind",
     .js = "kind",
     .type = T::kChoice,
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "KIND",
     .choices = kPhantomKinds,
     .default_text = "bifurcation",
     .needs = "bifurcation, tube, aneurysm, torus, tree, crossing, outlets or root",
     .doc = "the vessel model (tree: 17 branches, 11 openings; crossing: two vessels that touch "
            "and pass into each other, each its own shell; outlets: a capped tube with 20 tiny "
            "capped branches and 186 labelled faces, as SimVascular exports, written as .vtp to "
            "keep the labels; root: a short, wide root splitting into 2 branches that split "
            "again, 5 ends)"},
    {.id = "voxel",
     .cli = "voxel",
     .js = "voxel",
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "V",
     .min = 0,
     .min_exclusive = true,
     .default_text = "0.1",
     .unit = "length",
     .needs = "a positive voxel size",
     .doc = "voxel edge (the parent vessel's radius is 1)"},
    {.id = "noise",
     .cli = "noise",
     .js = "noise",
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "A",
     .min = 0,
     .default_text = "0",
     .needs = "a noise amplitude >= 0 (in voxels)",
     .doc = "voxel-value noise, in voxels"},
    {.id = "binary",
     .cli = "binary",
     .js = "binary",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .doc = "the raw staircase of a binary voxel mask (thresholded per voxel, not smoothed)"},
    {.id = "dirty",
     .cli = "dirty",
     .js = "dirty",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .doc = "add segmentation defects: small holes, a fin (non-manifold edge), touching holes "
            "(non-manifold vertex), duplicated faces, a flipped patch, a zero-area band"},
    {.id = "damaged_ends",
     .cli = "damaged-ends",
     .js = "damagedEnds",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .doc = "damage each opening as an image border does: folded rim triangles, a flap through "
            "the wall, a tiny loop, a twisted band (non-orientable)"},
    {.id = "seed",
     .cli = "seed",
     .js = "seed",
     .type = T::kInteger,
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "N",
     .min = 0,
     .max = 4294967295.0,
     .default_text = "1",
     .needs = "an integer from 0 to 4294967295",
     .doc = "noise seed"},
    {.id = "scale",
     .cli = "scale",
     .js = "scale",
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "S",
     .min = 0,
     .max = 1e30,
     .min_exclusive = true,
     .default_text = "1",
     .needs = "a positive scale factor up to 1e30 (STL coordinates are 32-bit floats)",
     .doc = "scale of the coordinates"},
    {.id = "open_ends",
     .cli = "closed",
     .js = "openEnds",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .default_on = true,
     .doc = "cut the vessel ends open (off: a closed surface with rounded ends)",
     .off_doc = "a closed surface with rounded ends"},
    {.id = "flat_caps",
     .cli = "flat-caps",
     .js = "flatCaps",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .doc = "close the cut ends by flat caps (a capped model, as SimVascular exports; the "
            "command writes OUT.vtp with SimVascular's face labels ModelFaceID: 1 the wall, 2.. "
            "each cap)"},
    {.id = "caps",
     .cli = "caps",
     .js = "caps",
     .type = T::kChoice,
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "flat|fan|dome",
     .choices = kCapShapes,
     .needs = "flat, fan or dome",
     .doc = "close the cut ends by caps of this shape: flat (as flat caps), fan (around an "
            "apex lifted 0.1 radius, as capping tools fill holes) or dome (smooth, bulging 0.3 "
            "to 1 radius, meeting the wall at a crease)"},
};

#pragma GCC diagnostic pop

std::string_view type_name(OptionType t) {
  switch (t) {
    case T::kNumber:
      return "number";
    case T::kInteger:
      return "integer";
    case T::kFlag:
      return "flag";
    case T::kChoice:
      return "choice";
    case T::kText:
      return "text";
    case T::kNumbers:
      return "numbers";
  }
  return "";
}

bool parse_number(std::string_view text, double& out) {
  // strtod needs a terminated string; from_chars(double) is missing in libc++ 14.
  std::string s(text);
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

Status needs(const OptionSpec& spec) {
  return Status::BadOption(std::string(spec.id), "needs " + std::string(spec.needs));
}

bool in_range(const OptionSpec& spec, double x) {
  if (spec.min_exclusive ? !(x > spec.min) : !(x >= spec.min)) return false;
  if (spec.max_exclusive ? !(x < spec.max) : !(x <= spec.max)) return false;
  return spec.type != T::kInteger || x == std::floor(x);
}

/// The shortest of %.15g .. %.17g that reads back to x exactly.
std::string shortest_text(double x) {
  char buf[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

std::string option_name(const OptionSpec& spec, OptionFace face) {
  return face == kFaceCli ? "--" + std::string(spec.cli) : std::string(spec.js);
}

}  // namespace

bool valid_group_name(std::string_view name) {
  if (name.empty() || name.size() > 64) return false;
  if (!((name[0] >= 'a' && name[0] <= 'z') || (name[0] >= 'A' && name[0] <= 'Z'))) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
          c == '-'))
      return false;
  return true;
}

std::span<const OptionSpec> option_table() { return kOptions; }

const OptionSpec* find_option(std::string_view id) {
  for (const OptionSpec& s : kOptions)
    if (s.id == id) return &s;
  return nullptr;
}

const OptionSpec* find_cli_option(std::string_view cli, OptionCommand command) {
  for (const OptionSpec& s : kOptions)
    if ((s.faces & kFaceCli) && (s.commands & command) && s.cli == cli) return &s;
  return nullptr;
}

const OptionSpec* find_js_option(std::string_view js, OptionCommand command) {
  for (const OptionSpec& s : kOptions)
    if ((s.faces & kFaceJs) && (s.commands & command) && s.js == js) return &s;
  return nullptr;
}

Status check_option_value(const OptionSpec& spec, const OptionValue& v) {
  if (v.opening < 0 || (v.opening > 0 && spec.per_opening == PerOpening::kNo) ||
      (v.opening == 0 && spec.per_opening == PerOpening::kRequired))
    return Status::BadOption(std::string(spec.id), "needs K=VALUE with K an opening number >= 1");
  switch (spec.type) {
    case T::kNumber:
    case T::kInteger:
      if (!std::isfinite(v.number) || !in_range(spec, v.number)) return needs(spec);
      break;
    case T::kChoice: {
      bool found = false;
      for (std::string_view c : spec.choices) found = found || c == v.text;
      if (!found) return needs(spec);
      break;
    }
    case T::kNumbers:
      if (v.numbers.size() != size_t(spec.list_size)) return needs(spec);
      for (double x : v.numbers)
        if (!std::isfinite(x) || !in_range(spec, x)) return needs(spec);
      break;
    case T::kText:
      if (v.text.empty()) return needs(spec);
      break;
    case T::kFlag:
      break;
  }
  return Status::Ok();
}

Result<OptionValue> parse_option_text(const OptionSpec& spec, std::string_view text) {
  OptionValue v;
  if (spec.per_opening != PerOpening::kNo) {
    const size_t eq = text.find('=');
    double k = 0;
    if (eq != std::string_view::npos && parse_number(text.substr(0, eq), k)) {
      if (k < 1 || k != std::floor(k) || k > 1e6)
        return Status::BadOption(std::string(spec.id),
                                 "needs K=VALUE with K an opening number >= 1");
      v.opening = int(k);
      text = text.substr(eq + 1);
    }
  }
  switch (spec.type) {
    case T::kNumber:
    case T::kInteger:
      if (!parse_number(text, v.number)) return needs(spec);
      break;
    case T::kNumbers: {
      size_t start = 0;
      while (start <= text.size()) {
        size_t comma = text.find(',', start);
        if (comma == std::string_view::npos) comma = text.size();
        double x = 0;
        if (!parse_number(text.substr(start, comma - start), x)) return needs(spec);
        v.numbers.push_back(x);
        start = comma + 1;
      }
      break;
    }
    case T::kChoice:
    case T::kText:
      v.text = std::string(text);
      break;
    case T::kFlag:
      v.flag = !spec.default_on;
      break;
  }
  Status st = check_option_value(spec, v);
  if (!st.ok()) return st;
  return v;
}

Status apply_option(MeshJobOptions& o, const OptionSpec& spec, const OptionValue& v) {
  const std::string_view id = spec.id;
  SizeOptions& size = o.remesh_options.size;
  const double x = v.number;
  if (id == "size") {
    size.mode = SizeMode::kUniform;
    size.size = x;
    o.size_given = true;
  } else if (id == "per_circumference") {
    size.mode = SizeMode::kPerCircumference;
    size.per_circumference = x;
    o.size_given = true;
  } else if (id == "size_min") {
    size.size_min = x;
  } else if (id == "size_max") {
    size.size_max = x;
  } else if (id == "refine") {
    if (!(v.numbers[3] > 0) || !(v.numbers[4] > 0)) return needs(spec);
    size.spheres.push_back(
        {{v.numbers[0], v.numbers[1], v.numbers[2]}, v.numbers[3], v.numbers[4]});
  } else if (id == "gradation") {
    size.gradation = x;
  } else if (id == "curvature") {
    size.curvature_points = x;
  } else if (id == "feature_angle") {
    o.remesh_options.feature_angle_degrees = x;
  } else if (id == "fidelity") {
    o.remesh_options.fidelity = x;
    o.remesh_options.fidelity_rounds = x > 0 ? RemeshOptions{}.fidelity_rounds : 0;
    o.remesh_options.fidelity_size_rounds = x > 0 ? RemeshOptions{}.fidelity_size_rounds : 0;
  } else if (id == "inlet") {
    o.inlet = int(x) - 1;
  } else if (id == "max_volume_change") {
    o.max_volume_change = x;
  } else if (id == "max_elements") {
    o.max_elements = x;
  } else if (id == "core_size") {
    o.core_size = x;
  } else if (id == "layers") {
    o.viscous.layers = int(x);
  } else if (id == "wall_layers") {
    o.vessel.layers = int(x);
  } else if (id == "layer_thickness") {
    o.viscous.thickness_fraction = x;
  } else if (id == "wall_thickness") {
    o.vessel.thickness_fraction = x;
    o.wall_thickness_given = true;
    if (o.vessel.layers == 0) o.vessel.layers = 4;
  } else if (id == "first_layer") {
    o.viscous.first_height = x;
  } else if (id == "growth") {
    o.viscous.growth = x;
  } else if (id == "first_layer_yplus") {
    o.yplus.yplus = x;
  } else if (id == "inlet_velocity") {
    o.yplus.velocity = x;
  } else if (id == "density") {
    o.yplus.density = x;
  } else if (id == "viscosity") {
    o.yplus.viscosity = x;
  } else if (id == "solver") {
    // The preset's defaults are applied by apply_options (solver_preset.h).
    if (v.text == "gmsh") o.solver = Solver::kGmsh;
    if (v.text == "openfoam") o.solver = Solver::kOpenFoam;
    if (v.text == "fenics") o.solver = Solver::kFenics;
    if (v.text == "svfsi") o.solver = Solver::kSvFsi;
  } else if (id == "threads") {
    o.threads = int(x);
  } else if (id == "param") {
    o.remesh_options.param = v.text == "harmonic"  ? ParamMethod::kHarmonic
                             : v.text == "floater" ? ParamMethod::kFloater
                                                   : ParamMethod::kLscm;
  } else if (id == "mesher2d") {
    o.remesh_options.patch.mesher = v.text == "delaunay" ? Mesher2D::kDelaunay
                                    : v.text == "adapt"  ? Mesher2D::kAdapt
                                                         : Mesher2D::kFrontal;
  } else if (id == "msh_version") {
    o.msh_version = v.text == "2.2" ? MshVersion::k22 : MshVersion::k41;
  } else if (id == "units") {
    o.prepare.units = parse_unit(v.text);
  } else if (id == "format") {
    auto f = parse_format(v.text);
    if (!f.ok()) return needs(spec);
    o.format = f.value();
  } else if (id == "output_units") {
    o.output_units = parse_unit(v.text);
  } else if (id == "flow_extension") {
    if (v.opening > 0)
      o.prepare.flow_extensions.emplace_back(v.opening - 1, x);
    else
      o.prepare.flow_extension = x;
  } else if (id == "smooth") {
    auto mode = parse_smoothing(v.text);
    if (!mode) return needs(spec);
    o.prepare.smoothing = *mode;
  } else if (id == "clip") {
    o.prepare.clip_auto = v.text == "auto";
  } else if (id == "clip_distance") {
    o.prepare.clip_distance = x;
  } else if (id == "clip_plane") {
    const double n = pm::hypot(v.numbers[3], v.numbers[4], v.numbers[5]);
    if (!(n > 0)) return needs(spec);
    o.prepare.clip_planes.push_back({{v.numbers[0], v.numbers[1], v.numbers[2]},
                                     {v.numbers[3] / n, v.numbers[4] / n, v.numbers[5] / n}});
  } else if (id == "clip_at") {
    o.prepare.clip_at.push_back({v.numbers[0], v.numbers[1], v.numbers[2]});
  } else if (id == "keep_caps") {
    o.prepare.keep_caps = v.flag;
  } else if (id == "name") {
    if (!valid_group_name(v.text)) return needs(spec);
    o.opening_names.emplace_back(v.opening - 1, v.text);
  } else if (id == "largest_component") {
    o.prepare.largest_component_only = v.flag;
  } else if (id == "repair") {
    o.prepare.repair = v.text == "auto";
  } else if (id == "hole_fraction") {
    o.prepare.hole_fraction = x;
  } else if (id == "remesh") {
    o.remesh = v.flag;
  } else if (id == "decimate") {
    o.remesh_options.decimate = v.text == "auto";
  } else if (id == "surface_only") {
    o.volume = !v.flag;
  } else if (id == "verify") {
    o.verify = v.flag;
  } else if (id == "tag_layer") {
    o.tag_layer = v.flag;
  } else if (id == "prisms") {
    o.keep_prisms = v.flag;
  } else if (id == "family") {
    o.family = int(x);
  } else if (id == "ratio") {
    o.family_ratio = x;
  } else if (id == "family_layers") {
    o.family_layers = v.text == "fixed" ? FamilyLayers::kFixed : FamilyLayers::kRefine;
  } else if (spec.faces != kFaceCli || !(spec.commands & (kCommandInfo | kCommandMesh))) {
    // Options of the CLI alone (paths, printing) are the CLI's business;
    // any other id must have been handled above.
    return Status::Internal("option " + std::string(id) + " is not applied to the job");
  }
  return Status::Ok();
}

Status apply_option(PhantomOptions& o, const OptionSpec& spec, const OptionValue& v) {
  const std::string_view id = spec.id;
  if (id == "kind") {
    o.kind = v.text == "tube"       ? PhantomKind::kTube
             : v.text == "aneurysm" ? PhantomKind::kAneurysm
             : v.text == "torus"    ? PhantomKind::kTorus
             : v.text == "tree"     ? PhantomKind::kTree
             : v.text == "crossing" ? PhantomKind::kCrossing
             : v.text == "outlets"  ? PhantomKind::kOutlets
             : v.text == "root"     ? PhantomKind::kRoot
                                    : PhantomKind::kBifurcation;
  } else if (id == "voxel") {
    o.voxel = v.number;
  } else if (id == "noise") {
    o.noise = v.number;
  } else if (id == "binary") {
    o.binary = v.flag;
  } else if (id == "dirty") {
    o.dirty = v.flag;
  } else if (id == "damaged_ends") {
    o.damaged_ends = v.flag;
  } else if (id == "seed") {
    o.seed = uint32_t(v.number);
  } else if (id == "scale") {
    o.scale = v.number;
  } else if (id == "open_ends") {
    o.open_ends = v.flag;
  } else if (id == "flat_caps") {
    o.flat_caps = v.flag;
  } else if (id == "caps") {
    o.flat_caps = true;
    o.cap_shape = v.text == "fan"    ? PhantomCapShape::kFan
                  : v.text == "dome" ? PhantomCapShape::kDome
                                     : PhantomCapShape::kFlat;
  } else {
    return Status::Internal("option " + std::string(id) + " is not a phantom option");
  }
  return Status::Ok();
}

Status set_option_text(MeshJobOptions& options, std::string_view id, std::string_view text) {
  const OptionSpec* spec = find_option(id);
  if (!spec) return Status::Internal("unknown option id " + std::string(id));
  auto v = parse_option_text(*spec, text);
  if (!v.ok()) return v.status();
  return apply_option(options, *spec, v.value());
}

std::string option_value_text(const OptionSpec& spec, const OptionValue& v) {
  std::string text = v.opening > 0 ? std::to_string(v.opening) + "=" : "";
  switch (spec.type) {
    case T::kNumber:
    case T::kInteger:
      return text + shortest_text(v.number);
    case T::kFlag:
      return text + (v.flag ? "true" : "false");
    case T::kNumbers:
      for (size_t i = 0; i < v.numbers.size(); ++i) {
        if (i) text += ',';
        text += shortest_text(v.numbers[i]);
      }
      return text;
    case T::kChoice:
    case T::kText:
      break;
  }
  return text + v.text;
}

std::string options_provenance(std::span<const std::pair<const OptionSpec*, OptionValue>> values) {
  std::string out;
  for (const auto& [spec, value] : values) {
    // Paths, printing and the thread count change no mesh.
    if (spec->faces == kFaceCli || spec->id == "threads") continue;
    if (!out.empty()) out += " ";
    out += std::string(spec->id) + "=" + option_value_text(*spec, value);
  }
  return out;
}

std::string phrase_options(std::string_view message, OptionFace face) {
  std::string out;
  out.reserve(message.size());
  size_t i = 0;
  while (i < message.size()) {
    if (message[i] == '{') {
      const size_t close = message.find('}', i);
      if (close != std::string_view::npos) {
        if (const OptionSpec* spec = find_option(message.substr(i + 1, close - i - 1))) {
          out += option_name(*spec, face);
          i = close + 1;
          continue;
        }
      }
    }
    out += message[i++];
  }
  return out;
}

std::string phrase_error(const Status& status, OptionFace face) {
  std::string message = phrase_options(status.message(), face);
  if (status.kind() == ErrorKind::kBadOption) {
    if (const OptionSpec* spec = find_option(status.option()))
      return option_name(*spec, face) + " " + message;
  }
  return message;
}

std::string option_table_json() {
  JsonWriter j;
  j.begin_array();
  for (const OptionSpec& s : kOptions) {
    j.begin_object();
    j.key("id").value(s.id);
    j.key("cli").value(s.cli);
    j.key("js").value(s.js);
    j.key("type").value(type_name(s.type));
    j.key("commands").begin_array();
    for (auto [bit, name] : {std::pair{kCommandInfo, "info"}, std::pair{kCommandMesh, "mesh"},
                             std::pair{kCommandPhantom, "phantom"}})
      if (s.commands & bit) j.value(name);
    j.end_array();
    j.key("faces").begin_array();
    if (s.faces & kFaceCli) j.value("cli");
    if (s.faces & kFaceJs) j.value("js");
    j.end_array();
    j.key("group").value(s.group);
    j.key("metavar").value(s.metavar);
    if (s.min > -kInf) j.key("min").value(s.min);
    if (s.max < kInf) j.key("max").value(s.max);
    j.key("minExclusive").value(s.min_exclusive);
    j.key("maxExclusive").value(s.max_exclusive);
    j.key("choices").begin_array();
    for (std::string_view c : s.choices) j.value(c);
    j.end_array();
    j.key("listSize").value(s.list_size);
    j.key("defaultOn").value(s.default_on);
    j.key("default").value(s.default_text);
    j.key("unit").value(s.unit);
    j.key("needs").value(s.needs);
    j.key("doc").value(s.doc);
    j.key("offDoc").value(s.off_doc);
    j.key("repeatable").value(s.repeatable);
    j.key("perOpening")
        .value(s.per_opening == PerOpening::kNo         ? "no"
               : s.per_opening == PerOpening::kOptional ? "optional"
                                                        : "required");
    j.end_object();
  }
  j.end_array();
  return j.str();
}

}  // namespace vm
