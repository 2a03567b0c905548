#include "geometry/scene_loader.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "tests/common/open_box.h"
#include "tests/common/test_util.h"

namespace radkit {
namespace {

using test::dataPath;

struct Expected {
  const char* file;
  std::size_t surfaces, materials;
  std::size_t warnings;  // non-planar or non-emitting notices expected on load
};

TEST(SceneLoader, EveryDataSceneLoads) {
  const Expected scenes[] = {
      {"cornell-box.json", 8, 4, 1},  // the measured left wall is non-planar
      {"cornell-box-empty.json", 6, 4, 1},
      {"cube-one-emitter.json", 6, 2, 0},
      {"furnace.json", 6, 1, 0},
      {"parallel-squares.json", 2, 2, 0},
      {"perpendicular-squares.json", 2, 2, 0},
      {"sphere-interior.json", 1, 1, 0},
      {"terrain-room.json", 2, 2, 0},
  };
  for (const Expected& e : scenes) {
    SCOPED_TRACE(e.file);
    LoadReport report;
    Scene scene = loadScene(dataPath(e.file), &report);
    EXPECT_EQ(scene.surfaces.size(), e.surfaces);
    EXPECT_EQ(scene.materials.size(), e.materials);
    EXPECT_EQ(report.warnings.size(), e.warnings);
    for (const Surface& s : scene.surfaces) {
      ASSERT_GE(s.material, 0);
      for (const Face& f : s.faces) EXPECT_TRUE(f.vertices.size() == 3 || f.vertices.size() == 4);
    }
  }
}

TEST(SceneLoader, EnclosuresFaceInward) {
  // Every face of the closed and open boxes must face the scene's centre: an outward face
  // sees nothing, and its form factors are all zero.
  for (const char* file : {"cornell-box-empty.json", "cube-one-emitter.json", "furnace.json",
                           "sphere-interior.json"}) {
    SCOPED_TRACE(file);
    Scene scene = loadScene(dataPath(file));
    Bounds3 b = scene.bounds();
    Vec3 centre = (b.lo + b.hi) * 0.5;
    for (const Surface& s : scene.surfaces)
      for (const Face& f : s.faces) {
        const auto& v = s.vertices;
        Vec3 n = cross(v[f.vertices[1]] - v[f.vertices[0]], v[f.vertices[2]] - v[f.vertices[0]]);
        EXPECT_GT(dot(n, centre - v[f.vertices[0]]), 0) << s.name;
      }
  }
}

TEST(SceneLoader, CornellBoxAsMeasured) {
  LoadReport report;
  Scene scene = loadScene(dataPath("cornell-box.json"), &report);
  EXPECT_EQ(scene.units, "mm");
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_NEAR(scene.camera->fovDeg, 39.3077, 1e-12);
  const Material& light = scene.materials[scene.findMaterial("light")];
  EXPECT_EQ(light.emission, (Vec3{17, 12, 4}));
  // The light is 130 x 105 mm (docs/oracles.md, The Cornell box).
  double area = 0;
  for (const Surface& s : scene.surfaces)
    if (s.name == "light")
      for (const Face& f : s.faces) {
        Vec3 a = s.vertices[f.vertices[0]], b = s.vertices[f.vertices[1]],
             c = s.vertices[f.vertices[2]];
        area += length(cross(b - a, c - a)) * (f.vertices.size() == 4 ? 1.0 : 0.5);
      }
  EXPECT_NEAR(area, 13650.0, 1e-9);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("left wall"), std::string::npos);
  EXPECT_NE(report.warnings[0].find("not planar"), std::string::npos);
}

TEST(SceneLoader, MaterialModels) {
  test::TempDir dir;
  std::string scene = dir.file("s.json", R"({"materials": {
      "plastic": {"brdf": "phong", "kd": [0.5, 0.4, 0.3], "ks": [0.2, 0.2, 0.2], "shininess": 50},
      "gold": {"brdf": "cook-torrance", "base_color": [0.9, 0.7, 0.3], "metallic": 1, "roughness": 0.3},
      "ceramic": {"brdf": "cook-torrance", "base_color": [0.8, 0.8, 0.8], "ior": 1.5},
      "glass": {"brdf": "glass", "ior": 1.5},
      "mirror": {"brdf": "mirror"},
      "lamp": {"emission": [1, 1, 1]}},
    "surfaces": [{"name": "a", "material": "lamp", "polygon": [[0,0,0],[1,0,0],[1,1,0]]}]})");
  Scene s = loadScene(scene);
  const Material& plastic = s.materials[s.findMaterial("plastic")];
  EXPECT_EQ(plastic.bsdf, "phong");
  EXPECT_EQ(plastic.diffuseAlbedo(), (Vec3{0.5, 0.4, 0.3}));
  EXPECT_NE(plastic.description.find("n=50"), std::string::npos) << plastic.description;
  EXPECT_EQ(s.materials[s.findMaterial("gold")].diffuseAlbedo(),
            (Vec3{0, 0, 0}));  // metals have no diffuse part
  // ((1.5-1)/(1.5+1))² = 0.04
  EXPECT_NE(s.materials[s.findMaterial("ceramic")].description.find("F0=[0.04, 0.04, 0.04]"),
            std::string::npos);
  EXPECT_EQ(s.materials[s.findMaterial("glass")].diffuseAlbedo(), (Vec3{0, 0, 0}));
  EXPECT_NE(s.materials[s.findMaterial("mirror")].description.find("colour=[1, 1, 1]"),
            std::string::npos);
  EXPECT_EQ(s.materials[s.findMaterial("gold")].bsdf, "cook-torrance");
  // A key of another model, an unknown model and a non-conserving Phong are errors.
  for (const char* bad : {R"("brdf": "lambert", "shininess": 3)", R"("brdf": "velvet")",
                          R"("brdf": "phong", "kd": [0.6,0.6,0.6], "ks": [0.5,0.5,0.5])",
                          R"("brdf": "cook-torrance", "roughness": 0)"}) {
    std::string text =
        std::string(R"({"materials": {"m": {"emission": [1,1,1], )") + bad +
        R"(}}, "surfaces": [{"name": "a", "material": "m", "polygon": [[0,0,0],[1,0,0],[1,1,0]]}]})";
    try {
      loadScene(dir.file("bad.json", text));
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      // The message names the file and the material.
      EXPECT_NE(std::string(e.what()).find("bad.json: material \"m\""), std::string::npos)
          << e.what();
    }
  }
}

