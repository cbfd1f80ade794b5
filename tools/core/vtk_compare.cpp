// VTK XML comparison (see vtk_compare.hpp).
#include "core/vtk_compare.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>
#include <vtkXMLGenericDataObjectReader.h>

#include <set>

#include "core/error.hpp"

namespace finverse {
namespace {

// Records that the reader reported an error (VTK 9.1's generic reader has no error query).
class ErrorFlag : public vtkCommand {
 public:
  static ErrorFlag* New() { return new ErrorFlag; }
  void Execute(vtkObject*, unsigned long, void*) override { raised = true; }
  bool raised = false;
};

vtkSmartPointer<vtkDataSet> load(const std::filesystem::path& p) {
  if (!std::filesystem::exists(p)) throw Error(p.string() + ": file not found");
  // Our one-line error replaces VTK's multi-line console messages.
  vtkObject::GlobalWarningDisplayOff();
  vtkNew<vtkXMLGenericDataObjectReader> reader;
  vtkNew<ErrorFlag> flag;
  reader->AddObserver(vtkCommand::ErrorEvent, flag);
  reader->SetFileName(p.c_str());
  reader->Update();
  auto* ds = vtkDataSet::SafeDownCast(reader->GetOutput());
  if (!ds || flag->raised) throw Error(p.string() + ": not a readable VTK XML dataset");
  return ds;
}

NdArray<double> to_array(vtkDataArray* a) {
  const auto n = static_cast<std::size_t>(a->GetNumberOfTuples());
  const auto k = static_cast<std::size_t>(a->GetNumberOfComponents());
  NdArray<double> out(k == 1 ? std::vector<std::size_t>{n} : std::vector<std::size_t>{n, k});
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < k; ++j) out.data[i * k + j] = a->GetComponent(static_cast<vtkIdType>(i), static_cast<int>(j));
  return out;
}

// Connectivity as one flat array: per cell its type, size and point ids.
NdArray<double> cells_of(vtkDataSet* ds) {
  std::vector<double> flat;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < ds->GetNumberOfCells(); ++c) {
    ds->GetCellPoints(c, ids);
    flat.push_back(ds->GetCellType(c));
    flat.push_back(static_cast<double>(ids->GetNumberOfIds()));
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i) flat.push_back(static_cast<double>(ids->GetId(i)));
  }
  return NdArray<double>({flat.size()}, std::move(flat));
}

void compare_data(const std::string& kind, vtkFieldData* r, vtkFieldData* c, const Tolerances& tol, const std::string& prefix,
                  std::vector<Comparison>& out) {
  std::set<std::string> names;
  for (int i = 0; i < r->GetNumberOfArrays(); ++i) if (r->GetArrayName(i)) names.insert(r->GetArrayName(i));
  for (int i = 0; i < c->GetNumberOfArrays(); ++i) if (c->GetArrayName(i)) names.insert(c->GetArrayName(i));
  for (const auto& n : names) {
    const std::string object = prefix + kind + "/" + n;
    if (tol.ignored(object)) continue;
    auto* ra = r->GetArray(n.c_str());
    auto* ca = c->GetArray(n.c_str());
    if (!ca) out.push_back(mismatch(object, "MISSING", "array missing in candidate"));
    else if (!ra) out.push_back(mismatch(object, "EXTRA", "array only in candidate"));
    else out.push_back(compare_values(object, to_array(ra), to_array(ca), tol.for_object(object)));
  }
}

}  // namespace

bool is_vtk_xml(const std::filesystem::path& p) {
  const auto e = p.extension().string();
  return e == ".vtp" || e == ".vtu" || e == ".vtr" || e == ".vti" || e == ".vts";
}

std::vector<Comparison> compare_vtk(const std::filesystem::path& reference, const std::filesystem::path& candidate,
                                    const Tolerances& tol, const std::string& prefix) {
  auto r = load(reference), c = load(candidate);
  std::vector<Comparison> out;
  if (std::string(r->GetClassName()) != c->GetClassName()) {
    out.push_back(mismatch(prefix + "type", "DTYPE", std::string(r->GetClassName()) + " vs " + c->GetClassName()));
    return out;
  }
  auto* rp = vtkPointSet::SafeDownCast(r);
  auto* cp = vtkPointSet::SafeDownCast(c);
  if (rp && cp && !tol.ignored(prefix + "Points") && rp->GetPoints() && cp->GetPoints())
    out.push_back(compare_values(prefix + "Points", to_array(rp->GetPoints()->GetData()), to_array(cp->GetPoints()->GetData()),
                                 tol.for_object(prefix + "Points")));
  auto* rr = vtkRectilinearGrid::SafeDownCast(r);
  auto* cr = vtkRectilinearGrid::SafeDownCast(c);
  if (rr && cr) {
    const char* axes[3] = {"Coordinates/x", "Coordinates/y", "Coordinates/z"};
    vtkDataArray* ra[3] = {rr->GetXCoordinates(), rr->GetYCoordinates(), rr->GetZCoordinates()};
    vtkDataArray* ca[3] = {cr->GetXCoordinates(), cr->GetYCoordinates(), cr->GetZCoordinates()};
    for (int a = 0; a < 3; ++a)
      out.push_back(compare_values(prefix + axes[a], to_array(ra[a]), to_array(ca[a]), tol.for_object(prefix + axes[a])));
  }
  if (!tol.ignored(prefix + "Cells")) {
    auto rc = cells_of(r), cc = cells_of(c);
    if (rc.shape != cc.shape || rc.data != cc.data)
      out.push_back(mismatch(prefix + "Cells", "DIFFERENT",
                             std::to_string(r->GetNumberOfCells()) + " vs " + std::to_string(c->GetNumberOfCells()) + " cells or different connectivity"));
    else
      out.push_back(compare_values(prefix + "Cells", rc, cc, {}));
  }
  compare_data("PointData", r->GetPointData(), c->GetPointData(), tol, prefix, out);
  compare_data("CellData", r->GetCellData(), c->GetCellData(), tol, prefix, out);
  return out;
}

}  // namespace finverse
