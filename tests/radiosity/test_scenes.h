// Hand-built patch meshes and the closed-form oracles of docs/oracles.md (View factors).
#pragma once

#include "tests/common/statistics.h"

#include <array>
#include <string>
#include <vector>

#include "geometry/patch_mesh.h"

namespace radkit::test {

/// Builds a PatchMesh surface by surface (each surface gets its own vertices).
class MeshBuilder {
 public:
  /// An nu×nv grid of quads over the parallelogram corner + [0,1]e1 + [0,1]e2; front side
  /// (normal) along e1 × e2. Returns the surface index.
  int addRectangle(const std::string& name, const Vec3& corner, const Vec3& e1, const Vec3& e2,
                   int nu = 1, int nv = 1);
  /// A regular polygon with `sides` vertices on the circle (centre, radius) in the plane
  /// normal to `normal`, as a fan of triangles around the centre; front side along normal.
  int addDisk(const std::string& name, const Vec3& centre, const Vec3& normal, double radius,
              int sides);
  /// Triangles given by their corners (front by the right-hand rule), one surface.
  int addTriangles(const std::string& name, const std::vector<Vec3>& corners);
  const PatchMesh& mesh() const { return m_mesh; }
  const std::vector<std::string>& names() const { return m_names; }

 private:
  int beginSurface(const std::string& name);
  void addPatch(const std::vector<int>& vertexIndices, int surface);
  PatchMesh m_mesh;
  std::vector<std::string> m_names;
};

/// Unit cube [0,1]³ with its six faces facing inwards, each an n×n grid.
/// Surfaces: 0 bottom (z=0), 1 top, 2 y=0, 3 y=1, 4 x=0, 5 x=1.
MeshBuilder cubeInterior(int n);
/// C-11: two a×b rectangles distance c apart facing each other, nu×nv patches each.
MeshBuilder parallelRectangles(double a, double b, double c, int n = 1);
/// C-14: A1 = l×w (z=0, normal +z) and A2 = l×h (y=0, normal +y) sharing the edge of length l.
MeshBuilder perpendicularRectangles(double l, double w, double h, int n = 1);
/// Unit icosphere subdivided `level` times (20·4^level triangles): vertices and triangles,
/// counter-clockwise seen from outside.
void unitIcosphere(int level, std::vector<Vec3>& vertices,
                   std::vector<std::array<int, 3>>& triangles);
/// Icosphere of radius r around the origin subdivided `level` times, normals inwards.
MeshBuilder icosphereInterior(int level, double r = 1.0);

// Closed forms (docs/oracles.md, View factors).
double c11ParallelRectangles(double X, double Y);
double c14PerpendicularRectangles(double W, double H);
double diskOnAxis(double R, double h);
double diskOffAxis(double r, double h, double l);
double coaxialDisks(double r1, double r2, double h);

}  // namespace radkit::test
