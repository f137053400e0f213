// vtk_read.cpp -- VTK's readers on bytes we read (docs/vtk.md section 6). Every message VTK
// emits while one of our reads runs ends up in that read's capture, never on the terminal:
//   - the reader's own errors and warnings: ErrorEvent / WarningEvent observers on it;
//   - messages of objects without observers (VTK's XML parser, data arrays): VTK sends those
//     to its process-wide vtkOutputWindow, and some readers log straight to vtkLogger (which
//     prints to stderr). We install once (std::call_once) a window and a vtkLogger callback
//     that append them to the capture of the read running on the calling thread
//     (thread_local), and turn vtkLogger's stderr output off. Those are process-wide
//     settings, acceptable because they only change where VTK's diagnostics go (the tool
//     prints ours instead); an application that wants VTK's own output can set it again
//     after its first import (docs/vtk.md section 6).
// A VTK warning that says "Error reading" (the legacy reader's "Error reading ascii data.
// Possible mismatch of datasize with declaration.") is a failed read: it counts as an error.
#include "vtk_read.hpp"

#include <mutex>
#include <string>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPolyDataReader.h>
#include <vtkRectilinearGridReader.h>
#include <vtkSTLReader.h>
#include <vtkStructuredGridReader.h>
#include <vtkStructuredPointsReader.h>
#include <vtkUnstructuredGridReader.h>

#include "import_error.hpp"
#include "vtk_preflight.hpp"
#include "vtk_xml_reader.hpp"

