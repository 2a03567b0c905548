// Tampered run folders: each case is a file radkit's viewer once crashed or hung on (SIGSEGV in
// SceneView or in VTK's readers, a FIFO that never opens) or refused although radkit wrote it
// (a quoted surface name with a line break). Every one must now read, or be refused with an
// InputError naming the file and the element.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>

#include "output/run_files.h"
#include "tests/common/test_util.h"
#include "tests/viewer/test_run.h"
#include "util/canvas.h"
#include "util/errors.h"
#include "util/output_folder.h"  // csvField: how radkit quotes names
#include "viewer/run_folder.h"

namespace radkit::viewer {
namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// `text` with the values of the DataArray named `name` replaced by `values`.
std::string withArray(std::string text, const std::string& name, const std::string& values) {
  const auto at = text.find("Name=\"" + name + "\"");
  EXPECT_NE(at, std::string::npos) << name;
  const auto open = text.find('>', at) + 1, close = text.find("</DataArray>", open);
  return text.replace(open, close - open, "\n" + values + "\n");
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

class HostileRunFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    test::writeTestRun(m_dir.path(""));
    m_vtp = readText(file("radiosity.vtp"));
  }
  std::string folder() const { return m_dir.path(""); }
  std::string file(const std::string& name) const { return m_dir.path(name); }
  /// The InputError readRunFolder throws ("" when it reads the folder); anything else fails.
  std::string refusal() const {
    try {
      readRunFolder(folder());
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  radkit::test::TempDir m_dir;
  std::string m_vtp;  ///< radiosity.vtp as written: 10 points, 3 quads
};

// Each was a SIGSEGV (ids, counts), undefined behaviour (int(NaN), int(3e9)), a crash, abort or
// hang inside VTK 9.1's XML reader (counts against the data, components), or an infinite
// colour scale (inf emission).
TEST_F(HostileRunFolder, TamperedVtpIsRefusedNamingFileAndPatch) {
  const struct {
    const char* what;
    std::string vtp;
    const char* message;
  } cases[] = {
      {"id past the point count", withArray(m_vtp, "connectivity", "0 1 2 3 3 2 4 5 6 7 8 99"),
       "radiosity.vtp: patch 2 names point 99, but the file has 10 points"},
      {"negative id", withArray(m_vtp, "connectivity", "0 1 2 3 3 2 4 -5 6 7 8 9"),
       "radiosity.vtp: patch 1 names point -5"},
      {"negative polygon count", replaced(m_vtp, "NumberOfPolys=\"3\"", "NumberOfPolys=\"-1\""),
       "radiosity.vtp: Piece needs whole, non-negative NumberOfPoints and NumberOfPolys"},
      {"negative point count", replaced(m_vtp, "NumberOfPoints=\"10\"", "NumberOfPoints=\"-5\""),
       "radiosity.vtp: Piece needs whole, non-negative"},
      {"more polygons declared than present",
       replaced(m_vtp, "NumberOfPolys=\"3\"", "NumberOfPolys=\"5\""),
       "radiosity.vtp: Polys offsets array holds 3 numbers; the Piece's count needs 5"},
      {"fewer points declared than present",
       replaced(m_vtp, "NumberOfPoints=\"10\"", "NumberOfPoints=\"8\""),
       "radiosity.vtp: Points array holds 30 numbers; the Piece's count needs 8 × 3"},
      {"short offsets", withArray(m_vtp, "offsets", "4 8"), "Polys offsets array holds 2 numbers"},
      {"offsets past the connectivity", withArray(m_vtp, "offsets", "4 8 16"),
       "radiosity.vtp: patch 2 has offset 16 after 8 among 12 connectivity ids"},
      {"offsets going back", withArray(m_vtp, "offsets", "4 2 12"),
       "radiosity.vtp: patch 1 has offset 2"},
      {"connectivity longer than the offsets",
       withArray(m_vtp, "connectivity", "0 1 2 3 3 2 4 5 6 7 8 9 1"),
       "the connectivity array holds 13 ids, but the offsets end at 12"},
      {"NaN surface index", withArray(m_vtp, "surface", "0 nan 1"),
       "radiosity.vtp: patch 1 has surface index nan"},
      {"3e9 surface index", withArray(m_vtp, "surface", "0 0 3000000000"),
       "radiosity.vtp: patch 2 has surface index 3e+09"},
      {"fractional surface index", withArray(m_vtp, "surface", "0 0.5 1"),
       "radiosity.vtp: patch 1 has surface index 0.5"},
      {"infinite emission", withArray(m_vtp, "emission", "0 0 0 inf 0 0 0 0 0"),
       "radiosity.vtp: patch 1 has an emission that is negative, NaN or beyond"},
      {"negative emission", withArray(m_vtp, "emission", "0 0 0 0 0 0 0 -1 0"),
       "radiosity.vtp: patch 2 has an emission that is negative"},
      {"NaN radiosity", withArray(m_vtp, "radiosity", "0 0 0 0 0 0 0 nan 0"),
       "radiosity.vtp: patch 2 has a radiosity that is NaN"},
      {"reflectance above 1", withArray(m_vtp, "reflectance", "0.5 0.5 0.5 1.5 0 0 0 0 0"),
       "radiosity.vtp: patch 1 has a reflectance outside [0, 1]"},
      {"zero area", withArray(m_vtp, "area", "0.475 0 0.95"),
       "radiosity.vtp: patch 1 has area 0, not a finite number > 0"},
      {"NaN area", withArray(m_vtp, "area", "nan 0.475 0.95"),
       "radiosity.vtp: patch 0 has area nan"},
      {"infinite point", replaced(m_vtp, "\n-1 -0.5 0\n", "\ninf -0.5 0\n"),
       "radiosity.vtp: point 0 is not finite"},
      {"too few values in a cell array", withArray(m_vtp, "radiosity", "0 0 0 0 0 0"),
       "cell array 'radiosity' holds 6 numbers; the Piece's count needs 3 × 3"},
      {"a word among the numbers", withArray(m_vtp, "area", "0.475 12abc 0.95"),
       "radiosity.vtp: array 'area': value 1 '12abc' is not a number"},
      {"negative components",
       replaced(m_vtp, "Name=\"reflectance\" NumberOfComponents=\"3\"",
                "Name=\"reflectance\" NumberOfComponents=\"-3\""),
       "array 'reflectance': NumberOfComponents is not a whole count"},
      {"huge components",
       replaced(m_vtp, "Name=\"reflectance\" NumberOfComponents=\"3\"",
                "Name=\"reflectance\" NumberOfComponents=\"2000000000\""),
       "cell array 'reflectance' must have 3 component(s) per patch"},
      {"a string array",
       replaced(m_vtp, "type=\"Int32\" Name=\"surface\"", "type=\"String\" Name=\"surface\""),
       "array 'surface' has type 'String', not a number type"},
      {"compressed binary",
       replaced(m_vtp, "byte_order=\"LittleEndian\"",
                "byte_order=\"LittleEndian\" compressor=\"vtkZLibDataCompressor\""),
       "radiosity.vtp: holds compressed binary data"},
      {"two pieces",
       replaced(
           m_vtp, "</Piece>",
           "</Piece><Piece NumberOfPoints=\"9223372036854775000\" NumberOfPolys=\"1\"></Piece>"),
       "radiosity.vtp: holds more than one Piece"},
      {"vertices",
       replaced(m_vtp, "NumberOfPolys=\"3\"", "NumberOfPolys=\"3\" NumberOfVerts=\"4000000000\""),
       "radiosity.vtp: holds vertices, lines or strips"},
  };
  for (const auto& c : cases) {
    m_dir.file("radiosity.vtp", c.vtp);
    const std::string e = refusal();
    EXPECT_NE(e.find(c.message), std::string::npos) << c.what << ": " << e;
  }
  // A surface index past report.json's list (the views index the names with it).
  m_dir.file("radiosity.vtp", withArray(m_vtp, "surface", "0 0 7"));
  EXPECT_NE(refusal().find("patch 2 has surface index 7, but report.json lists 2 surfaces"),
            std::string::npos)
      << refusal();
  // The untampered file still reads, and so does one with the arrays radkit's hierarchical
  // runs add and the empty sections ParaView writes.
  m_dir.file("radiosity.vtp",
             replaced(replaced(m_vtp, "</CellData>",
                               "<DataArray type=\"Float64\" Name=\"level\" format=\"ascii\">\n1 2 "
                               "3\n</DataArray>\n</CellData>"),
                      "<Polys>",
                      "<Verts><DataArray type=\"Int64\" Name=\"connectivity\" "
                      "format=\"ascii\"></DataArray></Verts><Polys>"));
  EXPECT_EQ(refusal(), "");
}

// The report's camera: a number in place of the object threw nlohmann's type_error (not an
// InputError); a position of 1e300 is beyond the scenes' ±1e15 (its square overflows).
TEST_F(HostileRunFolder, ReportCameraMustBeAnObjectOfFiniteNumbers) {
  m_dir.file("report.json", R"({"scene": {"surfaces": ["a", "b"], "camera": 5}})");
  EXPECT_NE(refusal().find("report.json: scene.camera must be an object"), std::string::npos)
      << refusal();
  m_dir.file("report.json", R"({"scene": {"surfaces": ["a", "b"], "camera":
      {"position": [1e300, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0]}}})");
  EXPECT_NE(refusal().find("report.json: scene.camera.position must be 3 finite numbers"),
            std::string::npos)
      << refusal();
}

