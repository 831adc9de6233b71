// MeshLOD demo: a marching-cubes isosurface turned into levels of detail with smooth
// transitions between them, everything written for ParaView, and a picture of a few levels.
//
//   MeshLODDemo [output-directory] [--field NAME] [--resolution N] [--input FILE] [--frames N]
//               [--no-render]
//
// output-directory  default demo-output; created if needed
// --field           metaballs (default), gyroid, torus, sphere or wavelet
// --resolution      samples per axis of the volume (default: about 200k triangles)
// --input           your own surface instead of the isosurface: a .vtp, .vtk (legacy polydata),
//                   .stl, .ply or .obj file (polygons and strips are triangulated first)
// --frames          frames per level transition in the time series (default 8)
// --no-render       skip the picture (it needs an X display; run-demo.sh provides one with Xvfb)
//
// Each hierarchy producer (HierarchyProducers() below: vtkTriangleCollapseDecimation, named
// triangle_collapse, and vtkVertexClusterOctree, named vertex_cluster_octree) makes levels of
// detail of the same isosurface (or input surface), and the demo writes
// into the output directory, <name> being the producer's name:
//   <name>.vtm + <name>/           the hierarchy: block i = "Level i", level 0 = the isosurface
//                                  (flying edges at 0 of the field), with the morph arrays and
//                                  the field data of MeshLODHierarchy.h
//   <name>_frames.pvd +            vtkLODGeomorph driven through the pipeline time, as a
//   <name>_frames/frame_NNN.vtp    ParaView animation drives it: time = level of detail, from 0
//                                  (the finest level) to the coarsest, --frames per transition
//   <name>_levels.png              a few levels side by side, rendered off-screen
// and prints a table: level, triangles, the producer's own error estimate, the error measured
// against level 0 (symmetric Hausdorff and RMS surface distance, all in % of the bounding-box
// diagonal), and where the level is in the time series.
#include "MeshLODHierarchy.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestMeshes.h"
#include "vtkLODGeomorph.h"
#include "vtkTriangleCollapseDecimation.h"
#include "vtkVertexClusterOctree.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCoordinate.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPNGWriter.h"
#include "vtkPolyDataReader.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkTriangleFilter.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLMultiBlockDataWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#ifdef MESHLOD_DEMO_HAS_GLX
#include <GL/glx.h>
#include <X11/Xlib.h>
#endif

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

vtkPolyData* Level(vtkMultiBlockDataSet* levels, unsigned int i)
{
  return vtkPolyData::SafeDownCast(levels->GetBlock(i));
}

//==================================================================================================
// HIERARCHY PRODUCERS. Each makes the levels of detail of the isosurface in the layout of
// MeshLODHierarchy.h (vtkLODGeomorph needs its morph arrays). To show another method, write a
// function like ProduceTriangleCollapse() and add one line to HierarchyProducers().
//==================================================================================================
struct HierarchyProducer
{
  std::string Name;        // file names: <Name>.vtm, <Name>_frames.pvd, <Name>_levels.png
  std::string Description; // printed above the table
  std::function<vtkSmartPointer<vtkMultiBlockDataSet>(vtkPolyData* surface)> Produce;
};

vtkSmartPointer<vtkMultiBlockDataSet> ProduceTriangleCollapse(vtkPolyData* surface)
{
  vtkNew<vtkTriangleCollapseDecimation> decimate;
  decimate->SetInputData(surface);
  decimate->Update();
  return decimate->GetHierarchy();
}

vtkSmartPointer<vtkMultiBlockDataSet> ProduceVertexClusterOctree(vtkPolyData* surface)
{
  // The same level sizes as the triangle collapse's defaults: 56%, 32%, ..., 1% of the input's
  // triangles (the surface is all triangles: see main), each count at least 4 (a tetrahedron)
  // and below the one before; a surface too small for any keeps its own count, in one level.
  const vtkIdType triangles = surface->GetNumberOfPolys();
  vtkNew<vtkVertexClusterOctree> cluster;
  cluster->SetInputData(surface);
  cluster->SetLevelModeToTargetTriangleCounts();
  vtkIdType last = triangles;
  for (int k = 1; k <= 8; ++k)
  {
    const vtkIdType count = std::max<vtkIdType>(
      4, static_cast<vtkIdType>(static_cast<double>(triangles) * std::pow(0.01, k / 8.0)));
    if (count < last)
    {
      cluster->AddTargetTriangleCount(count);
      last = count;
    }
  }
  if (last == triangles)
  {
    cluster->AddTargetTriangleCount(triangles);
  }
  cluster->Update();
  return cluster->GetHierarchy();
}

