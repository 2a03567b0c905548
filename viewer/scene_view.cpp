#include "viewer/scene_view.h"

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkHardwareSelector.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkProperty.h>
#include <vtkSelection.h>
#include <vtkSelectionNode.h>
#include <vtkSmartPointer.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>

#include "render/camera.h"
#include "render/smooth_radiosity.h"
#include "viewer/colour_maps.h"

namespace radkit::viewer {

namespace {

/// render/'s automatic camera on the run's patches, so the viewer and render.png agree.
Camera framingCamera(const PatchData& patches) {
  std::vector<Triangle> triangles;
  std::vector<char> emitting;
  for (std::size_t i = 0; i < patches.polygons.size(); ++i) {
    const std::vector<int>& p = patches.polygons[i];
    const bool emits = i < patches.emission.size() && maxComponent(patches.emission[i]) > 0;
    for (std::size_t k = 1; k + 1 < p.size(); ++k) {
      triangles.push_back({patches.points[p[0]], patches.points[p[k]], patches.points[p[k + 1]]});
      emitting.push_back(emits ? 1 : 0);
    }
  }
  return automaticCamera(triangles, &emitting);
}

constexpr double kZeroColour[3] = {0.32, 0.32, 0.36};  // F_ij = 0: not seen from the picked patch
constexpr double kAboveColour[3] = {1.0, 1.0, 1.0};    // emitters, above the false-colour range
constexpr double kOutline[3] = {0.2, 0.95, 1.0};

std::string triple(const Vec3& v) {
  return "(" + formatShort(v.x) + ", " + formatShort(v.y) + ", " + formatShort(v.z) + ")";
}

vtkSmartPointer<vtkUnsignedCharArray> colourArray(const std::vector<Vec3>& b, double exposure) {
  auto a = vtkSmartPointer<vtkUnsignedCharArray>::New();
  a->SetName("colour");
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(vtkIdType(b.size()));
  for (std::size_t i = 0; i < b.size(); ++i) {
    auto c = trueColour(b[i], exposure);
    a->SetTypedTuple(vtkIdType(i), c.data());
  }
  return a;
}

vtkSmartPointer<vtkDoubleArray> valueArray(const std::vector<double>& v) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName("value");
  a->SetNumberOfValues(vtkIdType(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a->SetValue(vtkIdType(i), v[i]);
  return a;
}

/// Smooth shading's per-corner values, in m_surface's point order (corner by corner).
template <class T>
std::vector<T> corners(const PatchData& p, const std::vector<T>& perPatch) {
  return smoothCornerValues(p.points, p.polygons, p.surface, perPatch);
}

}  // namespace

SceneView::SceneView(const RunFolder& run) : m_run(run) {
  const PatchData& p = run.patches;
  // Every polygon gets its own corner points: smooth shading interpolates per-corner values,
  // which differ across creases, surface boundaries and shadow edges (smoothCornerValues).
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  for (const auto& poly : p.polygons) {
    polys->InsertNextCell(vtkIdType(poly.size()));
    for (int v : poly)
      polys->InsertCellPoint(points->InsertNextPoint(p.points[v].x, p.points[v].y, p.points[v].z));
  }
  m_surface->SetPoints(points);
  m_surface->SetPolys(polys);
  m_autoExposure = autoExposure(p);

  m_mapper->SetInputData(m_surface);
  m_mapper->SetLookupTable(m_lut);
  m_mapper->UseLookupTableScalarRangeOn();
  m_mapper->InterpolateScalarsBeforeMappingOn();  // smooth false colour follows the map
  m_actor->SetMapper(m_mapper);
  m_actor->GetProperty()->LightingOff();  // radiosity is the shading
  // A patch's radiosity leaves its front only; its back is not drawn, so from outside a closed
  // room one sees in, and a surface seen from behind does not show the other side's light.
  m_actor->GetProperty()->BackfaceCullingOn();
  m_actor->GetProperty()->SetEdgeColor(0.05, 0.05, 0.05);
  m_renderer->AddActor(m_actor);

  m_outlineMapper->SetInputData(m_outline);
  m_outlineActor->SetMapper(m_outlineMapper);
  m_outlineActor->GetProperty()->SetColor(kOutline[0], kOutline[1], kOutline[2]);
  m_outlineActor->GetProperty()->SetLineWidth(3);
  m_outlineActor->GetProperty()->LightingOff();
  m_outlineActor->PickableOff();
  m_renderer->AddActor(m_outlineActor);

  m_scalarBar->SetLookupTable(m_lut);
  m_scalarBar->SetNumberOfLabels(5);
  m_scalarBar->SetPosition(0.87, 0.1);
  m_scalarBar->SetPosition2(0.12, 0.8);
  m_scalarBar->SetBarRatio(0.3);
  m_scalarBar->SetLabelFormat("%-#6.3g");
  m_renderer->AddActor2D(m_scalarBar);
  m_title->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  m_title->SetPosition(0.012, 0.975);
  m_info->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  m_info->SetPosition(0.012, 0.91);
  m_renderer->AddActor2D(m_title);
  m_renderer->AddActor2D(m_info);
  setFontSize(16);

  if (run.sky) {
    const SkyPanorama& sky = *run.sky;
    m_skyImage->SetDimensions(sky.width, sky.height, 1);
    m_skyImage->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    m_skyTexture->SetInputData(m_skyImage);
    m_skyTexture->InterpolateOn();
    m_skyTexture->RepeatOn();  // bearing wraps around at the panorama's left and right edges
    m_skybox->SetTexture(m_skyTexture);
    // vtkSkybox's sphere projection: texture u = atan2(d·right, d·(plane × right))/2π + 1/2,
    // v = elevation/π + 1/2. With right = −east, plane × right is −north and u is the bearing
    // over 2π: sky.pfm's layout.
    m_skybox->SetProjection(vtkSkybox::Sphere);
    m_skybox->SetFloorPlane(sky.frame.up.x, sky.frame.up.y, sky.frame.up.z, 0);
    m_skybox->SetFloorRight(-sky.frame.east.x, -sky.frame.east.y, -sky.frame.east.z);
    m_skybox->PickableOff();
    m_skybox->VisibilityOff();
    m_renderer->AddActor(m_skybox);
  }
  m_renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  resetCamera();
}

void SceneView::showSky(double exposure) {
  if (!m_run.sky) return;
  m_skybox->SetVisibility(exposure >= 0);
  if (exposure < 0 || exposure == m_skyExposure) return;
  const SkyPanorama& sky = *m_run.sky;
  auto* pixels = static_cast<unsigned char*>(m_skyImage->GetScalarPointer());
  // VTK images start at the bottom row; the panorama's first row is the zenith.
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < sky.width; ++x) {
      // trueColour takes radiosity B = πL of a Lambertian surface; the sky is radiance L.
      const auto c = trueColour(sky.radiance[std::size_t(y) * sky.width + x] * M_PI, exposure);
      std::copy(c.begin(), c.end(), pixels + 3 * (std::size_t(sky.height - 1 - y) * sky.width + x));
    }
  m_skyImage->Modified();
  m_skyExposure = exposure;
}

void SceneView::setFontSize(int pixels) {
  styleText(m_title->GetTextProperty(), pixels);
  m_title->GetTextProperty()->SetVerticalJustificationToTop();
  styleText(m_info->GetTextProperty(), pixels);
  m_info->GetTextProperty()->SetVerticalJustificationToTop();
  m_info->GetTextProperty()->SetFontFamilyToCourier();  // numbers line up
  styleScalarBar(m_scalarBar, pixels);
}

void SceneView::resetCamera() {
  const Camera c = m_run.report.camera ? *m_run.report.camera : framingCamera(m_run.patches);
  vtkCamera* cam = m_renderer->GetActiveCamera();
  cam->SetPosition(c.position.x, c.position.y, c.position.z);
  cam->SetFocalPoint(c.lookAt.x, c.lookAt.y, c.lookAt.z);
  cam->SetViewUp(c.up.x, c.up.y, c.up.z);
  cam->SetViewAngle(c.fovDeg);  // vertical, as in radkit::Camera
  cam->OrthogonalizeViewUp();
  m_renderer->ResetCameraClippingRange();
}

void SceneView::show(const ViewSettings& s) {
  m_actor->GetProperty()->SetEdgeVisibility(s.edges);
  m_scalarBar->SetVisibility(s.mode != ViewMode::Radiosity);
  if (s.mode == ViewMode::FalseColour)
    showFalseColour(s);
  else if (s.mode == ViewMode::FormFactorRow && m_run.formFactors && s.picked >= 0)
    showFormFactorRow(s);
  else
    showTrueColour(s);
  showOutline(s.picked);
  m_info->SetInput(s.picked >= 0 ? patchInfo(s.picked).c_str() : "");
  m_info->SetVisibility(s.picked >= 0);
  m_renderer->ResetCameraClippingRange();
}

void SceneView::showTrueColour(const ViewSettings& s) {
  m_exposureUsed = s.exposure > 0 ? s.exposure : m_autoExposure;
  const std::vector<Vec3>& b = m_run.patches.radiosity;
  m_surface->GetCellData()->AddArray(colourArray(b, m_exposureUsed));
  m_surface->GetPointData()->AddArray(colourArray(corners(m_run.patches, b), m_exposureUsed));
  m_mapper->SetColorModeToDirectScalars();
  m_mapper->SetScalarMode(s.smooth ? VTK_SCALAR_MODE_USE_POINT_FIELD_DATA
                                   : VTK_SCALAR_MODE_USE_CELL_FIELD_DATA);
  m_mapper->SelectColorArray("colour");
  m_scalarBar->SetVisibility(false);
  showSky(m_exposureUsed);
  std::string note;
  if (s.mode == ViewMode::FormFactorRow)
    note = m_run.formFactors ? "  [click a patch to paint its row of F]"
                             : "  [" + m_run.formFactorsMissing + "]";
  m_title->SetInput((m_run.report.sceneName + ": radiosity, true colour (exposure " +
                     formatShort(m_exposureUsed) + (s.exposure > 0 ? "" : ", auto") + ", " +
                     (s.smooth ? "smooth" : "flat") + ")" + note)
                        .c_str());
}

void SceneView::showFalseColour(const ViewSettings& s) {
  showSky(-1);  // a colour scale's background stays neutral
  std::vector<double> v(m_run.patches.size());
  for (int i = 0; i < m_run.patches.size(); ++i)
    v[i] = channelValue(m_run.patches.radiosity[i], s.channel, s.photometric);
  const double hi = falseColourTop(m_run.patches, v);
  fillLookupTable(m_lut, ColourMap::Inferno, 0, hi, false, kZeroColour, kAboveColour);
  setValues(v, s.smooth);
  std::string label = channelLabel(s.channel, s.photometric);
  m_scalarBar->SetTitle(label.replace(label.find(" ("), 2, "\n(").c_str());
  m_scalarBar->SetNumberOfLabels(6);
  m_scalarBar->SetLabelFormat("%-#6.3g");
  m_scalarBar->SetDrawAboveRangeSwatch(*std::max_element(v.begin(), v.end()) > hi);
  m_scalarBar->SetAboveRangeAnnotation("above,\nemitters");
  m_title->SetInput((m_run.report.sceneName + ": false colour, " +
                     channelLabel(s.channel, s.photometric) + " (" +
                     (s.smooth ? "smooth" : "flat") + ")")
                        .c_str());
}

void SceneView::showFormFactorRow(const ViewSettings& s) {
  showSky(-1);
  std::vector<double> row = m_run.formFactors->row(s.picked);
  const double max = std::max(1e-300, *std::max_element(row.begin(), row.end()));
  const double hi = std::pow(10.0, std::ceil(std::log10(max) - 1e-9));
  const double lo = hi * 1e-5;  // five whole decades: the near field to the far corners
  for (double& f : row) f = f > 0 ? f : lo * 1e-3;  // zeros (not seen) below the range
  fillLookupTable(m_lut, ColourMap::Viridis, lo, hi, true, kZeroColour, kAboveColour);
  setValues(row, s.smooth);
  m_scalarBar->SetTitle(("F_ij\ni = " + std::to_string(s.picked)).c_str());
  m_scalarBar->SetNumberOfLabels(6);  // one per decade
  m_scalarBar->SetLabelFormat("%.0e");
  m_scalarBar->SetDrawAboveRangeSwatch(false);
  m_scalarBar->SetDrawBelowRangeSwatch(true);
  m_scalarBar->SetBelowRangeAnnotation("0");
  double sum = 0;
  for (long long k = m_run.formFactors->rowStart[s.picked];
       k < m_run.formFactors->rowStart[s.picked + 1]; ++k)
    sum += m_run.formFactors->value[k];
  m_title->SetInput((m_run.report.sceneName + ": form factors F_ij from patch " +
                     std::to_string(s.picked) + " (log scale; row sum " + formatShort(sum) + ")")
                        .c_str());
}

void SceneView::setValues(const std::vector<double>& perPatch, bool smooth) {
  m_surface->GetCellData()->AddArray(valueArray(perPatch));
  m_surface->GetPointData()->AddArray(valueArray(corners(m_run.patches, perPatch)));
  m_mapper->SetColorModeToMapScalars();
  m_mapper->SetScalarMode(smooth ? VTK_SCALAR_MODE_USE_POINT_FIELD_DATA
                                 : VTK_SCALAR_MODE_USE_CELL_FIELD_DATA);
  m_mapper->SelectColorArray("value");
  m_scalarBar->SetDrawBelowRangeSwatch(false);
}

void SceneView::showOutline(int patch) {
  m_outlineActor->SetVisibility(patch >= 0);
  if (patch < 0) return;
  // Nudged towards the eye along each sight line: the same pixels, never hidden by the patch.
  double eye[3];
  m_renderer->GetActiveCamera()->GetPosition(eye);
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  const auto& poly = m_run.patches.polygons[patch];
  lines->InsertNextCell(vtkIdType(poly.size() + 1));
  for (std::size_t k = 0; k <= poly.size(); ++k) {
    const Vec3& x = m_run.patches.points[poly[k % poly.size()]];
    const Vec3 nudged = x + (Vec3{eye[0], eye[1], eye[2]} - x) * 0.002;
    lines->InsertCellPoint(points->InsertNextPoint(nudged.x, nudged.y, nudged.z));
  }
  m_outline->SetPoints(points);
  m_outline->SetLines(lines);
  m_outline->Modified();
}

std::string SceneView::patchInfo(int i) const {
  const PatchData& p = m_run.patches;
  const std::string units = m_run.report.units.empty() ? "units" : m_run.report.units;
  return "patch " + std::to_string(i) + "  surface '" + m_run.surfaceName(i) + "'" +  //
         "\narea " + formatShort(p.area[i]) + " " + units + "²" +                     //
         "\nrho  " + triple(p.reflectance[i]) +                                       //
         "\nE    " + triple(p.emission[i]) + " W/m²" +                                //
         "\nB    " + triple(p.radiosity[i]) + " W/m²" +                               //
         "\nL_v  " + formatShort(channelValue(p.radiosity[i], Channel::Luminance, true)) + " cd/m²";
}

int SceneView::pick(double x, double y) {
  // Picks what is drawn: a hardware selection honours back-face culling, so a click where a
  // wall is seen from behind finds the patch seen through it (a ray picker returns the wall).
  if (x < 0 || y < 0) return -1;
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(m_renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  const auto px = static_cast<unsigned>(x), py = static_cast<unsigned>(y);
  selector->SetArea(px, py, px, py);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  for (unsigned n = 0; selection && n < selection->GetNumberOfNodes(); ++n) {
    vtkSelectionNode* node = selection->GetNode(n);
    if (node->GetProperties()->Get(vtkSelectionNode::PROP()) != m_actor.GetPointer()) continue;
    auto* ids = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    if (!ids || ids->GetNumberOfTuples() == 0) continue;
    const vtkIdType cell = ids->GetValue(0);
    return cell >= 0 && cell < vtkIdType(m_run.patches.size()) ? int(cell) : -1;
  }
  return -1;
}

}  // namespace radkit::viewer
