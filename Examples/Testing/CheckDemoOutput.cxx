// Reads back what MeshLODDemo wrote for one hierarchy producer and checks it, for the demo's
// tests:
//
//   CheckDemoOutput <output-directory> <producer-name> <levels> <frames-per-transition> [--picture]
//
// - <name>.vtm: <levels> blocks, each a vtkPolyData named "Level i", strictly fewer triangles
//   level after level, field data LevelIndex / NumberOfTriangles / EstimatedError, and the
//   morph arrays of every level but the last consistent with the next level (the layout of
//   MeshLODHierarchy.h survives the files);
// - <name>_frames.pvd: (levels - 1) * frames-per-transition + 1 frames at times k / frames, each
//   readable; a frame at time i + t has level i's triangles (the same connectivity) and its
//   points on the segments from level i's points to their MorphTarget (the fraction t of the
//   way); a frame at a whole time is that level exactly; LevelOfDetail field data = the time;
// - with --picture, <name>_levels.png: a strip of 400x400 tiles, one per level shown (up to 4),
//   not blank.
// Prints every failed check and exits non-zero when any failed.
#include "MeshLODHierarchy.h"
#include "MeshLODHierarchyChecks.h"
#include "MeshLODTestCheck.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLMultiBlockDataReader.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

namespace
{
using namespace meshlod;

vtkPolyData* Level(vtkMultiBlockDataSet* h, int i)
{
  return vtkPolyData::SafeDownCast(h->GetBlock(static_cast<unsigned int>(i)));
}

double Field(vtkPolyData* mesh, const char* name)
{
  vtkDataArray* a = mesh->GetFieldData()->GetArray(name);
  return a != nullptr && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : std::nan("");
}

bool SameTriangles(vtkPolyData* a, vtkPolyData* b)
{
  vtkDataArray* x = a->GetPolys()->GetConnectivityArray();
  vtkDataArray* y = b->GetPolys()->GetConnectivityArray();
  if (a->GetNumberOfPolys() != b->GetNumberOfPolys() ||
    x->GetNumberOfTuples() != y->GetNumberOfTuples())
  {
    return false;
  }
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    if (x->GetTuple1(i) != y->GetTuple1(i))
    {
      return false;
    }
  }
  return true;
}

vtkSmartPointer<vtkMultiBlockDataSet> CheckHierarchy(const std::string& path, int levels)
{
  vtkNew<vtkXMLMultiBlockDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  auto h = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  h->ShallowCopy(reader->GetOutput());
  MESHLOD_CHECK_EQ(static_cast<int>(h->GetNumberOfBlocks()), levels);
  if (static_cast<int>(h->GetNumberOfBlocks()) != levels)
  {
    return nullptr;
  }
  const std::string layout = CheckHierarchyLayout(h, true);
  if (!layout.empty())
  {
    std::cerr << path << ": " << layout << "\n";
    ++testing::FailureCount();
    return nullptr;
  }
  MESHLOD_CHECK_EQ(testing::CountCorrespondenceViolations(h), 0);
  for (int i = 0; i < levels; ++i)
  {
    vtkPolyData* level = Level(h, i);
    vtkInformation* metaData = h->GetMetaData(static_cast<unsigned int>(i));
    const char* name = metaData->Get(vtkCompositeDataSet::NAME());
    MESHLOD_CHECK_EQ(std::string(name ? name : ""), LevelBlockName(i));
    MESHLOD_CHECK_GT(level->GetNumberOfPolys(), 0);
    if (i > 0)
    {
      MESHLOD_CHECK_LT(level->GetNumberOfPolys(), Level(h, i - 1)->GetNumberOfPolys());
    }
    MESHLOD_CHECK_EQ(Field(level, names::LevelIndex), static_cast<double>(i));
    MESHLOD_CHECK_EQ(Field(level, names::NumberOfTriangles),
      static_cast<double>(level->GetNumberOfPolys()));
    MESHLOD_CHECK_GE(Field(level, names::EstimatedError), 0.0);
    const bool hasMorph = level->GetPointData()->GetArray(names::MorphTarget) != nullptr;
    MESHLOD_CHECK_EQ(hasMorph, i + 1 < levels);
  }
  return h;
}

struct FrameEntry
{
  double Time;
  std::string File;
};

std::vector<FrameEntry> ReadCollection(const std::string& path)
{
  std::vector<FrameEntry> frames;
  std::ifstream pvd(path);
  MESHLOD_CHECK(pvd.good());
  const std::regex dataset("<DataSet timestep=\"([^\"]+)\"[^>]* file=\"([^\"]+)\"");
  std::string line;
  while (std::getline(pvd, line))
  {
    std::smatch match;
    if (std::regex_search(line, match, dataset))
    {
      frames.push_back({ std::stod(match[1].str()), match[2].str() });
    }
  }
  return frames;
}

