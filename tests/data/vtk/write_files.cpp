#include <vtkBitArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkRectilinearGrid.h>
#include <vtkRectilinearGridWriter.h>
#include <vtkStringArray.h>
#include <vtkStructuredPointsWriter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridWriter.h>
int main() {
  vtkNew<vtkUnstructuredGrid> g;
  vtkNew<vtkPoints> p;
  double h[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (auto& x : h)
    p->InsertNextPoint(x);
  g->SetPoints(p);
  vtkIdType ids[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  g->InsertNextCell(VTK_HEXAHEDRON, 8, ids);
  vtkNew<vtkFloatArray> v;
  v->SetName("velocity");
  v->SetNumberOfComponents(3);
  v->SetComponentName(0, "vx");
  v->SetNumberOfTuples(8);
  for (int i = 0; i < 24; ++i)
    v->SetValue(i, i);
  g->GetPointData()->AddArray(v);
  vtkNew<vtkFloatArray> t;
  t->SetName("temp");
  t->SetNumberOfTuples(8);
  for (int i = 0; i < 8; ++i)
    t->SetValue(i, i * 0.5);
  g->GetPointData()->SetScalars(t);
  vtkNew<vtkIntArray> m;
  m->SetName("mat");
  m->SetNumberOfTuples(1);
  m->SetValue(0, 7);
  g->GetCellData()->AddArray(m);
  vtkNew<vtkBitArray> b;
  b->SetName("flag");
  b->SetNumberOfTuples(8);
  for (int i = 0; i < 8; ++i)
    b->SetValue(i, i & 1);
  g->GetPointData()->AddArray(b);
  vtkNew<vtkStringArray> s;
  s->SetName("label");
  s->SetNumberOfTuples(1);
  s->SetValue(0, "part one");
  g->GetFieldData()->AddArray(s);
  for (int bin = 0; bin < 2; ++bin) {
    vtkNew<vtkUnstructuredGridWriter> w;
    w->SetInputData(g);
    w->SetFileName(bin ? "w_bin.vtk" : "w_ascii.vtk");
    if (bin) w->SetFileTypeToBinary();
    w->Write();
    vtkNew<vtkUnstructuredGridWriter> w4;
    w4->SetInputData(g);
    w4->SetFileVersion(42);
    w4->SetFileName(bin ? "w42_bin.vtk" : "w42_ascii.vtk");
    if (bin) w4->SetFileTypeToBinary();
    w4->Write();
    vtkNew<vtkImageData> im;
    im->SetDimensions(3, 3, 3);
    im->SetOrigin(0.5, 0, 0);
    im->SetSpacing(1, 2, 3);
    vtkNew<vtkFloatArray> q;
    q->SetName("q");
    q->SetNumberOfTuples(27);
    for (int i = 0; i < 27; ++i)
      q->SetValue(i, i);
    im->GetPointData()->SetScalars(q);
    vtkNew<vtkStructuredPointsWriter> sw;
    sw->SetInputData(im);
    sw->SetFileName(bin ? "sp_bin.vtk" : "sp_ascii.vtk");
    if (bin) sw->SetFileTypeToBinary();
    sw->Write();
    vtkNew<vtkRectilinearGrid> rg;
    rg->SetDimensions(2, 3, 2);
    vtkNew<vtkFloatArray> xs, ys, zs;
    xs->InsertNextValue(0);
    xs->InsertNextValue(1);
    ys->InsertNextValue(0);
    ys->InsertNextValue(1);
    ys->InsertNextValue(3);
    zs->InsertNextValue(0);
    zs->InsertNextValue(2);
    rg->SetXCoordinates(xs);
    rg->SetYCoordinates(ys);
    rg->SetZCoordinates(zs);
    vtkNew<vtkRectilinearGridWriter> rw;
    rw->SetInputData(rg);
    rw->SetFileName(bin ? "rg_bin.vtk" : "rg_ascii.vtk");
    if (bin) rw->SetFileTypeToBinary();
    rw->Write();
  }
}
