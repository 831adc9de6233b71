// MeshLOD demo: a marching-cubes isosurface turned into levels of detail, with everything written
// for ParaView and a picture of a few levels.
//
//   MeshLODDemo [output-directory] [--field NAME] [--resolution N] [--no-render]
//
// output-directory  default demo-output; created if needed
// --field           metaballs (default), gyroid, torus, sphere or wavelet
// --resolution      samples per axis of the volume (default: about 200k triangles)
// --no-render       skip the picture (it needs an X display; run-demo.sh provides one with Xvfb)
//
// It writes into the output directory
//   hierarchy.vtm + hierarchy/        the levels of detail, block i = "Level i"; level 0 is the
//                                     input (flying edges at 0 of the field)
//   frames.pvd + frames/frame_NNN.vtp a time series from the finest to the coarsest level
//   levels.png                        a few levels side by side, rendered off-screen
// and prints a table: level, triangles, error to level 0 (symmetric Hausdorff and RMS surface
// distance in % of the bounding-box diagonal) and time.
//
// The two places that make levels and frames are ProduceHierarchy() and ProduceFrames() below.
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestMeshes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCoordinate.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkQuadricDecimation.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLMultiBlockDataWriter.h"
#include "vtkXMLPolyDataWriter.h"

#ifdef MESHLOD_DEMO_HAS_GLX
#include <GL/glx.h>
#include <X11/Xlib.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
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

/// The levels of detail and how they were made.
struct Hierarchy
{
  vtkSmartPointer<vtkMultiBlockDataSet> Levels; // block i = level i, level 0 the input
  std::string Method;                           // printed above the table
  std::vector<double> LevelSeconds; // time spent on each level, if the producer knows it
  double TotalSeconds = 0.0;
};

/// One step of the time series.
struct Frame
{
  double Time = 0.0; // continuous level: 0 = finest, 1.5 = halfway from level 1 to level 2
  vtkSmartPointer<vtkPolyData> Mesh;
};

vtkPolyData* Level(vtkMultiBlockDataSet* levels, unsigned int i)
{
  return vtkPolyData::SafeDownCast(levels->GetBlock(i));
}

//==================================================================================================
// HIERARCHY PRODUCER. Placeholder until vtkTriangleCollapseDecimation lands: VTK's own
// vtkQuadricDecimation applied level after level (each level decimates the one before it), with
// the blocks named and numbered like MeshLOD's hierarchy output. The real filter makes the whole
// hierarchy in one Update() and adds the morph arrays vtkLODGeomorph needs.
//==================================================================================================
Hierarchy ProduceHierarchy(vtkPolyData* surface)
{
  // Fractions of the input's triangles kept by levels 1, 2, ...
  const double keep[] = { 0.3, 0.1, 0.03, 0.01, 0.003 };

  Hierarchy result;
  result.Method = "vtkQuadricDecimation level after level "
                  "(placeholder until vtkTriangleCollapseDecimation lands)";
  result.Levels = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  result.Levels->SetBlock(0, surface);
  result.LevelSeconds.push_back(0.0);

  const double inputTriangles = static_cast<double>(surface->GetNumberOfPolys());
  vtkSmartPointer<vtkPolyData> previous = surface;
  for (double fraction : keep)
  {
    const double target = fraction * inputTriangles;
    const double have = static_cast<double>(previous->GetNumberOfPolys());
    if (target < 4.0 || target >= have)
    {
      break;
    }
    const Clock::time_point start = Clock::now();
    vtkNew<vtkQuadricDecimation> decimate;
    decimate->SetInputData(previous);
    decimate->SetTargetReduction(1.0 - target / have);
    decimate->Update();
    auto level = vtkSmartPointer<vtkPolyData>::New();
    level->ShallowCopy(decimate->GetOutput());
    result.LevelSeconds.push_back(SecondsSince(start));
    result.TotalSeconds += result.LevelSeconds.back();
    result.Levels->SetBlock(result.Levels->GetNumberOfBlocks(), level);
    previous = level;
  }

  // Name and number the levels the way MeshLOD's hierarchy output does.
  for (unsigned int i = 0; i < result.Levels->GetNumberOfBlocks(); ++i)
  {
    auto level = vtkSmartPointer<vtkPolyData>::New();
    level->ShallowCopy(Level(result.Levels, i)); // do not add field data to the caller's input
    vtkNew<vtkIntArray> index;
    index->SetName("LevelIndex");
    index->InsertNextValue(static_cast<int>(i));
    vtkNew<vtkIdTypeArray> triangles;
    triangles->SetName("NumberOfTriangles");
    triangles->InsertNextValue(level->GetNumberOfPolys());
    vtkNew<vtkFieldData> fieldData;
    fieldData->AddArray(index);
    fieldData->AddArray(triangles);
    level->SetFieldData(fieldData);
    result.Levels->SetBlock(i, level);
    result.Levels->GetMetaData(i)->Set(
      vtkCompositeDataSet::NAME(), ("Level " + std::to_string(i)).c_str());
  }
  return result;
}

