// CapturedOpenMeshErrors used to leak 32 bytes per mesh read: OpenMesh's disconnect() drops
// the target connect() allocated without freeing it. Counted here by replacing the global
// operator new/delete of this test binary (counting only, allocation goes to malloc).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "geometry/mesh_reader.h"
#include "geometry/openmesh_errors.h"
#include "tests/common/test_util.h"

namespace {
std::atomic<long> g_live{0};
}

void* operator new(std::size_t size) {
  void* p = std::malloc(size ? size : 1);
  if (!p) throw std::bad_alloc();
  ++g_live;
  return p;
}
void operator delete(void* p) noexcept {
  if (!p) return;
  --g_live;
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }

namespace radkit {
namespace {

TEST(MeshReader, ReadingLeavesNoAllocationBehind) {
  test::TempDir dir;
  const std::string off =
      dir.file("t.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
  const std::string ply = dir.file("t.ply",
                                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                   "property float y\nproperty float z\nelement face 1\n"
                                   "property list uchar int vertex_indices\nend_header\n"
                                   "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  readMeshFile(off);  // first reads register OpenMesh's readers and other statics
  readMeshFile(ply);
  const long before = g_live.load();
  for (int k = 0; k < 20; ++k) {
    EXPECT_EQ(readMeshFile(off).faces.size(), 2u);
    EXPECT_EQ(readMeshFile(ply).faces.size(), 1u);
  }
  EXPECT_LT(g_live.load() - before, 10) << "allocations still live after 40 reads";
}

// A bad file can make OpenMesh say the same thing once per face: radkit's message quotes each
// distinct line once, with its count, on one line.
TEST(MeshReader, OpenMeshsRepeatedComplaintsAreQuotedOnce) {
  std::string text;
  {
    const CapturedOpenMeshErrors errors;
    for (int k = 0; k < 3; ++k) omerr() << "ImporterT: Face contains invalid vertex index\n";
    omerr() << "another complaint\n";
    omerr().flush();
    text = errors.text();
  }
  EXPECT_EQ(text, "ImporterT: Face contains invalid vertex index (3 times); another complaint");
}

}  // namespace
}  // namespace radkit
