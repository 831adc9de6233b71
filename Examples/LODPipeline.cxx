// LODPipeline: levels of detail of an isosurface, and the smooth meshes between them, in one VTK
// pipeline: vtkSampleFunction -> vtkFlyingEdges3D -> vtkTriangleCollapseDecimation (the levels)
// -> vtkLODGeomorph (time i is level i; time i + f moves level i the fraction f of the way to
// level i + 1, with level i's triangles).
//
//   LODPipeline [output-prefix]
//
// writes <prefix>.vtm (the levels; open it in ParaView; their files go into <prefix>/) and
// <prefix>_<time>.vtp for a few times. Exits with 1 when a file cannot be written.
#include "vtkErrorCode.h"
#include "vtkFlyingEdges3D.h"
#include "vtkLODGeomorph.h"
#include "vtkNew.h"
#include "vtkSampleFunction.h"
#include "vtkSphere.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkXMLMultiBlockDataWriter.h"
#include "vtkXMLPolyDataWriter.h"
#include <filesystem>
#include <iostream>
#include <string>

// vtkXMLWriter::Write returns 1 even where it could not write the file; its error code tells.
bool WriteSucceeded(vtkXMLWriter* writer)
{
  return writer->Write() == 1 && writer->GetErrorCode() == vtkErrorCode::NoError;
}

int main(int argc, char* argv[])
{
  const std::string first = argc > 1 ? argv[1] : "";
  if (argc > 2 || (!first.empty() && first[0] == '-'))
  {
    const bool help = first == "-h" || first == "--help";
    (help ? std::cout : std::cerr) << "usage: " << argv[0] << " [output-prefix]\n"
      << "writes <prefix>.vtm (the levels, files in <prefix>/) and <prefix>_<time>.vtp; "
         "the prefix defaults to lod\n";
    return help ? 0 : 2;
  }
  const std::string prefix = argc > 1 ? argv[1] : "lod";
  // The levels' files go into <prefix>/, which the writer would fail to make without a word in
  // its error code (a file of that name, say).
  std::error_code error;
  std::filesystem::create_directories(prefix, error);
  if (error)
  {
    std::cerr << "cannot create the folder " << prefix << ": " << error.message() << "\n";
    return 1;
  }
  vtkNew<vtkSphere> shape; // radius 0.5: its isosurface at 0 in a 50^3 volume over [-1, 1]^3
  vtkNew<vtkSampleFunction> volume;
  volume->SetImplicitFunction(shape);
  vtkNew<vtkFlyingEdges3D> surface;
  surface->SetInputConnection(volume->GetOutputPort());
  surface->SetValue(0, 0.0);
  vtkNew<vtkTriangleCollapseDecimation> levels; // levels 1-4 keep 38%, 14%, 5.3%, 2%
  levels->SetInputConnection(surface->GetOutputPort());
  levels->SetNumberOfLevels(4);
  levels->SetTargetReduction(0.98);
  vtkNew<vtkXMLMultiBlockDataWriter> levelWriter;
  levelWriter->SetInputConnection(levels->GetOutputPort());
  levelWriter->SetFileName((prefix + ".vtm").c_str());
  bool written = WriteSucceeded(levelWriter);
  vtkNew<vtkLODGeomorph> geomorph;
  geomorph->SetInputConnection(levels->GetOutputPort());
  vtkNew<vtkXMLPolyDataWriter> meshWriter;
  meshWriter->SetInputConnection(geomorph->GetOutputPort());
  for (const char* time : { "0", "0.5", "1", "2.25", "4" })
  {
    geomorph->UpdateTimeStep(std::stod(time)); // as a ParaView animation asks; the writer keeps it
    meshWriter->SetFileName((prefix + "_" + time + ".vtp").c_str());
    written = written && WriteSucceeded(meshWriter);
  }
  if (!written)
  {
    std::cerr << "cannot write the files of " << prefix << "\n";
  }
  return written ? 0 : 1;
}