std::vector<HierarchyProducer> HierarchyProducers()
{
  return {
    { "triangle_collapse",
      "vtkTriangleCollapseDecimation (defaults: quadric method, greedy schedule, triangle and "
      "edge collapses, 8 levels down to 1%)",
      ProduceTriangleCollapse },
    { "vertex_cluster_octree",
      "vtkVertexClusterOctree (adaptive octree clustering, levels at about the same triangle "
      "counts)",
      ProduceVertexClusterOctree },
  };
}

//--------------------------------------------------------------------------------------------------
/// A field-data value of a level, or a negative number when the level does not have it.
double LevelField(vtkPolyData* level, const char* name)
{
  vtkDataArray* array = level->GetFieldData()->GetArray(name);
  return array != nullptr && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : -1.0;
}

/// The frames of the time series: framesPerTransition per level transition, then the
/// coarsest level. Frame k * framesPerTransition is level k, at time k with vtkLODGeomorph's
/// default TimeScale (1).
std::vector<double> FrameTimes(const std::vector<double>& levelTimes, int framesPerTransition)
{
  std::vector<double> times;
  for (size_t i = 0; i + 1 < levelTimes.size(); ++i)
  {
    for (int k = 0; k < framesPerTransition; ++k)
    {
      times.push_back(
        levelTimes[i] + (levelTimes[i + 1] - levelTimes[i]) * k / framesPerTransition);
    }
  }
  if (!levelTimes.empty())
  {
    times.push_back(levelTimes.back());
  }
  return times;
}

void PrintTable(const HierarchyProducer& producer, vtkMultiBlockDataSet* levels, double seconds,
  int framesPerTransition)
{
  vtkPolyData* finest = Level(levels, 0);
  const double diagonal = finest->GetLength();
  // Fewer samples than the yardstick's default (100k per surface): enough for a table a user
  // reads, and far quicker than the filters' ComputeLevelError. The benchmark uses the default.
  meshlod::SurfaceDistanceOptions yardstick;
  yardstick.SamplesPerSurface = 20000;
  yardstick.MaximumVertexSamples = 20000;
  const Clock::time_point start = Clock::now();
  std::cout << "\nLevels of detail: " << producer.Description << "\n";
  std::printf("All %u levels made in %.3f s.\n", levels->GetNumberOfBlocks(), seconds);
  std::cout
    << "Errors in % of the bounding-box diagonal: estimated = the producer's own EstimatedError;\n"
       "Hausdorff and RMS = symmetric surface distance to level 0, measured here.\n"
       "time = the level's time in "
    << producer.Name << "_frames.pvd (its frame in " << producer.Name << "_frames/).\n\n"
    << "| level | triangles | estimated % | Hausdorff % |   RMS %  | time |     frame     |\n"
    << "|------:|----------:|------------:|------------:|---------:|-----:|--------------:|\n";
  for (unsigned int i = 0; i < levels->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(levels, i);
    meshlod::SurfaceDistance distance;
    if (i > 0)
    {
      distance = meshlod::MeasureSurfaceDistance(finest, level, yardstick);
    }
    const double estimated = LevelField(level, meshlod::names::EstimatedError);
    char estimatedText[32] = "-";
    if (estimated >= 0.0 && diagonal > 0.0)
    {
      std::snprintf(estimatedText, sizeof(estimatedText), "%.4f", 100.0 * estimated / diagonal);
    }
    char row[160];
    std::snprintf(row, sizeof(row),
      "| %5u | %9lld | %11s | %11.4f | %8.5f | %4u | frame_%03u.vtp |\n", i,
      static_cast<long long>(level->GetNumberOfPolys()), estimatedText, distance.HausdorffPercent(),
      distance.RmsPercent(), i, i * framesPerTransition);
    std::cout << row;
  }
  std::printf("\nErrors measured in %.3f s\n", SecondsSince(start));
  std::cout.flush();
}

//--------------------------------------------------------------------------------------------------
/// vtkXMLWriter::Write returns 1 even where it could not write the file; its error code tells.
bool WriteSucceeded(vtkXMLWriter* writer)
{
  return writer->Write() == 1 && writer->GetErrorCode() == vtkErrorCode::NoError;
}