namespace tlod_import_detail {
namespace {

struct Capture {
  std::string errors, warnings;
};

thread_local Capture* tl_capture = nullptr;

// "ERROR: In /path/vtkFoo.cxx, line 12\nvtkFoo (0x55d0): message\n\n" -> "vtkFoo: message"; object
// addresses dropped everywhere, and a pipeline's dump of its request cut after its first words.
std::string clean(const char* text) {
  std::string s(text ? text : "");
  if (s.rfind("ERROR: In ", 0) == 0 || s.rfind("Warning: In ", 0) == 0 || s.rfind("Generic Warning: In ", 0) == 0) {
    const size_t nl = s.find('\n');
    s = nl == std::string::npos ? "" : s.substr(nl + 1);
  }
  const size_t dump = s.find(" returned failure for request");
  if (dump != std::string::npos) s.erase(dump + 29);
  for (size_t at; (at = s.find("(0x")) != std::string::npos;) {
    const size_t from = at > 0 && s[at - 1] == ' ' ? at - 1 : at;
    const size_t close = s.find(')', at);
    s.erase(from, close == std::string::npos ? std::string::npos : close + 1 - from);
  }
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ')
    s.pop_back();
  return s;
}

// One message into c (nothing when no read is capturing); see the header comment on "Error reading".
void add(Capture* c, bool error, const char* text) {
  if (!c) return;
  const std::string m = clean(text);
  std::string& to = error || m.find("Error reading") != std::string::npos ? c->errors : c->warnings;
  if (m.empty() || to.find(m) != std::string::npos) return; // VTK repeats itself
  if (!to.empty()) to += "; ";
  to += m;
}

class QuietWindow : public vtkOutputWindow {
public:
  static QuietWindow* New() {
    QuietWindow* w = new QuietWindow;
    w->InitializeObjectBase();
    return w;
  }
  void DisplayText(const char*) override {}
  void DisplayErrorText(const char* t) override { add(tl_capture, true, t); }
  void DisplayWarningText(const char* t) override { add(tl_capture, false, t); }
  void DisplayGenericWarningText(const char* t) override { DisplayWarningText(t); }
  void DisplayDebugText(const char*) override {}
};

void on_log(void*, const vtkLogger::Message& m) {
  if (m.verbosity <= vtkLogger::VERBOSITY_WARNING)
    add(tl_capture, m.verbosity < vtkLogger::VERBOSITY_WARNING, m.message);
}

void install_quiet_window() {
  static std::once_flag once;
  std::call_once(once, [] {
    QuietWindow* w = QuietWindow::New();
    vtkOutputWindow::SetInstance(w);
    w->Delete();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    vtkLogger::AddCallback("tesslod-import", on_log, nullptr, vtkLogger::VERBOSITY_WARNING);
  });
}

void on_message(vtkObject*, unsigned long event, void* client, void* call) {
  add(static_cast<Capture*>(client), event == vtkCommand::ErrorEvent, static_cast<const char*>(call));
}

void on_progress(vtkObject*, unsigned long, void* client, void* call) {
  const auto* p = static_cast<const std::function<void(double)>*>(client);
  if (*p && call) (*p)(*static_cast<double*>(call));
}

// Observers on reader into c; progress forwarded.
void observe(vtkAlgorithm* reader, Capture* c, const std::function<void(double)>* progress) {
  vtkNew<vtkCallbackCommand> msg;
  msg->SetCallback(on_message);
  msg->SetClientData(c);
  reader->AddObserver(vtkCommand::ErrorEvent, msg);
  reader->AddObserver(vtkCommand::WarningEvent, msg);
  vtkNew<vtkCallbackCommand> prog;
  prog->SetCallback(on_progress);
  prog->SetClientData(const_cast<std::function<void(double)>*>(progress));
  reader->AddObserver(vtkCommand::ProgressEvent, prog);
}

vtkSmartPointer<vtkDataReader> legacy_reader(const std::string& dataset) {
  if (dataset == "unstructured_grid") return vtkSmartPointer<vtkUnstructuredGridReader>::New();
  if (dataset == "polydata") return vtkSmartPointer<vtkPolyDataReader>::New();
  if (dataset == "structured_grid") return vtkSmartPointer<vtkStructuredGridReader>::New();
  if (dataset == "rectilinear_grid") return vtkSmartPointer<vtkRectilinearGridReader>::New();
  if (dataset == "structured_points") return vtkSmartPointer<vtkStructuredPointsReader>::New();
  fail(TLOD_ERROR_UNSUPPORTED, format("DATASET %.40s: not read (UNSTRUCTURED_GRID, POLYDATA, STRUCTURED_GRID, "
                                      "RECTILINEAR_GRID or STRUCTURED_POINTS)",
                                      dataset.c_str()));
}

vtkSmartPointer<vtkAlgorithm> make_reader(const VtkSource& src, size_t room) {
  switch (src.format) {
  case VtkFormat::Legacy: {
    std::string dataset;
    preflight_legacy(src.data, src.size, room, &dataset);
    vtkSmartPointer<vtkDataReader> r = legacy_reader(dataset);
    r->ReadAllScalarsOn();
    r->ReadAllVectorsOn();
    r->ReadAllNormalsOn();
    r->ReadAllTensorsOn();
    r->ReadAllFieldsOn();
    r->ReadAllTCoordsOn();
    r->ReadAllColorScalarsOn();
    r->SetBinaryInputString(src.data, int(src.size));
    r->ReadFromInputStringOn();
    return r;
  }
  case VtkFormat::Vtu:
  case VtkFormat::Vtp: {
    preflight_xml(src.data, src.size, room);
    vtkSmartPointer<vtkXMLReader> r;
    if (src.format == VtkFormat::Vtu)
      r = vtkSmartPointer<GridReader>::New();
    else
      r = vtkSmartPointer<PolyReader>::New();
    r->ReadFromInputStringOn();
    r->SetInputString(std::string(src.data, src.size));
    return r;
  }
  case VtkFormat::Stl: {
    preflight_stl(src.data, src.size);
    if (!src.file_path) fail(TLOD_ERROR_UNSUPPORTED, "STL from memory: VTK's STL reader reads files only");
    vtkSmartPointer<vtkSTLReader> r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(src.file_path);
    r->MergingOn(); // STL repeats every corner; merged points give a connected surface
    return r;
  }
  }
  fail(TLOD_ERROR_UNSUPPORTED, "unknown VTK format");
}

// Sets tl_capture for the lifetime of a read (restored on throw).
struct CaptureScope {
  Capture* saved;
  explicit CaptureScope(Capture* c) : saved(tl_capture) { tl_capture = c; }
  ~CaptureScope() { tl_capture = saved; }
};

} // namespace

bool vtk_format_of(const std::string& name, VtkFormat* out) {
  const char* s = name.c_str();
  if (_tlod_str_ends_with_nocase(s, ".vtk"))
    *out = VtkFormat::Legacy;
  else if (_tlod_str_ends_with_nocase(s, ".vtu"))
    *out = VtkFormat::Vtu;
  else if (_tlod_str_ends_with_nocase(s, ".vtp"))
    *out = VtkFormat::Vtp;
  else if (_tlod_str_ends_with_nocase(s, ".stl"))
    *out = VtkFormat::Stl;
  else
    return false;
  return true;
}

vtkSmartPointer<vtkDataSet> read_vtk(const VtkSource& src, size_t budget_room,
                                     const std::function<void(const std::string&)>& warn,
                                     const std::function<void(double)>& progress) {
  install_quiet_window();
  if (src.size > size_t(INT32_MAX)) fail(TLOD_ERROR_UNSUPPORTED, "file larger than 2 GiB (VTK reads ints)");
  Capture capture;
  CaptureScope scope(&capture);
  vtkSmartPointer<vtkAlgorithm> reader = make_reader(src, budget_room);
  observe(reader, &capture, &progress);
  reader->Update();
  vtkDataSet* out = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
  if (!capture.warnings.empty()) warn("VTK: " + capture.warnings);
  if (!capture.errors.empty()) fail(TLOD_ERROR_PARSE, "VTK: " + capture.errors);
  if (!out) fail(TLOD_ERROR_PARSE, "VTK's reader produced no data set");
  return out;
}

} // namespace tlod_import_detail