TEST(SceneLoader, ObjWithMtlAsScene) {
  test::TempDir dir;
  dir.file("box.mtl", "newmtl white\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 2 3 4\n");
  std::string obj =
      dir.file("box.obj",
               "mtllib box.mtl\n"
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\n"
               "o floor\nusemtl white\nf 1 2 3 4\n"
               "o lamp\nusemtl lamp\nf 5 6 7 8\n");
  Scene scene = loadScene(obj);
  ASSERT_EQ(scene.surfaces.size(), 2u);
  EXPECT_EQ(scene.surfaces[0].name, "floor");
  EXPECT_EQ(scene.surfaces[1].name, "lamp");
  const Material& lamp = scene.materials[scene.surfaces[1].material];
  EXPECT_EQ(lamp.emission, (Vec3{2, 3, 4}));
  EXPECT_EQ(scene.materials[scene.surfaces[0].material].diffuseAlbedo(), (Vec3{0.5, 0.5, 0.5}));
  EXPECT_EQ(scene.surfaces[0].vertices.size(), 4u);
}

TEST(SceneLoader, MeshFormatsAndTransform) {
  test::TempDir dir;
  // One unit square as two triangles, written in each format OpenMesh reads.
  dir.file("sq.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  dir.file("sq.ply",
           "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
           "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
           "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  dir.file("sq.stl",
           "solid sq\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
           "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\n"
           "vertex 0 1 0\nendloop\nendfacet\nendsolid sq\n");
  for (const char* ext : {"off", "ply", "stl"}) {
    SCOPED_TRACE(ext);
    std::string scene = dir.file(
        "s.json",
        std::string(R"({"materials": {"m": {"reflectance": [0.5,0.5,0.5], "emission": [1,1,1]}},
      "surfaces": [{"name": "sq", "material": "m", "mesh": "sq.)") +
            ext + R"(", "transform": {"scale": 2, "translate": [10, 0, 0]}}]})");
    Scene s = loadScene(scene);
    ASSERT_EQ(s.surfaces.size(), 1u);
    EXPECT_EQ(s.surfaces[0].faces.size(), 2u);
    EXPECT_EQ(s.surfaces[0].vertices.size(), 4u);  // STL's repeated corners are merged
    Bounds3 b = s.bounds();
    EXPECT_EQ(b.lo, (Vec3{10, 0, 0}));
    EXPECT_EQ(b.hi, (Vec3{12, 2, 0}));
  }
}