//==================================================================================================
// FRAME PRODUCER. Placeholder until vtkLODGeomorph lands: one frame per level at whole times
// (0, 1, 2, ...), no blending in between. With the geomorph, the frames will include the
// in-between meshes (e.g. eight per transition) so that the series plays as a smooth morph.
//==================================================================================================
std::vector<Frame> ProduceFrames(vtkMultiBlockDataSet* levels)
{
  std::vector<Frame> frames;
  for (unsigned int i = 0; i < levels->GetNumberOfBlocks(); ++i)
  {
    frames.push_back(Frame{ static_cast<double>(i), Level(levels, i) });
  }
  return frames;
}

//--------------------------------------------------------------------------------------------------
void PrintTable(const Hierarchy& hierarchy)
{
  vtkPolyData* finest = Level(hierarchy.Levels, 0);
  // Fewer samples than the yardstick's default (100k per surface): enough for a table a user
  // reads, and it keeps the demo quick. The benchmark uses the default.
  meshlod::SurfaceDistanceOptions yardstick;
  yardstick.SamplesPerSurface = 20000;
  yardstick.MaximumVertexSamples = 20000;
  std::cout << "\nLevels of detail: " << hierarchy.Method << "\n"
            << "Error: surface distance to level 0 in % of the bounding-box diagonal.\n\n"
            << "| level | triangles | Hausdorff % |   RMS %  | time (s) |\n"
            << "|------:|----------:|------------:|---------:|---------:|\n";
  for (unsigned int i = 0; i < hierarchy.Levels->GetNumberOfBlocks(); ++i)
  {
    vtkPolyData* level = Level(hierarchy.Levels, i);
    meshlod::SurfaceDistance distance;
    if (i > 0)
    {
      distance = meshlod::MeasureSurfaceDistance(finest, level, yardstick);
    }
    char time[32] = "-";
    if (i < hierarchy.LevelSeconds.size())
    {
      std::snprintf(time, sizeof(time), "%.3f", hierarchy.LevelSeconds[i]);
    }
    char row[160];
    std::snprintf(row,
      sizeof(row),
      "| %5u | %9lld | %11.4f | %8.5f | %8s |\n",
      i,
      static_cast<long long>(level->GetNumberOfPolys()),
      distance.HausdorffPercent(),
      distance.RmsPercent(),
      time);
    std::cout << row;
  }
  std::printf("\nAll levels: %.3f s\n", hierarchy.TotalSeconds);
  std::cout.flush();
}

//--------------------------------------------------------------------------------------------------
bool WritePolyData(vtkPolyData* mesh, const fs::path& path)
{
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(mesh);
  writer->SetFileName(path.string().c_str());
  return writer->Write() == 1;
}

bool WriteHierarchy(vtkMultiBlockDataSet* levels, const fs::path& path)
{
  vtkNew<vtkXMLMultiBlockDataWriter> writer;
  writer->SetInputData(levels);
  writer->SetFileName(path.string().c_str());
  return writer->Write() == 1;
}

