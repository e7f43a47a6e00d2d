// The rows of the output, advanced and phantom options (option_rows.h):
// what each takes, its help, and where its value goes in the job's (or the
// phantom's) options.
#include "core/pipeline/option_rows.h"
#include "core/pipeline/option_values.h"
#include "core/pipeline/write_outputs.h"

namespace vm::option_rows {
namespace {

constexpr std::string_view kParams[] = {"lscm", "harmonic", "floater"};
constexpr std::string_view kMeshers[] = {"frontal", "delaunay", "adapt"};
constexpr std::string_view kMshVersions[] = {"4.1", "2.2"};
constexpr std::string_view kPhantomKinds[] = {"bifurcation", "tube",     "aneurysm", "torus",
                                              "tree",        "crossing", "outlets",  "root"};
constexpr std::string_view kCapShapes[] = {"flat", "fan", "dome"};
constexpr std::string_view kFormats[] = {"msh", "vtu", "vtp", "stl", "mesh-complete", "foam"};
constexpr std::string_view kSolvers[] = {"gmsh", "openfoam", "fenics", "svfsi"};
constexpr std::string_view kFamilyLayers[] = {"refine", "fixed"};
constexpr std::string_view kSolverAliases[] = {"for"};
constexpr std::string_view kOpenEndsAliases[] = {"closed"};

// GCC 12 warns about every member a designated initializer leaves to its
// default member initializer; that is the point of the syntax here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

const OptionSpec kRows[] = {
    // ---- output
    {.key = "output",
     .type = T::kText,
     .faces = kFaceCli,
     .group = "output",
     .metavar = "OUT.msh",
     .needs = "a file name",
     .doc = "the file to write (also -o)"},
    {.key = "solver",
     .type = T::kChoice,
     .group = "output",
     .metavar = "SOLVER",
     .choices = kSolvers,
     .needs = "gmsh, openfoam, fenics or svfsi",
     .doc = "defaults for this solver: element types, format, MSH version, output unit "
            "(docs/outputs.md, Solver presets); options you give and the output's extension win",
     .cli_aliases = kSolverAliases,
     .set =
         [](O& o, const V& v) {
           o.solver = solver_of(v.text);
           return true;
         },
     .read = [](const O& o) -> std::string { return std::string(solver_word(o.solver)); }},
    {.key = "format",
     .type = T::kChoice,
     .group = "output",
     .metavar = "F",
     .choices = kFormats,
     .needs = "msh, vtu, vtp, stl, mesh-complete or foam",
     .doc = "the file format (default: from the output's extension, .msh .vtu .vtp .stl, .zip "
            "or a folder for mesh-complete, .foam or a folder with system/controlDict for an "
            "OpenFOAM case; JS: msh); foam: constant/polyMesh in a folder (-o case/), around "
            "NAME.foam, or zipped (.zip)",
     .set =
         [](O& o, const V& v) {
           auto f = parse_format(v.text);
           if (!f.ok()) return false;
           o.format = f.value();
           return true;
         },
     .read = [](const O& o) -> std::string {
       return o.format ? std::string(format_name(*o.format)) : "";
     }},
    {.key = "outputUnits",
     .type = T::kChoice,
     .group = "output",
     .metavar = "U",
     .choices = kUnits,
     .needs = "mm, cm or m",
     .doc = "convert the written mesh to this unit (default: the input's)",
     .set =
         [](O& o, const V& v) {
           o.output_units = parse_unit(v.text);
           return true;
         },
     .read = [](const O& o) -> std::string { return std::string(unit_symbol(o.output_units)); }},
    {.key = "mshVersion",
     .type = T::kChoice,
     .group = "output",
     .metavar = "V",
     .choices = kMshVersions,
     .needs = "4.1 or 2.2",
     .doc = "Gmsh MSH format version",
     .set =
         [](O& o, const V& v) {
           o.msh_version = msh_version_of(v.text);
           return true;
         },
     .read = [](const O& o) -> std::string {
       return std::string(msh_version_word(o.msh_version));
     }},
    {.key = "mshBinary",
     .type = T::kFlag,
     .group = "output",
     .doc = "write the MSH file in Gmsh's binary layout (MSH 4.1 only, little-endian): the same "
            "mesh, opened about 10 times faster by Gmsh and meshio, in about 1.2 times the bytes "
            "(8-byte tags)",
     .set =
         [](O& o, const V& v) {
           o.msh_binary = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.msh_binary); }},
    {.key = "vtkCompress",
     .type = T::kFlag,
     .group = "output",
     .doc = "compress the arrays of a VTU or VTP file with zlib (VTK's vtkZLibDataCompressor "
            "blocks, read by ParaView, VTK and meshio): the same mesh in about 0.3 times the "
            "bytes, a little slower to write and to read; the mesh-complete folder stays raw",
     .set =
         [](O& o, const V& v) {
           o.vtk_compress = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.vtk_compress); }},
    {.key = "foamBinary",
     .type = T::kFlag,
     .group = "output",
     .doc = "write the OpenFOAM case's points, faces, owner and neighbour in OpenFOAM's binary "
            "format (32-bit labels, 64-bit scalars, little-endian): the same mesh, the exact "
            "coordinates, in about 0.7 times the bytes",
     .set =
         [](O& o, const V& v) {
           o.foam_binary = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.foam_binary); }},
    {.key = "family",
     .type = T::kInteger,
     .group = "output",
     .metavar = "N",
     .min = 1,
     .max = 6,
     .needs = "a number of meshes from 1 (one mesh) to 6",
     .doc = "a mesh-independence family: N meshes, mesh k with every size divided by {ratio}^k "
            "(wall, core, refinements, gradation), all of one prepared surface; written as "
            "OUT_0 .. OUT_N-1 with a table OUT_family.csv and .json (JS: a zip) "
            "(docs/family.md)",
     .set =
         [](O& o, const V& v) {
           o.family = int(v.number);
           return true;
         },
     .read = [](const O& o) -> std::string { return std::to_string(o.family); }},
    {.key = "ratio",
     .group = "output",
     .metavar = "R",
     .min = 1.1,
     .max = 2,
     .needs = "a refinement ratio from 1.1 to 2 (1.3 or more for a grid convergence index)",
     .doc = "with {family}: the refinement ratio r between neighbouring meshes",
     .set =
         [](O& o, const V& v) {
           o.family_ratio = v.number;
           return true;
         },
     .read = [](const O& o) -> std::string { return num(o.family_ratio); }},
    {.key = "familyLayers",
     .type = T::kChoice,
     .group = "output",
     .metavar = "refine|fixed",
     .choices = kFamilyLayers,
     .needs = "refine or fixed",
     .doc = "with {family}: refine: the boundary layer's first height divided by r^k with more "
            "layers of the same thickness; fixed: the first mesh's layers in every mesh (one "
            "first-layer height, the y+ choice)",
     .set =
         [](O& o, const V& v) {
           o.family_layers = family_layers_of(v.text);
           return true;
         },
     .read = [](const O& o) -> std::string {
       return std::string(family_layers_word(o.family_layers));
     }},
    {.key = "report",
     .type = T::kText,
     .faces = kFaceCli,
     .group = "output",
     .metavar = "FILE.json",
     .needs = "a file name",
     .doc = "write the JSON report (the JS API returns it as `report`)"},
    {.key = "reportHtml",
     .type = T::kText,
     .faces = kFaceCli,
     .group = "output",
     .metavar = "FILE.html",
     .needs = "a file name",
     .doc = "write the methods report: one offline HTML page with pictures, quality "
            "histograms, parameters, openings, repairs, provenance, the family's table and a "
            "paragraph for a paper's methods section (JS: report())"},
    {.key = "quiet",
     .type = T::kFlag,
     .faces = kFaceCli,
     .group = "output",
     .doc = "print nothing but errors"},
    // ---- advanced
    {.key = "remesh",
     .type = T::kFlag,
     .group = "advanced",
     .default_on = true,
     .doc = "remesh the surface (off: mesh the repaired input as it is)",
     .off_doc = "mesh the repaired input as it is, without remeshing",
     .set =
         [](O& o, const V& v) {
           o.remesh = v.flag;
           return true;
         },
     .read = [](const O& o) -> std::string { return flag(o.remesh); }},
    {.key = "decimate",
     .type = T::kChoice,
     .group = "advanced",
     .metavar = "auto|off",
     .choices = kOffAuto,
     .needs = "auto or off",
     .doc = "auto: an input of 200,000 triangles or more, over 8 times the triangles the sizes "
            "ask for, is first decimated (edge collapses within 0.02 h of it, edges up to h/2), "
            "then remeshed; off: remeshed from the input as it is",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.decimate = v.text == "auto";
           return true;
         },
     .read = [](const O& o) -> std::string { return o.remesh_options.decimate ? "auto" : "off"; }},
    {.key = "threads",
     .type = T::kInteger,
     .commands = kCommandInfo | kCommandMesh,
     .group = "advanced",
     .metavar = "N",
     .min = 0,
     .max = 256,
     .needs = "an integer from 0 (all cores) to 256",
     .doc = "threads for the preparation's loops, the vessel radius, the meshing of the wall's "
            "patches, the distance checks, the volume refinement (two slabs at once) and the "
            "volume optimizer's flips and smoothing (eight slabs) (0: all cores); the mesh is "
            "the same with any number; in the browser at most the threads the page's core has "
            "(api.threads: its cores on a cross-origin isolated page, else 1)",
     .set =
         [](O& o, const V& v) {
           o.threads = int(v.number);
           return true;
         },
     .read = [](const O& o) -> std::string { return std::to_string(o.threads); }},
    {.key = "param",
     .type = T::kChoice,
     .group = "advanced",
     .metavar = "MAP",
     .choices = kParams,
     .needs = "lscm, harmonic or floater",
     .doc = "the map of each patch to the plane",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.param = param_method_of(v.text);
           return true;
         },
     .read = [](const O& o) -> std::string {
       return std::string(param_method_word(o.remesh_options.param));
     }},
    {.key = "mesher2d",
     .type = T::kChoice,
     .group = "advanced",
     .metavar = "M",
     .choices = kMeshers,
     .needs = "frontal, delaunay or adapt",
     .doc = "the planar mesher",
     .set =
         [](O& o, const V& v) {
           o.remesh_options.patch.mesher = mesher2d_of(v.text);
           return true;
         },
     .read = [](const O& o) -> std::string {
       return std::string(mesher2d_word(o.remesh_options.patch.mesher));
     }},
    // ---- phantom
    {.key = "kind",
     .type = T::kChoice,
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "KIND",
     .choices = kPhantomKinds,
     .needs = "bifurcation, tube, aneurysm, torus, tree, crossing, outlets or root",
     .doc = "the vessel model (tree: 17 branches, 11 openings; crossing: two vessels that touch "
            "and pass into each other, each its own shell; outlets: a capped tube with 20 tiny "
            "capped branches and 186 labelled faces, as SimVascular exports, written as .vtp to "
            "keep the labels; root: a short, wide root splitting into 2 branches that split "
            "again, 5 ends)",
     .set_phantom =
         [](P& o, const V& v) {
           o.kind = phantom_kind_of(v.text);
           return true;
         },
     .read_phantom = [](const P& o) -> std::string {
       return std::string(phantom_kind_word(o.kind));
     }},
    {.key = "voxel",
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "V",
     .min = 0,
     .min_exclusive = true,
     .unit = "length",
     .needs = "a positive voxel size",
     .doc = "voxel edge (the parent vessel's radius is 1)",
     .set_phantom =
         [](P& o, const V& v) {
           o.voxel = v.number;
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return num(o.voxel); }},
    {.key = "noise",
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "A",
     .min = 0,
     .needs = "a noise amplitude >= 0 (in voxels)",
     .doc = "voxel-value noise, in voxels",
     .set_phantom =
         [](P& o, const V& v) {
           o.noise = v.number;
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return num(o.noise); }},
    {.key = "binary",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .doc = "the raw staircase of a binary voxel mask (thresholded per voxel, not smoothed)",
     .set_phantom =
         [](P& o, const V& v) {
           o.binary = v.flag;
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return flag(o.binary); }},
    {.key = "dirty",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .doc = "add segmentation defects: small holes, a fin (non-manifold edge), touching holes "
            "(non-manifold vertex), duplicated faces, a flipped patch, a zero-area band",
     .set_phantom =
         [](P& o, const V& v) {
           o.dirty = v.flag;
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return flag(o.dirty); }},
    {.key = "damagedEnds",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .doc = "damage each opening as an image border does: folded rim triangles, a flap through "
            "the wall, a tiny loop, a twisted band (non-orientable)",
     .set_phantom =
         [](P& o, const V& v) {
           o.damaged_ends = v.flag;
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return flag(o.damaged_ends); }},
    {.key = "seed",
     .type = T::kInteger,
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "N",
     .min = 0,
     .max = 4294967295.0,
     .needs = "an integer from 0 to 4294967295",
     .doc = "noise seed",
     .set_phantom =
         [](P& o, const V& v) {
           o.seed = uint32_t(v.number);
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return std::to_string(o.seed); }},
    {.key = "scale",
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "S",
     .min = 0,
     .max = 1e30,
     .min_exclusive = true,
     .needs = "a positive scale factor up to 1e30 (STL coordinates are 32-bit floats)",
     .doc = "scale of the coordinates",
     .set_phantom =
         [](P& o, const V& v) {
           o.scale = v.number;
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return num(o.scale); }},
    {.key = "openEnds",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .default_on = true,
     .doc = "cut the vessel ends open (off: a closed surface with rounded ends)",
     .off_doc = "a closed surface with rounded ends",
     .cli_aliases = kOpenEndsAliases,
     .set_phantom =
         [](P& o, const V& v) {
           o.open_ends = v.flag;
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return flag(o.open_ends); }},
    {.key = "flatCaps",
     .type = T::kFlag,
     .commands = kCommandPhantom,
     .group = "phantom",
     .doc = "close the cut ends by flat caps (a capped model, as SimVascular exports; the "
            "command writes OUT.vtp with SimVascular's face labels ModelFaceID: 1 the wall, 2.. "
            "each cap)",
     .set_phantom =
         [](P& o, const V& v) {
           o.flat_caps = v.flag;
           return true;
         },
     .read_phantom = [](const P& o) -> std::string { return flag(o.flat_caps); }},
    {.key = "caps",
     .type = T::kChoice,
     .commands = kCommandPhantom,
     .group = "phantom",
     .metavar = "flat|fan|dome",
     .choices = kCapShapes,
     .needs = "flat, fan or dome",
     .doc = "close the cut ends by caps of this shape: flat (as flat caps), fan (around an "
            "apex lifted 0.1 radius, as capping tools fill holes) or dome (smooth, bulging 0.3 "
            "to 1 radius, meeting the wall at a crease)",
     .set_phantom =
         [](P& o, const V& v) {
           o.flat_caps = true;
           o.cap_shape = cap_shape_of(v.text);
           return true;
         },
     .read_phantom = [](const P& o) -> std::string {
       return o.flat_caps ? std::string(cap_shape_word(o.cap_shape)) : "";
     }},
};

#pragma GCC diagnostic pop

}  // namespace

std::span<const OptionSpec> output_advanced_phantom() { return kRows; }

}  // namespace vm::option_rows