TEST(SceneLoader, NonPlanarQuadIsSplitWithWarning) {
  test::TempDir dir;
  std::string scene = dir.file("s.json", R"({"materials": {"m": {"emission": [1,1,1]}},
    "surfaces": [{"name": "bent", "material": "m", "polygon": [[0,0,0],[1,0,0],[1,1,0.1],[0,1,0]]}]})");
  LoadReport report;
  Scene s = loadScene(scene, &report);
  ASSERT_EQ(s.surfaces[0].faces.size(), 2u);
  EXPECT_EQ(s.surfaces[0].faces[0].vertices.size(), 3u);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("\"bent\""), std::string::npos);
}

TEST(SceneLoader, PolygonWithManyVerticesIsTriangulated) {
  test::TempDir dir;
  // An L-shaped hexagon (non-convex): ear clipping must keep the area, 3 units².
  std::string scene = dir.file("s.json", R"({"materials": {"m": {"emission": [1,1,1]}},
    "surfaces": [{"name": "L", "material": "m", "polygon": [[0,0,0],[2,0,0],[2,1,0],[1,1,0],[1,2,0],[0,2,0]]}]})");
  Scene s = loadScene(scene);
  double area = 0;
  for (const Face& f : s.surfaces[0].faces) {
    ASSERT_EQ(f.vertices.size(), 3u);
    const auto& v = s.surfaces[0].vertices;
    Vec3 n = cross(v[f.vertices[1]] - v[f.vertices[0]], v[f.vertices[2]] - v[f.vertices[0]]);
    EXPECT_GT(n.z, 0);  // orientation kept
    area += 0.5 * length(n);
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

TEST(SceneLoader, SelfIntersectionIsAWarning) {
  test::TempDir dir;
  // Two triangles of one surface crossing each other.
  std::string scene = dir.file("s.json", R"({"materials": {"m": {"emission": [1,1,1]}},
    "surfaces": [{"name": "x", "material": "m", "polygons": [
      [[0,0,0],[2,0,0],[1,2,0]], [[1,1,-1],[1,1.5,1],[1,0.5,1]] ]}]})");
  LoadReport report;
  loadScene(scene, &report);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("intersects itself"), std::string::npos);
}

}  // namespace
}  // namespace radkit

namespace radkit {
namespace {

TEST(SceneLoader, JsonIncludesObjKeepingItsMtlMaterials) {
  test::TempDir dir;
  test::writeOpenBoxObj(dir, true);
  // The scene adds units, a camera, a scale and one override ("red" becomes blue).
  const std::string json = dir.file("scene.json", R"({"units": "cm",
    "materials": {"red": {"reflectance": [0.1, 0.1, 0.6]}},
    "surfaces": [{"include": "box.obj", "transform": {"scale": 100}}],
    "camera": {"position": [50, 50, 300], "look_at": [50, 50, 0]}})");
  const Scene s = loadScene(json);
  EXPECT_EQ(s.units, "cm");
  ASSERT_TRUE(s.camera);
  ASSERT_EQ(s.surfaces.size(), 6u);
  auto material = [&](const std::string& surface) {
    for (const Surface& x : s.surfaces)
      if (x.name == surface) return s.materials[x.material];
    ADD_FAILURE() << "no surface " << surface;
    return Material{};
  };
  EXPECT_DOUBLE_EQ(material("left").diffuseAlbedo().z, 0.6)
      << "the scene's material overrides the MTL's";
  EXPECT_DOUBLE_EQ(material("right").diffuseAlbedo().y, 0.5) << "Kd from the MTL";
  EXPECT_DOUBLE_EQ(material("light").emission.x, 20) << "Ke from the MTL";
  EXPECT_NEAR(s.bounds().hi.z, 100, 1e-9) << "the transform scales the included geometry";

