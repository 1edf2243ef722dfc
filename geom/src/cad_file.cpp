// STEP / IGES faces through the OCCT data-exchange readers, and a small STEP writer for
// B-spline faces. Lengths in the session are millimetres (xstep.cascade.unit); the readers
// convert from the unit the file states.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Precision.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepData_StepModel.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <StepShape_AdvancedFace.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>
#include <mutex>
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif
#include <system_error>
#include <vector>

#include "occt_surface.h"
#include "stitchsim/geom/cad_surface.h"

namespace stitchsim::geom {
namespace {

// Once per process: the kernel's messages (to stdout by default) silenced, stitchsim's output
// is its own; the data-exchange controllers registered. Their registries live until exit and
// are never freed, so the leak checker of sanitizer builds is told to ignore them.
void QuietKernel() {
  static std::once_flag once;
  std::call_once(once, [] {
#if defined(__SANITIZE_ADDRESS__)
    __lsan::ScopedDisabler kernel_registries;
#endif
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    STEPControl_Controller::Init();
    IGESControl_Controller::Init();
  });
}

std::string FaceName(XSControl_Reader& reader, const TopoDS_Face& face) {
  const Handle(XSControl_TransferReader) tr = reader.WS()->TransferReader();
  if (tr.IsNull()) return "";
  for (int mode : {1, -1}) {
    const Handle(StepRepr_RepresentationItem) item =
        Handle(StepRepr_RepresentationItem)::DownCast(tr->EntityFromShapeResult(face, mode));
    if (!item.IsNull() && !item->Name().IsNull()) return item->Name()->ToCString();
  }
  return "";
}

std::unique_ptr<Surface> ReadFace(XSControl_Reader& reader, const std::filesystem::path& file,
                                  CadFormat format, const CadFaceRef& ref, std::string& error) {
  const char* what = format == CadFormat::kStep ? "STEP" : "IGES";
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  if (reader.ReadFile(file.string().c_str()) != IFSelect_RetDone) {
    error = file.string() + " is not a readable " + what + " file";
    return nullptr;
  }
  reader.TransferRoots();
  const TopoDS_Shape shape = reader.OneShape();
  std::vector<TopoDS_Face> faces;
  if (!shape.IsNull()) {
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
      faces.push_back(TopoDS::Face(ex.Current()));
    }
  }
  if (faces.empty()) {
    error = file.string() + " has no faces";
    return nullptr;
  }
  const TopoDS_Face* face = nullptr;
  if (!ref.name.empty()) {
    for (const auto& f : faces) {
      if (format == CadFormat::kStep && FaceName(reader, f) == ref.name) {
        face = &f;
        break;
      }
    }
    if (!face) {
      error = file.string() + " has no face named '" + ref.name + "'" +
              (format == CadFormat::kIges ? " (IGES faces are chosen by index)" : "");
      return nullptr;
    }
  } else if (ref.index < 0 || ref.index >= static_cast<int>(faces.size())) {
    error = "face " + std::to_string(ref.index) + " is out of range: " + file.string() + " has " +
            std::to_string(faces.size()) + " face(s), 0.." + std::to_string(faces.size() - 1);
    return nullptr;
  } else {
    face = &faces[static_cast<std::size_t>(ref.index)];
  }
  const Handle(Geom_Surface) s = BRep_Tool::Surface(*face);
  detail::ParamBox box;
  BRepTools::UVBounds(*face, box.u0, box.u1, box.v0, box.v1);
  const bool reversed = face->Orientation() == TopAbs_REVERSED;
  auto out = detail::MakeOcctSurface(s, box, reversed != ref.flip_normal,
                                     format == CadFormat::kStep ? "step" : "iges", error);
  if (!out) error = file.string() + ": " + error;
  return out;
}

}  // namespace

std::unique_ptr<Surface> ReadCadFace(const std::filesystem::path& file, CadFormat format,
                                     const CadFaceRef& face, std::string& error) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) {
    error = "cannot read " + file.string() + ": " + ec.message();
    return nullptr;
  }
  if (size == 0) {
    error = file.string() + " is empty";
    return nullptr;
  }
  QuietKernel();
  try {
    if (format == CadFormat::kStep) {
      STEPControl_Reader reader;
      return ReadFace(reader, file, format, face, error);
    }
    IGESControl_Reader reader;
    return ReadFace(reader, file, format, face, error);
  } catch (const Standard_Failure& e) {
    error = file.string() + ": the kernel failed: " + e.GetMessageString();
    return nullptr;
  }
}

namespace {

// The face made of `spec`'s B-spline, or a null face with `error` set.
TopoDS_Face BSplineFace(const BSplineSpec& spec, std::string& error) {
  const Handle(Geom_BSplineSurface) s = detail::BuildBSpline(spec, error);
  if (s.IsNull()) return {};
  BRepBuilderAPI_MakeFace mk(s, Precision::Confusion());
  if (!mk.IsDone()) {
    error = "the kernel cannot make a face of the B-spline";
    return {};
  }
  TopoDS_Face f = mk.Face();
  if (spec.flip_normal) f.Reverse();
  return f;
}

}  // namespace

bool WriteBSplineCad(const std::vector<BSplineSpec>& faces, const std::vector<std::string>& names,
                     const std::filesystem::path& file, CadFormat format, const std::string& unit,
                     std::string& error) {
  // Both writers convert from the session's millimetres to `unit` themselves. The STEP writer
  // takes its unit from the session parameter when it is constructed (OCCT 7.6), so the
  // parameter is set first: set after, the first writer of a process states the unit without
  // converting and every later one converts with the unit left by the one before.
  if (unit != "MM" && unit != "CM" && unit != "M" && unit != "INCH") {
    error = "unit must be MM, CM, M or INCH, got '" + unit + "'";
    return false;
  }
  QuietKernel();
  try {
    BRep_Builder b;
    TopoDS_Compound c;
    b.MakeCompound(c);
    for (const BSplineSpec& spec : faces) {
      const TopoDS_Face f = BSplineFace(spec, error);
      if (f.IsNull()) return false;
      b.Add(c, f);
    }
    if (format == CadFormat::kIges) {
      IGESControl_Writer writer(unit == "INCH" ? "IN" : unit.c_str(), 0);
      const bool added = writer.AddShape(c);
      writer.ComputeModel();
      if (!added || !writer.Write(file.string().c_str())) {
        error = "cannot write " + file.string();
        return false;
      }
      return true;
    }
    Interface_Static::SetCVal("xstep.cascade.unit", "MM");
    Interface_Static::SetCVal("write.step.unit", unit.c_str());
    STEPControl_Writer writer;
    if (writer.Transfer(c, STEPControl_AsIs) != IFSelect_RetDone) {
      error = "the kernel cannot translate the faces to STEP";
      return false;
    }
    // Names: the model lists the faces' ADVANCED_FACE entities in the compound's order.
    const Handle(StepData_StepModel) model = writer.Model();
    std::size_t k = 0;
    for (int i = 1; i <= model->NbEntities() && k < names.size(); ++i) {
      const auto face = Handle(StepShape_AdvancedFace)::DownCast(model->Value(i));
      if (!face.IsNull()) face->SetName(new TCollection_HAsciiString(names[k++].c_str()));
    }
    if (writer.Write(file.string().c_str()) != IFSelect_RetDone) {
      error = "cannot write " + file.string();
      return false;
    }
    return true;
  } catch (const Standard_Failure& e) {
    error = std::string("the kernel failed: ") + e.GetMessageString();
    return false;
  }
}

}  // namespace stitchsim::geom