// Form factors lie in [0, 1]: 1e300 is corruption, and the matrix view sums values per cell,
// where a few such overflow to infinity.
TEST_F(HostileRunFolder, FormFactorsFarBeyondOneAreRefused) {
  m_dir.file("formfactors.mtx",
             "%%MatrixMarket matrix coordinate real general\n3 3 1\n1 2 1e300\n");
  EXPECT_NE(refusal().find("formfactors.mtx:3: a value 1e+300 that is no form factor"),
            std::string::npos)
      << refusal();
}

/// A PNG of `w` × `h` (left half red, right half blue, top row green), as radkit writes one.
std::string pngBytes(const radkit::test::TempDir& dir, int w, int h) {
  Canvas c(w, h, {255, 0, 0});
  c.fill(w / 2, 0, w, h, {0, 0, 255});
  c.fill(0, 0, w, 1, {0, 255, 0});
  writePng(dir.path("made.png"), c);
  return readText(dir.path("made.png"));
}

// VTK 9.1's vtkPNGReader crashed (SIGSEGV after libpng's error) on a truncated links.png; a
// header declaring 100000 × 100000 pixels asked the decoder for 30 GB.
TEST_F(HostileRunFolder, LinksPngIsDecodedWhenTheFolderIsReadAndCheckedFirst) {
  std::filesystem::remove(file("formfactors.mtx"));  // a hierarchical run has no F
  const std::string png = pngBytes(m_dir, 64, 32);
  m_dir.file("links.png", png);
  const RunFolder run = readRunFolder(folder());
  ASSERT_EQ(run.links.width, 64);
  ASSERT_EQ(run.links.height, 32);
  auto pixel = [&](int x, int y) {
    const std::uint8_t* p = &run.links.rgb[(std::size_t(y) * 64 + x) * 3];
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  EXPECT_EQ(pixel(5, 0), (std::array<int, 3>{0, 255, 0}));  // rows from the top
  EXPECT_EQ(pixel(5, 20), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(pixel(60, 20), (std::array<int, 3>{0, 0, 255}));

  m_dir.file("links.png", png.substr(0, png.size() / 2));
  std::string e = refusal();
  EXPECT_NE(e.find("links.png: is damaged or truncated"), std::string::npos) << e;
  EXPECT_NE(e.find("Fix: rerun `radkit run --method hierarchical`"), std::string::npos) << e;

  std::string huge = png;  // IHDR's width and height, big-endian, after the 16-byte preamble
  for (int at : {16, 20}) {
    const unsigned v = 100000;
    huge[at] = char(v >> 24), huge[at + 1] = char(v >> 16), huge[at + 2] = char(v >> 8),
    huge[at + 3] = char(v);
  }
  m_dir.file("links.png", huge);
  e = refusal();
  EXPECT_NE(e.find("links.png: declares 100000x100000 pixels, more than a links image has"),
            std::string::npos)
      << e;

  m_dir.file("links.png", png.substr(0, 20));  // cut inside the header
  EXPECT_NE(refusal().find("links.png: has no PNG header (IHDR chunk)"), std::string::npos)
      << refusal();
  m_dir.file("links.png", "GIF89a not a png");  // only the PNG decoder runs
  EXPECT_NE(refusal().find("links.png: not a PNG image"), std::string::npos) << refusal();
}

// Opening a FIFO blocks until a writer comes: `radkit view` on a folder with a named pipe in
// place of any file it reads hung for ever. Each must be refused without opening it.
TEST_F(HostileRunFolder, PipesInPlaceOfFilesAreRefusedWithoutBlocking) {
  for (const std::string name :
       {"formfactors.bin", "formfactors.mtx", "links.png", "convergence.csv", "surfaces.csv",
        "report.json", "radiosity.vtp"}) {
    test::writeTestRun(folder());
    std::filesystem::remove(file("formfactors.bin"));
    if (name == "links.png") std::filesystem::remove(file("formfactors.mtx"));
    std::filesystem::remove(file(name));
    ASSERT_EQ(::mkfifo(file(name).c_str(), 0600), 0) << name;
    auto reading = std::async(std::launch::async, [&] { return refusal(); });
    if (reading.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
      ADD_FAILURE() << name << ": the read blocked on the FIFO";
      const int fd = ::open(file(name).c_str(), O_WRONLY | O_NONBLOCK);  // let it finish
      if (fd >= 0) ::close(fd);
    }
    const std::string e = reading.get();
    EXPECT_NE(e.find(name + ": is not a regular file (a folder, pipe or device)"),
              std::string::npos)
        << name << ": " << e;
    EXPECT_NE(e.find("Fix:"), std::string::npos) << e;
    std::filesystem::remove(file(name));
  }
  // A symbolic link is followed: to a regular file it reads, to a FIFO it is refused.
  test::writeTestRun(folder());
  std::filesystem::rename(file("surfaces.csv"), file("real.csv"));
  std::filesystem::create_symlink(file("real.csv"), file("surfaces.csv"));
  EXPECT_EQ(refusal(), "");
  std::filesystem::remove(file("surfaces.csv"));
  ASSERT_EQ(::mkfifo(file("pipe").c_str(), 0600), 0);
  std::filesystem::create_symlink(file("pipe"), file("surfaces.csv"));
  EXPECT_NE(refusal().find("surfaces.csv: is not a regular file"), std::string::npos) << refusal();
  // photons --compare reads surfaces.csv through output/run_files too.
  try {
    radkit::readSurfacesCsv(file("surfaces.csv"));
    ADD_FAILURE() << "a FIFO was read as surfaces.csv";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
  }
}

// radkit quotes a name with a comma, a quote or a line break (RFC 4180, csvField); the viewer
// read surfaces.csv line by line and refused the folder radkit wrote.
TEST_F(HostileRunFolder, QuotedNamesWithLineBreaksAndCommasReadBack) {
  const std::string names[] = {"left\nwall, west", "say \"hi\"\r\nthere", "right wall"};
  std::string csv =
      "surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2,luminance_cd_m2,illuminance_lux\r\n";
  for (const std::string& n : names) csv += csvField(n) + ",0.95,0.75,0.085,0.065,30.5,100.25\r\n";
  m_dir.file("surfaces.csv", csv);
  const RunFolder run = readRunFolder(folder());
  ASSERT_EQ(run.surfaces.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(run.surfaces[k].name, names[k]);
  EXPECT_EQ(run.surfaces[2].illuminance, 100.25);
  // The reader `radkit photons --compare` uses reads them alike.
  const std::vector<SurfaceRadiosity> compared = radkit::readSurfacesCsv(file("surfaces.csv"));
  ASSERT_EQ(compared.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(compared[k].name, names[k]);

  // Errors name the line a record starts on, counting the line breaks inside quotes.
  m_dir.file("surfaces.csv",
             "surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2\n\"a\nb\",1,2,3,4\nc,1,x,3,4\n");
  std::string e = refusal();
  EXPECT_NE(e.find("surfaces.csv:4: column 'b_r_W_m2': 'x' is not a number"), std::string::npos)
      << e;
  // A quote left open swallows the rest of the file: refused, naming where it opened.
  m_dir.file("surfaces.csv",
             "surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2\n\"a,1,2,3,4\nb,1,2,3,4\n");
  e = refusal();
  EXPECT_NE(e.find("surfaces.csv:2: a quoted field opened in this record is not closed"),
            std::string::npos)
      << e;
}

TEST(CsvReader, ReadsRfc4180Records) {
  std::istringstream in("a,\"b,c\",\"d\"\"e\"\r\n\r\n\"x\ny\",,z\nlast,\"\"");
  CsvReader csv(in, "t.csv");
  std::vector<std::string> f;
  ASSERT_TRUE(csv.next(f));
  EXPECT_EQ(f, (std::vector<std::string>{"a", "b,c", "d\"e"}));
  EXPECT_EQ(csv.line(), 1);
  ASSERT_TRUE(csv.next(f));  // the blank line is skipped
  EXPECT_EQ(f, (std::vector<std::string>{"x\ny", "", "z"}));
  EXPECT_EQ(csv.line(), 3);
  ASSERT_TRUE(csv.next(f));  // no line break at the end
  EXPECT_EQ(f, (std::vector<std::string>{"last", ""}));
  EXPECT_EQ(csv.line(), 5);
  EXPECT_FALSE(csv.next(f));
  EXPECT_EQ(splitCsvLine("p,\"q,r\"\r"), (std::vector<std::string>{"p", "q,r"}));
  EXPECT_EQ(splitCsvLine(""), (std::vector<std::string>{""}));
}

}  // namespace
}  // namespace radkit::viewer