  // A missing file and a non-OBJ are refused with the surface and the fix.
  const std::string missing =
      dir.file("missing.json", R"({"surfaces": [{"include": "nope.obj"}]})");
  try {
    loadScene(missing);
    ADD_FAILURE() << "a missing include was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("surfaces[0]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nope.obj"), std::string::npos) << e.what();
  }
  const std::string ply = dir.file("ply.json", R"({"surfaces": [{"include": "box.ply"}]})");
  EXPECT_THROW(loadScene(ply), InputError);
}

}  // namespace
}  // namespace radkit

namespace radkit {
namespace {

const char* kBox =
    "mtllib box.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\n"
    "o floor\nusemtl shiny\nf 1 2 3 4\n"
    "o lamp\nusemtl lamp\nf 5 6 7 8\n";

TEST(SceneLoader, MtlSemanticsAreWarnedNotSilent) {
  test::TempDir dir;
  // Ks only (Kd 0): a glossy Phong material, not black; Ka is ambient colour, not emission.
  dir.file("box.mtl",
           "newmtl shiny\nKd 0 0 0\nKa 1 1 1\nKs 0.5 0.5 0.5\nNs 20\nnewmtl lamp\nKd 0.5 0.5 "
           "0.5\nKe 5 5 5\n");
  LoadReport report;
  Scene scene = loadScene(dir.file("box.obj", kBox), &report);
  const Material& shiny = scene.materials[scene.findMaterial("shiny")];
  EXPECT_EQ(shiny.bsdf, "phong");
  EXPECT_NE(shiny.description.find("ks=[0.5, 0.5, 0.5]"), std::string::npos) << shiny.description;
  std::string all;
  for (const std::string& w : report.warnings) all += w + "\n";
  EXPECT_NE(all.find("\"shiny\": Ks read as a glossy Phong lobe"), std::string::npos) << all;
  EXPECT_NE(all.find("Ka (ambient colour) is ignored in 1 MTL material (\"shiny\")"),
            std::string::npos)
      << all;
  // Exporters give every material a Ka: one warning names them, not one per material.
  dir.file("box.mtl",
           "newmtl shiny\nKd 0.5 0.5 0.5\nKa 0.5 0.5 0.5\nnewmtl dull\nKd 0.2 0.2 0.2\nKa 0.2 "
           "0.2 0.2\nnewmtl lamp\nKd 0.5 0.5 0.5\nKa 1 1 1\nKe 5 5 5\n");
  report = {};
  loadScene(dir.file("box.obj", kBox), &report);
  int ambient = 0;
  for (const std::string& w : report.warnings)
    ambient += w.find("Ka (ambient") != std::string::npos;
  EXPECT_EQ(ambient, 1);
  all.clear();
  for (const std::string& w : report.warnings) all += w + "\n";
  EXPECT_NE(all.find("ignored in 2 MTL materials (\"shiny\", \"dull\")"), std::string::npos) << all;

  // Kd + Ks above 1 is scaled below 1, with a warning.
  dir.file("box.mtl", "newmtl shiny\nKd 0.8 0.8 0.8\nKs 1 1 1\nnewmtl lamp\nKe 5 5 5\n");
  report = {};
  scene = loadScene(dir.file("box.obj", kBox), &report);
  EXPECT_LT(scene.materials[scene.findMaterial("shiny")].diffuseAlbedo().x, 0.8 / 1.8 + 1e-9);

  // A light given only by Ka: no emitter at all is an error naming the fix.
  dir.file("box.mtl", "newmtl shiny\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0.5 0.5 0.5\nKa 17 12 4\n");
  try {
    loadScene(dir.file("box.obj", kBox));
    ADD_FAILURE() << "a scene without emitters loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no material emits"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Ke"), std::string::npos) << e.what();
  }

  // A missing MTL is named as such, not as "has no material".
  std::remove(dir.path("box.mtl").c_str());
  try {
    loadScene(dir.file("box.obj", kBox));
    ADD_FAILURE() << "loaded without its MTL";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("MTL file was not found"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace radkit