bool WriteHierarchy(vtkMultiBlockDataSet* levels, const fs::path& path)
{
  vtkNew<vtkXMLMultiBlockDataWriter> writer;
  writer->SetInputData(levels);
  writer->SetFileName(path.string().c_str());
  // Connectivity and MorphTargetId as 32-bit integers (enough below 2^31 points): smaller
  // files, and vtkLODGeomorph reads such a hierarchy back as it is. zlib's fastest level:
  // files about as small as the default level's, in half the time.
  writer->SetIdTypeToInt32();
  writer->SetCompressionLevel(1);
  // The writer puts the levels into <name>/ beside <name>.vtm and says nothing through its
  // error code when it cannot (a file of that name, say): the folder is made here first.
  std::error_code error;
  fs::create_directories(path.parent_path() / path.stem(), error);
  return !error && WriteSucceeded(writer);
}

/// Removes <folder>/frame_*.vtp: frames left over from an earlier, longer run would confuse a
/// user browsing the folder.
void RemoveOldFrames(const fs::path& folder)
{
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
  {
    const std::string name = entry.path().filename().string();
    if (name.rfind("frame_", 0) == 0 && entry.path().extension() == ".vtp")
    {
      fs::remove(entry.path());
    }
  }
}

/// The geomorph time series: vtkLODGeomorph publishes one time step per level; each frame is
/// an update at a requested time (UPDATE_TIME_STEP), as in a ParaView animation, written by a
/// writer connected to the geomorph (its update keeps the requested time). Writes
/// <name>_frames/frame_NNN.vtp and <name>_frames.pvd, a ParaView collection listing them with
/// their times. Returns the number of frames, or -1 when a file cannot be written.
int WriteGeomorphFrames(vtkMultiBlockDataSet* levels, const fs::path& directory,
  const std::string& name, int framesPerTransition)
{
  vtkNew<vtkLODGeomorph> geomorph;
  geomorph->SetInputData(levels);
  geomorph->UpdateInformation();
  vtkInformation* info = geomorph->GetOutputInformation(0);
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!info->Has(SDDP::TIME_STEPS()))
  {
    return -1; // not a hierarchy vtkLODGeomorph accepts (it said why)
  }
  const double* steps = info->Get(SDDP::TIME_STEPS());
  const std::vector<double> levelTimes(steps, steps + info->Length(SDDP::TIME_STEPS()));

  const fs::path folder = directory / (name + "_frames");
  std::error_code error;
  fs::create_directories(folder, error);
  if (error)
  {
    return -1;
  }
  RemoveOldFrames(folder);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(geomorph->GetOutputPort());
  writer->SetIdTypeToInt32();
  writer->SetCompressionLevel(1);

  std::ofstream pvd(directory / (name + "_frames.pvd"));
  pvd.precision(12);
  pvd << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  const std::vector<double> times = FrameTimes(levelTimes, framesPerTransition);
  for (size_t k = 0; k < times.size(); ++k)
  {
    char file[32];
    std::snprintf(file, sizeof(file), "frame_%03zu.vtp", k);
    geomorph->UpdateTimeStep(times[k]);
    writer->SetFileName((folder / file).string().c_str());
    if (!WriteSucceeded(writer))
    {
      return -1;
    }
    pvd << "    <DataSet timestep=\"" << times[k] << "\" group=\"\" part=\"0\" file=\"" << name
        << "_frames/" << file << "\"/>\n";
  }
  pvd << "  </Collection>\n</VTKFile>\n";
  return pvd ? static_cast<int>(times.size()) : -1;
}

//--------------------------------------------------------------------------------------------------
/// The X display the picture is rendered on. Debian's VTK renders through X only, and aborts
/// the program when it cannot open the display or find an OpenGL configuration there: check
/// both first, so that the picture is skipped instead. The connection stays open and is handed
/// to the render window: an X server resets when its last client disconnects, and a connection
/// opened during that reset fails.
class XDisplay
{
public:
  XDisplay() = default;
  XDisplay(const XDisplay&) = delete;
  XDisplay& operator=(const XDisplay&) = delete;
  ~XDisplay()
  {
#ifdef MESHLOD_DEMO_HAS_GLX
    if (this->Connection != nullptr)
    {
      XCloseDisplay(this->Connection);
    }
#endif
  }

