// trs-dataset: writes a mesh and a density map as one dataset file (.trsd) for trs-bench, from
// asset files (OBJ or glTF mesh; an image, or the glTF's emissive texture, as the map) or from
// trs-bench's generators. See docs/benchmarks.md.
// Exit status: 0 success, 1 bad input or failed write, 2 bad command line.

#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "dataset_file.h"
#include "density_maps.h"
#include "meshes.h"
#include "scene_io/atomic_file.h"
#include "scene_io/density_io.h"
#include "scene_io/file_error.h"
#include "scene_io/gltf_document.h"
#include "scene_io/image_output.h"
#include "scene_io/mesh_io.h"

namespace {

namespace fs = std::filesystem;

constexpr int kUsageError = 2;

struct CommandLine {
  fs::path mesh, density;
  bool emissive = false;
  std::string generate_mesh, generate_map;
  std::uint32_t map_size = 2048;
  fs::path out, obj, exr;
};

bool is_gltf(const fs::path& file) {
  const std::string extension = file.extension().string();
  return extension == ".gltf" || extension == ".glb";
}

/// A glTF material's emissive texture, as a file.
struct Emitter {
  int material = -1;
  fs::path image;
};

/// The first material with an emissive texture. Embedded images (in a .glb or a data URI) would
/// need decoding from memory, which the density loader does not do.
Emitter first_emitter(const fs::path& gltf_file) {
  const trs::gltf::Document document(gltf_file);
  const tinygltf::Model& model = document.model();
  for (std::size_t m = 0; m < model.materials.size(); ++m) {
    const tinygltf::TextureInfo& info = model.materials[m].emissiveTexture;
    if (info.index < 0) continue;
    const std::string what = "material " + std::to_string(m) + "'s emissive texture";
    if (info.texCoord != 0) document.fail(what + " uses TEXCOORD_" + std::to_string(info.texCoord) +
                                          "; datasets carry TEXCOORD_0 only");
    if (std::size_t(info.index) >= model.textures.size()) document.fail(what + " does not exist");
    const int source = model.textures[info.index].source;
    if (source < 0 || std::size_t(source) >= model.images.size()) document.fail(what + " has no image");
    const std::string& uri = model.images[source].uri;
    if (uri.empty() || uri.rfind("data:", 0) == 0)
      document.fail(what + " is embedded; extract it and give it as --density");
    return {int(m), document.resolve_uri(uri)};
  }
  document.fail("no material has an emissive texture; give a map with --density");
}

trs_bench::Mesh named_mesh(const fs::path& file, trs::MeshData data) {
  return {file.stem().string(), std::move(data.positions), std::move(data.uvs), std::move(data.indices)};
}

trs_bench::DensityMap asset_map(const fs::path& file) {
  trs::DensityMap data = trs::load_density_map(file, trs::MapEncoding::automatic);
  return {file.stem().string(), data.width, data.height, std::move(data.texels)};
}

/// The mesh as Wavefront OBJ, for trs-sample: v flipped to OBJ's (v = 0 at the bottom).
void write_obj(const fs::path& file, const trs_bench::Mesh& mesh) {
  std::string text;
  char line[96];
  for (std::size_t i = 0; i < mesh.positions.size(); i += 3) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2]);
    text += line;
  }
  for (std::size_t i = 0; i < mesh.uvs.size(); i += 2) {
    std::snprintf(line, sizeof line, "vt %.9g %.9g\n", mesh.uvs[i], 1.0 - double(mesh.uvs[i + 1]));
    text += line;
  }
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t] + 1, b = mesh.indices[t + 1] + 1, c = mesh.indices[t + 2] + 1;
    std::snprintf(line, sizeof line, "f %u/%u %u/%u %u/%u\n", a, a, b, b, c, c);
    text += line;
  }
  trs::AtomicFile out(file);
  out.write(text);
  out.commit();
}

/// The map as OpenEXR, for trs-sample: its density in R, G and B (luminance is the density).
void write_map_exr(const fs::path& file, const trs_bench::DensityMap& map) {
  std::vector<float> rgb(3 * map.texels.size());
  for (std::size_t i = 0; i < map.texels.size(); ++i) rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = map.texels[i];
  trs::write_exr(file, map.width, map.height, rgb.data());
}

