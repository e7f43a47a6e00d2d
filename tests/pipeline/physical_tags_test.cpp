// Physical tags are unique across dimensions in every output (issue 23:
// gmshToFoam names cell zones by number, so a surface group sharing a
// volume group's number renamed the lumen `wall`). The files are written,
// then read back as a reader would: MSH 4.1 and 2.2 ($PhysicalNames and the
// physical tag of every element), VTU ModelRegionID, VTP ModelFaceID and
// mesh-complete's names.json.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>
#include <string>

#include "core/io/stl.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/write_outputs.h"
#include "tests/support/meshed_tube.h"
#include "tests/support/test_meshes.h"
#include "tests/support/vtk_xml_reader.h"

namespace vm {
namespace {

/// An open tube meshed with every group there is: a tagged boundary layer
/// and a vessel wall (surfaces wall, inlet, outlet_1, outer_wall,
/// wall_inlet, wall_outlet_1; volumes lumen, boundary_layer, vessel_wall).
const MeshJobResult& tube_with_all_groups(bool prisms) {
  auto make = [](bool keep_prisms) {
    MeshJobOptions o;
    for (auto [id, text] : {std::pair{"size", "0.4"},
                            {"layers", "2"},
                            {"units", "mm"},
                            {"wall_thickness", "0.1"},
                            {"wall_layers", "2"}})
      EXPECT_TRUE(set_option_text(o, id, text).ok()) << id;
    o.tag_layer = true;
    o.keep_prisms = keep_prisms;
    return testing::meshed_tube(o);
  };
  static const MeshJobResult tets = make(false), prisms_kept = make(true);
  return prisms ? prisms_kept : tets;
}

int dimension_of(int msh_type) { return msh_type == 4 || msh_type == 6 ? 3 : 2; }

/// What a reader finds in an MSH file: the (dim, tag) of each physical
/// name, and per element its dimension and physical tag.
struct MshTags {
  std::map<std::pair<int, int>, std::string> names;
  std::vector<std::pair<int, int>> elements;  ///< (dim, physical tag)
};

/// Skips to the line after "$Section".
void seek(std::istringstream& in, const std::string& section) {
  std::string line;
  while (std::getline(in, line) && line != section) {
  }
}

MshTags read_msh_tags(const std::string& text) {
  MshTags t;
  std::istringstream in(text);
  std::string version;
  seek(in, "$MeshFormat");
  in >> version;
  seek(in, "$PhysicalNames");
  size_t n = 0;
  in >> n;
  for (size_t i = 0; i < n; ++i) {
    int dim = 0, tag = 0;
    std::string name;
    in >> dim >> tag >> name;
    t.names[{dim, tag}] = name.substr(1, name.size() - 2);  // without the quotes
  }
  if (version == "4.1") {
    // Entities give each entity its physical tag; element blocks name
    // their entity.
    seek(in, "$Entities");
    size_t counts[4] = {};
    in >> counts[0] >> counts[1] >> counts[2] >> counts[3];
    std::map<std::pair<int, int>, int> physical;  // (dim, entity) -> physical tag
    for (int dim = 2; dim <= 3; ++dim)
      for (size_t e = 0; e < counts[dim]; ++e) {
        int tag = 0, np = 0, physical_tag = 0, nb = 0;
        double box[6];
        in >> tag;
        for (double& x : box) in >> x;
        in >> np;
        EXPECT_EQ(np, 1);
        in >> physical_tag >> nb;
        physical[{dim, tag}] = physical_tag;
      }
    seek(in, "$Elements");
    size_t blocks = 0, total = 0, lo = 0, hi = 0;
    in >> blocks >> total >> lo >> hi;
    for (size_t b = 0; b < blocks; ++b) {
      int dim = 0, entity = 0, type = 0;
      size_t count = 0;
      in >> dim >> entity >> type >> count;
      EXPECT_EQ(dim, dimension_of(type));
      const int nodes = type == 2 ? 3 : type == 3 ? 4 : type == 4 ? 4 : 6;
      for (size_t e = 0; e < count; ++e) {
        long x = 0;
        for (int k = 0; k <= nodes; ++k) in >> x;
        t.elements.emplace_back(dim, physical.at({dim, entity}));
      }
    }
  } else {
    // 2.2: number type ntags physical elementary nodes...
    seek(in, "$Elements");
    size_t count = 0;
    in >> count;
    for (size_t e = 0; e < count; ++e) {
      int number = 0, type = 0, ntags = 0, physical_tag = 0, elementary = 0;
      in >> number >> type >> ntags >> physical_tag >> elementary;
      EXPECT_EQ(ntags, 2);
      const int nodes = type == 2 ? 3 : type == 3 ? 4 : type == 4 ? 4 : 6;
      long x = 0;
      for (int k = 0; k < nodes; ++k) in >> x;
      t.elements.emplace_back(dimension_of(type), physical_tag);
    }
  }
  return t;
}

/// No tag number is used by two dimensions; every element's (dim, tag) is
/// a named group.
void expect_unique_across_dimensions(const MshTags& t) {
  std::map<int, int> dim_of_tag;
  for (const auto& [key, name] : t.names) {
    const auto [dim, tag] = key;
    auto [it, fresh] = dim_of_tag.emplace(tag, dim);
    EXPECT_TRUE(fresh) << "tag " << tag << " is used by dimension " << it->second << " and " << dim
                       << " (" << name << ")";
  }
  for (const auto& e : t.elements) ASSERT_TRUE(t.names.count(e)) << e.first << " " << e.second;
}

TEST(PhysicalTags, NumberSurfacesFirstThenVolumesSkippingUnused) {
  const PhysicalTags t = physical_tags({"wall", "inlet", "outlet_1"}, {"lumen", "", "vessel_wall"});
  EXPECT_EQ(t.surface, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(t.region, (std::vector<int>{4, 0, 5}));
}

TEST(PhysicalTags, AreUniqueAcrossDimensionsInMsh41And22) {
  for (bool prisms : {false, true}) {
    const MeshJobResult& r = tube_with_all_groups(prisms);
    for (MshVersion version : {MshVersion::k41, MshVersion::k22}) {
      WriteOptions o;
      o.msh_version = version;
      auto files = write_outputs(r, OutputFormat::kMsh, o);
      ASSERT_TRUE(files.ok()) << files.message();
      const MshTags t = read_msh_tags(files.value()[0].bytes);
      SCOPED_TRACE(std::string(version == MshVersion::k41 ? "4.1" : "2.2") +
                   (prisms ? " prisms" : " tetrahedra"));
      expect_unique_across_dimensions(t);
      // Names unchanged; surfaces 1..6, then the volumes 7..9.
      const std::map<std::pair<int, int>, std::string> want = {
          {{2, 1}, "wall"},       {{2, 2}, "inlet"},          {{2, 3}, "outlet_1"},
          {{2, 4}, "outer_wall"}, {{2, 5}, "wall_inlet"},     {{2, 6}, "wall_outlet_1"},
          {{3, 7}, "lumen"},      {{3, 8}, "boundary_layer"}, {{3, 9}, "vessel_wall"}};
      EXPECT_EQ(t.names, want);
      // Every group has elements, and the counts are the report's.
      std::map<int, size_t> per_tag;
      for (const auto& [dim, tag] : t.elements) ++per_tag[tag];
      for (const OutputGroup& g : r.groups) {
        EXPECT_EQ(t.names.at({g.dim, g.tag}), g.name);
        EXPECT_EQ(per_tag[g.tag], g.elements) << g.name;
        EXPECT_GT(g.elements, 0u) << g.name;
      }
    }
  }
}

// Writes r in `format` (one VTK XML file) and counts its cells by their id
// in the cell array `array`; each group of dimension `dim` must have as many
// cells of its tag as it has elements.
void count_cells_by_id(const MeshJobResult& r, OutputFormat format, const char* array, int dim,
                       std::map<int, size_t>& count) {
  auto files = write_outputs(r, format);
  ASSERT_TRUE(files.ok()) << files.message();
  auto data = testing::read_vtk_xml(files.value()[0].bytes);
  ASSERT_TRUE(data.ok()) << data.message();
  for (int32_t id : data.value().values<int32_t>("CellData", array)) ++count[id];
  for (const OutputGroup& g : r.groups)
    if (g.dim == dim) {
      EXPECT_EQ(count[g.tag], g.elements) << g.name;
    }
}

TEST(PhysicalTags, VtkAndMeshCompleteIdsAreTheMshTags) {
  const MeshJobResult& r = tube_with_all_groups(false);
  std::set<int> surface_tags, volume_tags;
  for (const OutputGroup& g : r.groups) (g.dim == 2 ? surface_tags : volume_tags).insert(g.tag);

  std::map<int, size_t> per_region, per_face;
  count_cells_by_id(r, OutputFormat::kVtu, "ModelRegionID", 3, per_region);
  for (const auto& [id, n] : per_region) EXPECT_TRUE(volume_tags.count(id)) << id;
  count_cells_by_id(r, OutputFormat::kVtp, "ModelFaceID", 2, per_face);

  auto folder = write_outputs(r, OutputFormat::kMeshComplete);
  ASSERT_TRUE(folder.ok()) << folder.message();
  const std::string& names = folder.value().back().bytes;
  ASSERT_EQ(folder.value().back().path, "mesh-complete.names.json");
  for (const OutputGroup& g : r.groups) {
    const std::string entry = "{\"id\":" + std::to_string(g.tag) + ",\"name\":\"" + g.name + "\"";
    EXPECT_NE(names.find(entry), std::string::npos) << entry << " in " << names;
  }
}

}  // namespace
}  // namespace vm
