// Helpers shared by the VTK filter tests (header-only, test code only).
#ifndef TestFilterHelpers_h
#define TestFilterHelpers_h

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkIdList.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace shock_test
{

/// Records the error and warning messages an object emits.
class MessageLog
{
public:
  explicit MessageLog(vtkObject* object)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback([](vtkObject*, unsigned long event, void* client, void* data) {
      auto* self = static_cast<MessageLog*>(client);
      (event == vtkCommand::ErrorEvent ? self->Errors : self->Warnings) +=
        std::string(static_cast<const char*>(data)) + "\n";
    });
    object->AddObserver(vtkCommand::ErrorEvent, this->Callback);
    object->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }
  std::string Errors, Warnings;

private:
  vtkNew<vtkCallbackCommand> Callback;
};

/// All values of a numeric array, interleaved, as doubles (none for a null array).
inline std::vector<double> Values(vtkDataArray* array)
{
  if (!array)
  {
    return {};
  }
  std::vector<double> v(static_cast<size_t>(array->GetNumberOfValues()));
  for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
  {
    v[static_cast<size_t>(i)] = array->GetComponent(i / array->GetNumberOfComponents(),
      static_cast<int>(i % array->GetNumberOfComponents()));
  }
  return v;
}

/// Runs the algorithm and returns whether the pipeline update succeeded.
inline bool UpdateSucceeds(vtkAlgorithm* algorithm)
{
  return algorithm->GetExecutive()->Update() != 0;
}

/// Every array of `from` into `to`, tuple k of each taken from tuple order[k]; active attributes kept.
inline void CopyTuples(vtkDataSetAttributes* from, const std::vector<vtkIdType>& order, vtkDataSetAttributes* to)
{
  for (int a = 0; a < from->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* source = from->GetArray(a);
    vtkSmartPointer<vtkDataArray> copy = vtk::TakeSmartPointer(source->NewInstance());
    copy->SetName(source->GetName());
    copy->SetNumberOfComponents(source->GetNumberOfComponents());
    copy->SetNumberOfTuples(static_cast<vtkIdType>(order.size()));
    for (size_t k = 0; k < order.size(); ++k)
    {
      copy->SetTuple(static_cast<vtkIdType>(k), order[k], source);
    }
    to->AddArray(copy);
    for (int kind = 0; kind < vtkDataSetAttributes::NUM_ATTRIBUTES; ++kind)
    {
      if (source == from->GetAttribute(kind))
      {
        to->SetActiveAttribute(source->GetName(), kind);
      }
    }
  }
}

/// `mesh` with its points and cells renumbered: new point j is old point points[j], new cell k old cell cells[k].
inline vtkSmartPointer<vtkPolyData> Renumbered(vtkPolyData* mesh, const std::vector<vtkIdType>& points,
  const std::vector<vtkIdType>& cells)
{
  std::vector<vtkIdType> newId(points.size());
  for (size_t j = 0; j < points.size(); ++j)
  {
    newId[static_cast<size_t>(points[j])] = static_cast<vtkIdType>(j);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> xyz;
  xyz->SetDataTypeToDouble();
  for (vtkIdType old : points)
  {
    double x[3];
    mesh->GetPoint(old, x);
    xyz->InsertNextPoint(x);
  }
  out->SetPoints(xyz);
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIdList> ids;
  for (vtkIdType old : cells)
  {
    mesh->GetCellPoints(old, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      ids->SetId(k, newId[static_cast<size_t>(ids->GetId(k))]);
    }
    polys->InsertNextCell(ids);
  }
  out->SetPolys(polys);
  CopyTuples(mesh->GetPointData(), points, out->GetPointData());
  CopyTuples(mesh->GetCellData(), cells, out->GetCellData());
  return out;
}

/// The largest difference between tuple i of `a` and tuple order[i] of `b`.
inline double MaxDifferenceThrough(vtkDataArray* a, vtkDataArray* b, const std::vector<vtkIdType>& order)
{
  double m = 0.0;
  for (size_t i = 0; i < order.size(); ++i)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      m = std::max(m, std::abs(a->GetComponent(static_cast<vtkIdType>(i), c) - b->GetComponent(order[i], c)));
    }
  }
  return m;
}

} // namespace shock_test

#endif
