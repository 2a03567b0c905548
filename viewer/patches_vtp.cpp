// radiosity.vtp through VTK's XML reader (ASCII as radkit writes it, or binary as ParaView
// saves it), copied into PatchData so the rest of the viewer sees plain vectors.
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>

#include "geometry/scene_loader.h"
#include "viewer/run_folder.h"

namespace radkit::viewer {

namespace {

/// Collects VTK's error and warning text instead of letting it print to the terminal.
class MessageCollector : public vtkCommand {
 public:
  static MessageCollector* New() { return new MessageCollector; }
  void Execute(vtkObject*, unsigned long, void* callData) override {
    if (callData) text += static_cast<const char*>(callData);
  }
  std::string text;
};

vtkDataArray* cellArray(vtkPolyData* data, const char* name, int components,
                        const std::string& path) {
  vtkDataArray* a = data->GetCellData()->GetArray(name);
  if (!a)
    throw InputError(
        path + ": no cell array '" + name +
        "' (radkit mesh writes patches.vtp without radiosity; view the folder of `radkit run`)");
  if (a->GetNumberOfComponents() != components ||
      a->GetNumberOfTuples() != data->GetNumberOfCells())
    throw InputError(path + ": cell array '" + name + "' must have " + std::to_string(components) +
                     " component(s) per patch");
  return a;
}

std::vector<Vec3> triples(vtkDataArray* a) {
  std::vector<Vec3> v(a->GetNumberOfTuples());
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    v[i] = {a->GetComponent(i, 0), a->GetComponent(i, 1), a->GetComponent(i, 2)};
  return v;
}

}  // namespace

PatchData readPatchesVtp(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path + ": missing; `radkit run --out DIR` writes radiosity.vtp into DIR");
  vtkNew<vtkXMLPolyDataReader> reader;
  vtkNew<MessageCollector> messages;
  reader->AddObserver(vtkCommand::ErrorEvent, messages);
  reader->AddObserver(vtkCommand::WarningEvent, messages);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* data = reader->GetOutput();
  if (!messages->text.empty() || !data || data->GetNumberOfPoints() == 0)
    throw InputError(
        path + ": not a readable VTK XML PolyData file" +
        (messages->text.empty() ? std::string(" (no points)") : ": " + messages->text));
  if (data->GetNumberOfCells() != data->GetNumberOfPolys())
    throw InputError(path + ": holds vertices, lines or strips; radkit patches are polygons only");

  PatchData p;
  p.points.resize(data->GetNumberOfPoints());
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i) {
    const double* x = data->GetPoint(i);
    p.points[i] = {x[0], x[1], x[2]};
  }
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = data->GetPolys();
  polys->InitTraversal();
  while (polys->GetNextCell(ids)) {
    if (ids->GetNumberOfIds() < 3 || ids->GetNumberOfIds() > 4)
      throw InputError(path + ": polygon " + std::to_string(p.polygons.size()) + " has " +
                       std::to_string(ids->GetNumberOfIds()) +
                       " corners; patches are triangles or quads");
    std::vector<int>& poly = p.polygons.emplace_back();
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) poly.push_back(int(ids->GetId(k)));
  }
  vtkDataArray* surface = cellArray(data, "surface", 1, path);
  vtkDataArray* area = cellArray(data, "area", 1, path);
  for (int i = 0; i < p.size(); ++i) {
    p.surface.push_back(int(surface->GetComponent(i, 0)));
    p.area.push_back(area->GetComponent(i, 0));
  }
  p.reflectance = triples(cellArray(data, "reflectance", 3, path));
  p.emission = triples(cellArray(data, "emission", 3, path));
  p.radiosity = triples(cellArray(data, "radiosity", 3, path));
  for (int i = 0; i < p.size(); ++i)
    if (!isFinite(p.radiosity[i]))
      throw InputError(path + ": patch " + std::to_string(i) + " has a non-finite radiosity");
  return p;
}

}  // namespace radkit::viewer