int run(const CommandLine& cl) {
  trs_bench::Mesh mesh;
  trs_bench::DensityMap map;
  if (cl.emissive) {
    const Emitter emitter = first_emitter(cl.mesh);
    mesh = named_mesh(cl.mesh, trs::load_gltf_material(cl.mesh, emitter.material));
    map = asset_map(emitter.image);
  } else if (!cl.mesh.empty()) {
    mesh = named_mesh(cl.mesh, trs::load_mesh(cl.mesh));
  }
  if (!cl.generate_mesh.empty()) mesh = trs_bench::make_mesh(trs_bench::parse_mesh_spec(cl.generate_mesh));
  if (!cl.density.empty()) map = asset_map(cl.density);
  if (!cl.generate_map.empty())
    map = trs_bench::make_map(trs_bench::parse_map_spec(cl.generate_map), cl.map_size);
  if (!cl.out.empty()) {
    trs_bench::write_dataset(cl.out, mesh, map);
    std::cout << cl.out.string() << ": " << mesh.triangle_count() << " triangles, map " << map.width << "x"
              << map.height << "\n";
  }
  if (!cl.obj.empty()) {
    write_obj(cl.obj, mesh);
    std::cout << cl.obj.string() << ": " << mesh.triangle_count() << " triangles\n";
  }
  if (!cl.exr.empty()) {
    write_map_exr(cl.exr, map);
    std::cout << cl.exr.string() << ": " << map.width << "x" << map.height << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Writes a mesh with UVs and a density map as one dataset file for trs-bench "
      "(--meshes file:PATH, --maps file:PATH), from asset files or from trs-bench's generators.",
      "trs-dataset"};
  CommandLine cl;
  auto* mesh = app.add_option("--mesh", cl.mesh, "Wavefront OBJ or glTF 2.0 (.gltf, .glb) mesh with UVs")
                   ->check(CLI::ExistingFile);
  auto* density = app.add_option("--density", cl.density,
                                 "density map image (EXR, HDR, PNG, ...); colour maps give their luminance")
                      ->check(CLI::ExistingFile);
  auto* emissive = app.add_flag("--emissive", cl.emissive,
                                "the map is the emissive texture of the --mesh glTF's first material "
                                "with one (an external image file; its luminance), the mesh that "
                                "material's triangles")
                       ->needs(mesh)
                       ->excludes(density);
  app.add_option("--generate-mesh", cl.generate_mesh, "a trs-bench mesh instead, e.g. torus:1M")
      ->excludes(mesh);
  app.add_option("--generate-map", cl.generate_map, "a trs-bench map instead, e.g. threshold:1e-3")
      ->excludes(density)
      ->excludes(emissive);
  app.add_option("--map-size", cl.map_size, "width and height of a generated map, texels")
      ->check(CLI::Range(1u, 1u << 15))
      ->capture_default_str();
  app.add_option("--out", cl.out, "the dataset file to write (.trsd)");
  app.add_option("--obj", cl.obj, "the mesh as Wavefront OBJ, for trs-sample");
  app.add_option("--exr", cl.exr, "the map as OpenEXR (its density in R, G and B), for trs-sample");
  try {
    app.parse(argc, argv);
    if (!cl.generate_mesh.empty()) trs_bench::parse_mesh_spec(cl.generate_mesh);
    if (!cl.generate_map.empty()) trs_bench::parse_map_spec(cl.generate_map);
    if (cl.emissive && !is_gltf(cl.mesh)) throw CLI::ValidationError("--emissive", "needs a glTF --mesh");
    if (cl.out.empty() && cl.obj.empty() && cl.exr.empty())
      throw CLI::ValidationError("nowhere to write: give --out, --obj or --exr");
    if (!cl.obj.empty() && cl.mesh.empty() && cl.generate_mesh.empty())
      throw CLI::ValidationError("--obj", "needs a mesh (--mesh, --generate-mesh)");
    if (!cl.exr.empty() && cl.density.empty() && !cl.emissive && cl.generate_map.empty())
      throw CLI::ValidationError("--exr", "needs a map (--density, --emissive, --generate-map)");
    if (cl.mesh.empty() && cl.generate_mesh.empty() && cl.density.empty() && cl.generate_map.empty())
      throw CLI::ValidationError("nothing to write: give a mesh (--mesh, --generate-mesh), a map "
                                 "(--density, --emissive, --generate-map) or both");
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const std::exception& e) {  // CLI::ParseError, or a bad generator spec
    std::cerr << "trs-dataset: error: " << e.what() << "\nRun with --help for more information.\n";
    return kUsageError;
  }
  try {
    return run(cl);
  } catch (const std::exception& e) {
    std::cerr << "trs-dataset: error: " << e.what() << "\n";
    return 1;
  }
}