// A frame at time i + t: level i's connectivity, points the fraction t of the way to their
// MorphTarget (float points: one rounding), LevelOfDetail = the time.
void CheckFrame(vtkPolyData* frame, vtkMultiBlockDataSet* h, double time, const std::string& file)
{
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  const int i = std::min(static_cast<int>(std::floor(time)), n - 1);
  const double t = time - i;
  vtkPolyData* level = Level(h, i);
  int failures = testing::FailureCount();
  MESHLOD_CHECK_LE(std::abs(Field(frame, "LevelOfDetail") - time), 1e-9);
  MESHLOD_CHECK_EQ(frame->GetNumberOfPoints(), level->GetNumberOfPoints());
  MESHLOD_CHECK(SameTriangles(frame, level));
  if (t == 0.0)
  {
    MESHLOD_CHECK(testing::SameMesh(frame, level));
  }
  else if (frame->GetNumberOfPoints() == level->GetNumberOfPoints())
  {
    vtkDataArray* target = level->GetPointData()->GetArray(names::MorphTarget);
    int off = 0;
    for (vtkIdType p = 0; p < frame->GetNumberOfPoints(); ++p)
    {
      double x[3], a[3], b[3];
      frame->GetPoint(p, x);
      level->GetPoint(p, a);
      target->GetTuple(p, b);
      for (int c = 0; c < 3; ++c)
      {
        const double expected = (1.0 - t) * a[c] + t * b[c];
        off += std::abs(x[c] - expected) > 1e-6 * (1.0 + std::abs(expected));
      }
    }
    MESHLOD_CHECK_EQ(off, 0);
  }
  if (testing::FailureCount() != failures)
  {
    std::cerr << "  in " << file << " (time " << time << ")\n";
  }
}

void CheckFrames(
  const std::string& directory, const std::string& name, vtkMultiBlockDataSet* h, int perTransition)
{
  const int n = static_cast<int>(h->GetNumberOfBlocks());
  const std::vector<FrameEntry> frames = ReadCollection(directory + "/" + name + "_frames.pvd");
  MESHLOD_CHECK_EQ(static_cast<int>(frames.size()), (n - 1) * perTransition + 1);
  for (size_t k = 0; k < frames.size(); ++k)
  {
    const double expected = static_cast<double>(k) / perTransition;
    MESHLOD_CHECK_LE(std::abs(frames[k].Time - expected), 1e-5 * (1.0 + expected));
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName((directory + "/" + frames[k].File).c_str());
    reader->Update();
    vtkPolyData* frame = reader->GetOutput();
    MESHLOD_CHECK_GT(frame->GetNumberOfPolys(), 0);
    if (frame->GetNumberOfPolys() > 0)
    {
      CheckFrame(frame, h, expected, frames[k].File);
    }
  }
}

void CheckPicture(const std::string& path, int levels)
{
  vtkNew<vtkPNGReader> reader;
  MESHLOD_CHECK(reader->CanReadFile(path.c_str()));
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  MESHLOD_CHECK_EQ(dims[0], 400 * std::min(4, levels));
  MESHLOD_CHECK_EQ(dims[1], 400);
  // Not blank: a good share of the pixels are neither the white background nor one colour.
  vtkDataArray* pixels = image->GetPointData()->GetScalars();
  MESHLOD_CHECK(pixels != nullptr);
  if (pixels == nullptr)
  {
    return;
  }
  vtkIdType drawn = 0;
  double darkest = 255.0;
  for (vtkIdType p = 0; p < pixels->GetNumberOfTuples(); ++p)
  {
    const double red = pixels->GetComponent(p, 0);
    drawn += red < 250.0;
    darkest = std::min(darkest, red);
  }
  MESHLOD_CHECK_GT(drawn, pixels->GetNumberOfTuples() / 10);
  MESHLOD_CHECK_LT(darkest, 128.0);
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 5)
  {
    std::cerr << "usage: " << argv[0]
              << " <output-directory> <producer-name> <levels> <frames-per-transition>"
                 " [--picture]\n";
    return 2;
  }
  const std::string directory = argv[1];
  const std::string name = argv[2];
  const int levels = std::atoi(argv[3]);
  const int perTransition = std::atoi(argv[4]);
  const bool picture = argc > 5 && std::strcmp(argv[5], "--picture") == 0;

  vtkSmartPointer<vtkMultiBlockDataSet> h = CheckHierarchy(directory + "/" + name + ".vtm", levels);
  if (h != nullptr)
  {
    CheckFrames(directory, name, h, perTransition);
  }
  if (picture)
  {
    CheckPicture(directory + "/" + name + "_levels.png", levels);
  }
  if (testing::FailureCount() == 0)
  {
    std::cout << name << ": " << levels << " levels, "
              << (levels - 1) * perTransition + 1 << " frames checked\n";
  }
  return testing::Result();
}