  /// Opens the display; false (and why) when rendering is impossible.
  bool Open(std::string& why)
  {
    const char* name = std::getenv("DISPLAY");
    if (name == nullptr || *name == '\0')
    {
      why = "DISPLAY is not set (run the demo through xvfb-run -a, as run-demo.sh does)";
      return false;
    }
#ifdef MESHLOD_DEMO_HAS_GLX
    this->Connection = XOpenDisplay(nullptr);
    if (this->Connection == nullptr)
    {
      why = std::string("cannot open the X display ") + name;
      return false;
    }
    int errorBase = 0, eventBase = 0, configurations = 0;
    if (glXQueryExtension(this->Connection, &errorBase, &eventBase))
    {
      const int wanted[] = { GLX_RENDER_TYPE,
        GLX_RGBA_BIT,
        GLX_DRAWABLE_TYPE,
        GLX_WINDOW_BIT,
        GLX_RED_SIZE,
        1,
        GLX_GREEN_SIZE,
        1,
        GLX_BLUE_SIZE,
        1,
        GLX_DEPTH_SIZE,
        1,
        None };
      GLXFBConfig* found = glXChooseFBConfig(
        this->Connection, DefaultScreen(this->Connection), wanted, &configurations);
      if (found != nullptr)
      {
        XFree(found);
      }
    }
    if (configurations == 0)
    {
      why = std::string("the X display ") + name + " offers no OpenGL (GLX) configuration";
      return false;
    }
#endif
    return true;
  }

  /// For vtkRenderWindow::SetDisplayId (null: let VTK open the display itself).
  void* Get() const
  {
    return this->Connection;
  }

private:
#ifdef MESHLOD_DEMO_HAS_GLX
  Display* Connection = nullptr;
#else
  void* Connection = nullptr;
#endif
};

/// The meshes side by side, one viewport each, same camera, with a label under each.
bool RenderStrip(const std::vector<vtkPolyData*>& meshes,
  const std::vector<std::string>& labels,
  const fs::path& path,
  std::string& why)
{
  XDisplay display; // declared first: closed after the window is gone
  if (!display.Open(why))
  {
    return false;
  }
  const int tile = 400;
  vtkNew<vtkRenderWindow> window;
  if (display.Get() != nullptr)
  {
    window->SetDisplayId(display.Get());
  }
  window->SetOffScreenRendering(1);
  window->SetSize(tile * static_cast<int>(meshes.size()), tile);
  if (!window->SupportsOpenGL())
  {
    why = "the X display offers no usable OpenGL (Mesa's libgl1-mesa-dri missing?)";
    return false;
  }

  vtkNew<vtkCamera> camera;
  for (size_t i = 0; i < meshes.size(); ++i)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(meshes[i]);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.93, 0.78, 0.55);
    // Wire edges only where they can be told apart at this picture size.
    if (meshes[i]->GetNumberOfPolys() < 30000)
    {
      actor->GetProperty()->EdgeVisibilityOn();
      actor->GetProperty()->SetEdgeColor(0.25, 0.2, 0.15);
    }

    vtkNew<vtkTextActor> label;
    label->SetInput(labels[i].c_str());
    label->GetTextProperty()->SetFontSize(18);
    label->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
    label->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    label->GetPositionCoordinate()->SetValue(0.03, 0.03);

    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(
      static_cast<double>(i) / meshes.size(), 0.0, static_cast<double>(i + 1) / meshes.size(), 1.0);
    renderer->SetBackground(1.0, 1.0, 1.0);
    renderer->AddActor(actor);
    renderer->AddActor2D(label);
    renderer->SetActiveCamera(camera);
    window->AddRenderer(renderer);
    if (i == 0)
    {
      camera->Elevation(25.0);
      camera->Azimuth(30.0);
      renderer->ResetCamera();
      camera->Zoom(1.05);
    }
  }
  window->Render();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> png;
  png->SetInputConnection(grab->GetOutputPort());
  png->SetFileName(path.string().c_str());
  png->Write();
  if (png->GetErrorCode() != 0)
  {
    why = "cannot write " + path.string();
    return false;
  }
  return true;
}

/// The finest level and up to three coarser ones spread over the hierarchy.
std::vector<unsigned int> PickLevelsToShow(unsigned int count)
{
  std::vector<unsigned int> picked;
  const unsigned int shown = std::min(4u, count);
  for (unsigned int k = 0; k < shown; ++k)
  {
    const unsigned int level = shown == 1 ? 0 : k * (count - 1) / (shown - 1);
    if (picked.empty() || picked.back() != level)
    {
      picked.push_back(level);
    }
  }
  return picked;
}