/// frames/frame_NNN.vtp and a ParaView collection file (.pvd) listing them as a time series.
bool WriteFrames(const std::vector<Frame>& frames, const fs::path& directory)
{
  const fs::path folder = directory / "frames";
  fs::create_directories(folder);
  // Frames left over from an earlier, longer run would confuse a user browsing the folder.
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
  {
    const std::string name = entry.path().filename().string();
    if (name.rfind("frame_", 0) == 0 && entry.path().extension() == ".vtp")
    {
      fs::remove(entry.path());
    }
  }

  std::ofstream pvd(directory / "frames.pvd");
  pvd << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (size_t i = 0; i < frames.size(); ++i)
  {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%03zu.vtp", i);
    if (!WritePolyData(frames[i].Mesh, folder / name))
    {
      return false;
    }
    pvd << "    <DataSet timestep=\"" << frames[i].Time << "\" group=\"\" part=\"0\" file=\"frames/"
        << name << "\"/>\n";
  }
  pvd << "  </Collection>\n</VTKFile>\n";
  return static_cast<bool>(pvd);
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
    }
    else if (arg == "--resolution" && i + 1 < argc)
    {
      options.Resolution = std::atoi(argv[++i]);
      if (options.Resolution < 8 || options.Resolution > 2000)
      {
        std::cerr << "--resolution must be between 8 and 2000\n";
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
                 " [--resolution N] [--no-render]\n";
    return 2;
  }
  std::error_code error;
  fs::create_directories(options.Output, error);
  if (error)
  {
    std::cerr << "cannot create " << options.Output << ": " << error.message() << "\n";
    return 1;
  }

  // 1. The input: marching cubes (flying edges) on a sampled analytic field.
  const int resolution = options.Resolution > 0
    ? options.Resolution
    : meshlod::testing::ResolutionForTriangles(options.Field, DefaultTriangles);
  Clock::time_point start = Clock::now();
  vtkSmartPointer<vtkPolyData> surface =
    meshlod::testing::MakeIsosurface(options.Field, resolution, /*computeNormals=*/false);
  std::printf("Isosurface of %s on a %d^3 volume: %lld triangles, %lld points, %.3f s\n",
    meshlod::testing::FieldName(options.Field),
    resolution,
    static_cast<long long>(surface->GetNumberOfPolys()),
    static_cast<long long>(surface->GetNumberOfPoints()),
    SecondsSince(start));

  // 2. Levels of detail, and the table.
  const Hierarchy hierarchy = ProduceHierarchy(surface);
  start = Clock::now();
  PrintTable(hierarchy);
  std::printf("Errors measured in %.3f s\n", SecondsSince(start));
  start = Clock::now();

  // 3. Files for ParaView.
  bool written = WriteHierarchy(hierarchy.Levels, options.Output / "hierarchy.vtm");
  const std::vector<Frame> frames = ProduceFrames(hierarchy.Levels);
  written = written && WriteFrames(frames, options.Output);
  if (!written)
  {
    std::cerr << "cannot write into " << options.Output << "\n";
    return 1;
  }
  std::printf("\nWrote %s (+ hierarchy/) and %s (+ %zu frames in frames/) in %.3f s\n",
    (options.Output / "hierarchy.vtm").string().c_str(),
    (options.Output / "frames.pvd").string().c_str(),
    frames.size(),
    SecondsSince(start));

  // 4. A picture of a few levels.
  if (options.Render)
  {
    std::vector<vtkPolyData*> meshes;
    std::vector<std::string> labels;
    for (unsigned int level : PickLevelsToShow(hierarchy.Levels->GetNumberOfBlocks()))
    {
      meshes.push_back(Level(hierarchy.Levels, level));
      labels.push_back("Level " + std::to_string(level) + ": " +
        std::to_string(meshes.back()->GetNumberOfPolys()) + " triangles");
    }
    std::string why;
    const fs::path png = options.Output / "levels.png";
    if (RenderStrip(meshes, labels, png, why))
    {
      std::cout << "Wrote " << png.string() << "\n";
    }
    else
    {
      std::cout << "No picture: " << why << ". Everything else is written.\n";
    }
  }
  else
  {
    std::cout << "No picture (--no-render).\n";
  }
  return 0;
}
