// The text forms of option values (option_values.h).
#include "core/pipeline/option_values.h"

#include <charconv>
#include <span>
#include <utility>

#include "core/pipeline/write_outputs.h"

namespace vm {
namespace {

template <class E>
using Words = std::span<const std::pair<E, std::string_view>>;

template <class E>
E value_of(Words<E> words, std::string_view word) {
  for (const auto& [value, w] : words)
    if (w == word) return value;
  return words.front().first;
}

template <class E>
std::string_view word_of(Words<E> words, E value) {
  for (const auto& [v, w] : words)
    if (v == value) return w;
  return "";
}

constexpr std::pair<ParamMethod, std::string_view> kParamWords[] = {
    {ParamMethod::kLscm, "lscm"},
    {ParamMethod::kHarmonic, "harmonic"},
    {ParamMethod::kFloater, "floater"}};
constexpr std::pair<Mesher2D, std::string_view> kMesherWords[] = {{Mesher2D::kFrontal, "frontal"},
                                                                  {Mesher2D::kDelaunay, "delaunay"},
                                                                  {Mesher2D::kAdapt, "adapt"}};
constexpr std::pair<MshVersion, std::string_view> kMshWords[] = {{MshVersion::k41, "4.1"},
                                                                 {MshVersion::k22, "2.2"}};
constexpr std::pair<Solver, std::string_view> kSolverWords[] = {{Solver::kNone, ""},
                                                                {Solver::kGmsh, "gmsh"},
                                                                {Solver::kOpenFoam, "openfoam"},
                                                                {Solver::kFenics, "fenics"},
                                                                {Solver::kSvFsi, "svfsi"}};
constexpr std::pair<FamilyLayers, std::string_view> kFamilyLayerWords[] = {
    {FamilyLayers::kRefine, "refine"}, {FamilyLayers::kFixed, "fixed"}};
constexpr std::pair<PhantomKind, std::string_view> kKindWords[] = {
    {PhantomKind::kBifurcation, "bifurcation"},
    {PhantomKind::kTube, "tube"},
    {PhantomKind::kAneurysm, "aneurysm"},
    {PhantomKind::kTorus, "torus"},
    {PhantomKind::kTree, "tree"},
    {PhantomKind::kCrossing, "crossing"},
    {PhantomKind::kOutlets, "outlets"},
    {PhantomKind::kRoot, "root"}};
constexpr std::pair<PhantomCapShape, std::string_view> kCapWords[] = {
    {PhantomCapShape::kFlat, "flat"},
    {PhantomCapShape::kFan, "fan"},
    {PhantomCapShape::kDome, "dome"}};

}  // namespace

LengthUnit parse_unit(std::string_view s) {
  if (s == "mm") return LengthUnit::kMm;
  if (s == "cm") return LengthUnit::kCm;
  if (s == "m") return LengthUnit::kM;
  return LengthUnit::kGuess;
}

std::optional<Smoothing> parse_smoothing(std::string_view text) {
  Smoothing s;
  if (text == "auto") return s;
  if (text == "off") {
    s.mode = Smoothing::Mode::kOff;
    return s;
  }
  int n = 0;
  auto r = std::from_chars(text.data(), text.data() + text.size(), n);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || n < 1 || n > 1000)
    return std::nullopt;
  s.mode = Smoothing::Mode::kPasses;
  s.passes = n;
  return s;
}

std::string smoothing_text(const Smoothing& s) {
  switch (s.mode) {
    case Smoothing::Mode::kOff:
      return "off";
    case Smoothing::Mode::kPasses:
      return std::to_string(s.passes);
    case Smoothing::Mode::kAuto:
      break;
  }
  return "auto";
}

Result<OutputFormat> parse_format(std::string_view name) {
  for (OutputFormat f : {OutputFormat::kMsh, OutputFormat::kVtu, OutputFormat::kVtp,
                         OutputFormat::kStl, OutputFormat::kMeshComplete, OutputFormat::kFoam})
    if (format_name(f) == name) return f;
  return Result<OutputFormat>::Error("unknown output format '" + std::string(name) +
                                     "' (msh, vtu, vtp, stl, mesh-complete or foam)");
}

ParamMethod param_method_of(std::string_view w) { return value_of<ParamMethod>(kParamWords, w); }
std::string_view param_method_word(ParamMethod m) { return word_of<ParamMethod>(kParamWords, m); }
Mesher2D mesher2d_of(std::string_view w) { return value_of<Mesher2D>(kMesherWords, w); }
std::string_view mesher2d_word(Mesher2D m) { return word_of<Mesher2D>(kMesherWords, m); }
MshVersion msh_version_of(std::string_view w) { return value_of<MshVersion>(kMshWords, w); }
std::string_view msh_version_word(MshVersion v) { return word_of<MshVersion>(kMshWords, v); }
Solver solver_of(std::string_view w) { return value_of<Solver>(kSolverWords, w); }
std::string_view solver_word(Solver s) { return word_of<Solver>(kSolverWords, s); }
FamilyLayers family_layers_of(std::string_view w) {
  return value_of<FamilyLayers>(kFamilyLayerWords, w);
}
std::string_view family_layers_word(FamilyLayers l) {
  return word_of<FamilyLayers>(kFamilyLayerWords, l);
}
PhantomKind phantom_kind_of(std::string_view w) { return value_of<PhantomKind>(kKindWords, w); }
std::string_view phantom_kind_word(PhantomKind k) { return word_of<PhantomKind>(kKindWords, k); }
PhantomCapShape cap_shape_of(std::string_view w) { return value_of<PhantomCapShape>(kCapWords, w); }
std::string_view cap_shape_word(PhantomCapShape s) {
  return word_of<PhantomCapShape>(kCapWords, s);
}

}  // namespace vm