//--------------------------------------------------------------------------------------------------
struct Options
{
  fs::path Output = "demo-output";
  meshlod::testing::Field Field = meshlod::testing::Field::Metaballs;
  int Resolution = 0; // 0: about DefaultTriangles
  bool FieldGiven = false;
  fs::path Input;     // empty: the isosurface of Field
  int FramesPerTransition = 8;
  bool Render = true;
};

constexpr double DefaultTriangles = 200000.0;

bool ParseArguments(int argc, char* argv[], Options& options)
{
  bool haveOutput = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--field" && i + 1 < argc)
    {
      if (!meshlod::testing::FieldFromName(argv[++i], options.Field))
      {
        std::cerr << "unknown field " << argv[i] << "\n";
        return false;
      }
      options.FieldGiven = true;
    }
    else if (arg == "--input" && i + 1 < argc)
    {
      options.Input = argv[++i];
    }
    else if (arg == "--resolution" && i + 1 < argc)
    {
      options.Resolution = std::atoi(argv[++i]);
      if (options.Resolution < 8 || options.Resolution > 2000)
      {
        std::cerr << "--resolution must be between 8 and 2000\n";
        return false;
      }
      options.FieldGiven = true;
    }
    else if (arg == "--frames" && i + 1 < argc)
    {
      options.FramesPerTransition = std::atoi(argv[++i]);
      if (options.FramesPerTransition < 1 || options.FramesPerTransition > 100)
      {
        std::cerr << "--frames must be between 1 and 100\n";
        return false;
      }
    }
    else if (arg == "--no-render")
    {
      options.Render = false;
    }
    else if (!arg.empty() && arg[0] != '-' && !haveOutput)
    {
      options.Output = arg;
      haveOutput = true;
    }
    else
    {
      return false;
    }
  }
  if (!options.Input.empty() && options.FieldGiven)
  {
    std::cerr << "--input replaces the isosurface that --field and --resolution make: give one "
                 "or the other\n";
    return false;
  }
  return true;
}

/// A reader of class `Reader` for `file`.
template <typename Reader>
vtkSmartPointer<vtkAlgorithm> NewReader(const fs::path& file)
{
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(file.string().c_str());
  return reader;
}

/// The surface in `file`, read by the reader its extension names (.vtp, .vtk, .stl, .ply, .obj),
/// or null with the reason in `why`.
vtkSmartPointer<vtkPolyData> ReadSurface(const fs::path& file, std::string& why)
{
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // (vtkSTLReader merges the copies of each corner.)
  const vtkSmartPointer<vtkAlgorithm> reader =
    extension == ".vtp"   ? NewReader<vtkXMLPolyDataReader>(file)
    : extension == ".vtk" ? NewReader<vtkPolyDataReader>(file)
    : extension == ".stl" ? NewReader<vtkSTLReader>(file)
    : extension == ".ply" ? NewReader<vtkPLYReader>(file)
    : extension == ".obj" ? NewReader<vtkOBJReader>(file)
                          : nullptr;
  if (reader == nullptr)
  {
    why = "not a file type the demo reads (.vtp, .vtk, .stl, .ply or .obj)";
    return nullptr;
  }
  std::error_code error;
  if (!fs::is_regular_file(file, error))
  {
    why = "no such file";
    return nullptr;
  }
  reader->Update();
  vtkPolyData* surface = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (reader->GetErrorCode() != vtkErrorCode::NoError || surface == nullptr ||
    surface->GetNumberOfPolys() + surface->GetNumberOfStrips() == 0)
  {
    why = "no polygons read from it";
    return nullptr;
  }
  return surface;
}

/// One producer: its hierarchy, table, files and picture. False when a file cannot be written.
bool Demonstrate(const HierarchyProducer& producer, vtkPolyData* surface, const Options& options)
{
  Clock::time_point start = Clock::now();
  vtkSmartPointer<vtkMultiBlockDataSet> levels = producer.Produce(surface);
  const double seconds = SecondsSince(start);
  if (levels == nullptr || levels->GetNumberOfBlocks() == 0)
  {
    std::cerr << producer.Name << ": no levels\n";
    return false;
  }
  PrintTable(producer, levels, seconds, options.FramesPerTransition);

  // Files for ParaView.
  start = Clock::now();
  const fs::path vtm = options.Output / (producer.Name + ".vtm");
  if (!WriteHierarchy(levels, vtm))
  {
    std::cerr << "cannot write " << vtm.string() << "\n";
    return false;
  }
  const int frames =
    WriteGeomorphFrames(levels, options.Output, producer.Name, options.FramesPerTransition);
  if (frames < 0)
  {
    std::cerr << "cannot write the frames of " << producer.Name << " into " << options.Output
              << "\n";
    return false;
  }
  std::printf("\nWrote %s (+ %s/) and %s (+ %d frames in %s_frames/) in %.3f s\n",
    vtm.string().c_str(), producer.Name.c_str(),
    (options.Output / (producer.Name + "_frames.pvd")).string().c_str(), frames,
    producer.Name.c_str(), SecondsSince(start));

  // A picture of a few levels.
  if (!options.Render)
  {
    std::cout << "No picture (--no-render).\n";
    return true;
  }
  std::vector<vtkPolyData*> meshes;
  std::vector<std::string> labels;
  for (unsigned int level : PickLevelsToShow(levels->GetNumberOfBlocks()))
  {
    meshes.push_back(Level(levels, level));
    labels.push_back("Level " + std::to_string(level) + ": " +
      std::to_string(meshes.back()->GetNumberOfPolys()) + " triangles");
  }
  std::string why;
  const fs::path png = options.Output / (producer.Name + "_levels.png");
  if (RenderStrip(meshes, labels, png, why))
  {
    std::cout << "Wrote " << png.string() << "\n";
  }
  else
  {
    std::cout << "No picture: " << why << ". Everything else is written.\n";
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!ParseArguments(argc, argv, options))
  {
    std::cerr << "usage: " << argv[0]
              << " [output-directory] [--field metaballs|gyroid|torus|sphere|wavelet]"
                 " [--resolution N] [--input FILE.vtp|.vtk|.stl|.ply|.obj] [--frames N]"
                 " [--no-render]\n";
    return 2;
  }
  std::error_code error;
  fs::create_directories(options.Output, error);
  if (error)
  {
    std::cerr << "cannot create " << options.Output << ": " << error.message() << "\n";
    return 1;
  }

  // The input: the user's surface, or marching cubes (flying edges) on a sampled analytic field.
  const Clock::time_point start = Clock::now();
  vtkSmartPointer<vtkPolyData> surface;
  if (!options.Input.empty())
  {
    std::string why;
    surface = ReadSurface(options.Input, why);
    if (surface == nullptr)
    {
      std::cerr << "cannot read " << options.Input.string() << ": " << why << "\n";
      return 1;
    }
    const long long polygons = surface->GetNumberOfPolys();
    const long long strips = surface->GetNumberOfStrips();
    if (strips > 0 || surface->GetPolys()->IsHomogeneous() != 3)
    {
      // Polygons and strips as triangles here (the filters would do it themselves), so that
      // the octree's level counts and the tables count triangles.
      vtkNew<vtkTriangleFilter> triangulate;
      triangulate->SetInputData(surface);
      triangulate->PassVertsOff();
      triangulate->PassLinesOff();
      triangulate->Update();
      surface = triangulate->GetOutput();
    }
    std::printf("Read %s: %lld polygons and %lld strips, %lld triangles, %lld points, %.3f s\n",
      options.Input.string().c_str(), polygons, strips,
      static_cast<long long>(surface->GetNumberOfPolys()),
      static_cast<long long>(surface->GetNumberOfPoints()), SecondsSince(start));
  }
  else
  {
    const int resolution = options.Resolution > 0
      ? options.Resolution
      : meshlod::testing::ResolutionForTriangles(options.Field, DefaultTriangles);
    surface = meshlod::testing::MakeIsosurface(options.Field, resolution, /*computeNormals=*/false);
    std::printf("Isosurface of %s on a %d^3 volume: %lld triangles, %lld points, %.3f s\n",
      meshlod::testing::FieldName(options.Field), resolution,
      static_cast<long long>(surface->GetNumberOfPolys()),
      static_cast<long long>(surface->GetNumberOfPoints()), SecondsSince(start));
  }

  for (const HierarchyProducer& producer : HierarchyProducers())
  {
    if (!Demonstrate(producer, surface, options))
    {
      return 1;
    }
  }
  return 0;
}
