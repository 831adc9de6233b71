// Side-by-side benchmark of the registered decimation methods (BenchmarkMethods.h) on
// marching-cubes isosurfaces: time, throughput, peak memory growth and surface distance to the
// input, each compared with vtkQuadricDecimation. Writes a Markdown report.
//
//   MeshLODBenchmark [--meshes field:triangles,...] [--targets fraction,...] [--threads N]
//                    [--methods name,...] [--samples N] [--output FILE] [--command TEXT]
//                    [--fresh-memory 0|1]
//
// --meshes   isosurfaces to generate (default metaballs:150000,gyroid:600000,gyroid:2300000)
// --targets  output sizes as fractions of the input's triangles (default 0.1,0.01)
// --threads  thread count of the extra rows for methods that use vtkSMPTools (default 2; 0: none)
// --methods  only these methods (default: all registered)
// --samples  yardstick samples per surface (default 100000)
// --output   also write the report to this file
// --command  the command line to record in the report (default: this program's)
// --fresh-memory  measure each run's memory in a fresh process (default 1; 0: in this one)
//
// Memory is measured in a fresh process: the program starts itself again with --memory-probe 1,
// one mesh, one method and the targets of one timed job; that process makes the same mesh,
// prepares the method as here, runs the job once and prints its peak growth. In one long
// process the heap left by the methods before counts against the next: on the 2.3M-triangle
// gyroid, vtkTriangleCollapseDecimation grew by 199 B per triangle when it ran first and by 222
// after vtkQuadricDecimation and vtkDecimatePro (215 with glibc's mmap threshold held fixed).
//
// Single-thread rows run with vtkSMPTools' Sequential backend. Start the program with
// VTK_SMP_BACKEND_IN_USE=Sequential (run-benchmarks.sh does): with TBB, VTK 9.1 does not limit
// the threads of a scope. The untimed work (generating meshes, measuring distances) and the
// multi-thread rows switch to the parallel backend and back.
#include "BenchmarkArguments.h"
#include "BenchmarkMethods.h"
#include "BenchmarkTargets.h"
#include "MeshLODSurfaceDistance.h"
#include "MeshLODTestMeshes.h"

#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkVersion.h"

#include <malloc.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using meshlod::benchmark::Format;
using meshlod::benchmark::Method;
using Clock = std::chrono::steady_clock;
using Outputs = std::vector<vtkSmartPointer<vtkPolyData>>;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// CPU time of the calling thread. With the Sequential backend the whole method runs on it, so
/// unlike wall time this hardly changes when other programs compete for the cores.
double ThreadCpuSeconds()
{
  timespec now;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

std::vector<std::string> Split(const std::string& text, char separator)
{
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, separator))
  {
    if (!part.empty())
    {
      parts.push_back(part);
    }
  }
  return parts;
}

//------------------------------------------------------------------------------
// Memory: the growth of the resident set while a method runs, from the kernel's counters.

/// A field of /proc/self/status in kB (e.g. "VmRSS"), or -1.
long long StatusKilobytes(const std::string& field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.compare(0, field.size() + 1, field + ":") == 0)
    {
      return std::atoll(line.c_str() + field.size() + 1);
    }
  }
  return -1;
}

/// Gives freed memory back to the system and resets the peak (VmHWM) to the current resident
/// set. Returns false when the kernel refuses the reset.
bool ResetPeakMemory()
{
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.close();
  return !clear.fail();
}

//------------------------------------------------------------------------------
// SMP backends.

struct Backends
{
  std::string AtStart;  // what VTK_SMP_BACKEND_IN_USE (or the build default) selected
  std::string Parallel; // TBB, STDThread or OpenMP, whichever this VTK has ("" if none)
};

void UseBackend(const std::string& backend, int threads)
{
  vtkSMPTools::SetBackend(backend.c_str());
  vtkSMPTools::Initialize(threads);
}

Backends FindBackends()
{
  Backends backends;
  backends.AtStart = vtkSMPTools::GetBackend();
  for (const char* candidate : { "TBB", "STDThread", "OpenMP" })
  {
    if (vtkSMPTools::SetBackend(candidate))
    {
      backends.Parallel = candidate;
      break;
    }
  }
  return backends;
}

/// For untimed work: all cores.
void UseAllCores(const Backends& backends)
{
  UseBackend(backends.Parallel.empty() ? "Sequential" : backends.Parallel, 0);
}

/// For a timed run on `threads` threads: Sequential for one.
void UseTimedBackend(const Backends& backends, int threads)
{
  if (threads > 1)
  {
    UseBackend(backends.Parallel, threads);
  }
  else
  {
    UseBackend("Sequential", 1);
  }
}

//------------------------------------------------------------------------------
struct Options
{
  std::vector<std::pair<meshlod::testing::Field, double>> Meshes = {
    { meshlod::testing::Field::Metaballs, 150000.0 },
    { meshlod::testing::Field::Gyroid, 600000.0 },
    { meshlod::testing::Field::Gyroid, 2300000.0 },
  };
  std::vector<double> Targets = { 0.1, 0.01 };
  int Threads = 2;
  std::vector<std::string> Methods; // empty: all
  long long Samples = 100000;
  std::string Output;
  std::string Command;
  bool FreshMemory = true;
  bool MemoryProbe = false; // run as the fresh process of one memory measurement
};

bool ParseArguments(int argc, char* argv[], Options& options)
{
  options.Command = argv[0];
  for (int i = 1; i < argc; ++i)
  {
    options.Command += std::string(" ") + argv[i];
  }
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--meshes")
    {
      options.Meshes.clear();
      for (const std::string& item : Split(value, ','))
      {
        meshlod::testing::Field field;
        double triangles;
        if (!meshlod::benchmark::MeshArgument(item, field, triangles))
        {
          return false;
        }
        options.Meshes.emplace_back(field, triangles);
      }
    }
    else if (key == "--targets")
    {
      options.Targets.clear();
      for (const std::string& item : Split(value, ','))
      {
        const double fraction = std::atof(item.c_str());
        if (!(fraction > 0.0 && fraction < 1.0))
        {
          std::cerr << "targets are fractions between 0 and 1, got " << item << "\n";
          return false;
        }
        options.Targets.push_back(fraction);
      }
    }
    else if (key == "--threads")
    {
      options.Threads = std::max(0, std::atoi(value.c_str()));
    }
    else if (key == "--methods")
    {
      options.Methods = Split(value, ',');
    }
    else if (key == "--samples")
    {
      options.Samples = std::max(1000LL, std::atoll(value.c_str()));
    }
    else if (key == "--output")
    {
      options.Output = value;
    }
    else if (key == "--command")
    {
      options.Command = value;
    }
    else if (key == "--fresh-memory")
    {
      options.FreshMemory = std::atoi(value.c_str()) != 0;
    }
    else if (key == "--memory-probe")
    {
      options.MemoryProbe = std::atoi(value.c_str()) != 0;
    }
    else
    {
      return false;
    }
  }
  return argc % 2 == 1 && !options.Meshes.empty() && !options.Targets.empty();
}

//------------------------------------------------------------------------------
struct Mesh
{
  std::string Label;
  std::string Field;
  int Resolution = 0;
  double Seconds = 0.0;
  vtkIdType Dropped = 0; // degenerate triangles removed by the cleaning
  vtkSmartPointer<vtkPolyData> Data;
};

/// One timed run of a method: its outputs, time and memory.
struct Run
{
  Outputs Results;
  double Seconds = 0.0;
  double CpuSeconds = 0.0;  // CPU time of the calling thread
  long long PeakBytes = -1; // growth of the resident set during the run, -1 unknown
};

/// Times one call of `make` (wall and CPU time).
template <typename Make>
Run Time(Make&& make)
{
  Run run;
  const double cpu = ThreadCpuSeconds();
  const Clock::time_point start = Clock::now();
  run.Results = make();
  run.Seconds = SecondsSince(start);
  run.CpuSeconds = ThreadCpuSeconds() - cpu;
  return run;
}

/// Times one call of `make`, and the growth of the resident set while it runs.
template <typename Make>
Run Measure(Make&& make)
{
  const bool peakReset = ResetPeakMemory();
  const long long before = StatusKilobytes("VmRSS");
  Run run = Time(make);
  const long long peak = StatusKilobytes("VmHWM");
  if (peakReset && before >= 0 && peak >= 0)
  {
    run.PeakBytes = 1024 * (peak - before);
  }
  return run;
}

// Repeats. The machines the results come from are shared: one method's time swings by a third
// between runs minutes apart, and a slow phase can last a whole method's runs. So each method
// runs once in each of several passes over all the methods of a mesh, and keeps its fastest
// time: every method meets the slow and the fast phases alike.
constexpr int Passes = 3;
// Runs of over this many seconds skip the last pass (two runs in all) ...
constexpr double LongRunSeconds = 10.0;
// ... and runs of under this many are made ShortRunRepeats times per pass after the first (nine
// in all): a run of a fifth of a second took from 0.15 to 0.19 s in ten repeats within minutes,
// and with five in all the two-thread row of such a run could miss its fast phases.
constexpr double ShortRunSeconds = 1.0;
constexpr int ShortRunRepeats = 4;

/// One line of the report.
struct Row
{
  size_t MeshIndex = 0;
  std::string Method;
  int Threads = 1;
  double Fraction = 0.0;
  vtkIdType InputTriangles = 0;
  vtkIdType OutputTriangles = 0;
  double Seconds = 0.0;
  double CpuSeconds = 0.0;
  long long PeakBytes = -1;
  double Hausdorff = 0.0; // % of the diagonal
  double Rms = 0.0;
  bool WholeHierarchy = false;
  int Repeats = 1;

  /// Peak memory growth per input triangle, -1 when not measured.
  double BytesPerTriangle() const
  {
    return this->PeakBytes >= 0 ? static_cast<double>(this->PeakBytes) / this->InputTriangles
                                : -1.0;
  }
};

/// The triangle counts of the targets (fractions of the input's triangles).
std::vector<vtkIdType> TargetCounts(vtkPolyData* input, const std::vector<double>& fractions)
{
  std::vector<vtkIdType> targets;
  for (const double fraction : fractions)
  {
    targets.push_back(
      std::max<vtkIdType>(4, std::llround(fraction * input->GetNumberOfPolys())));
  }
  return targets;
}

using TimedJob = std::function<Outputs()>;

/// The timed jobs of a method on an input: one making every level for a hierarchy method, one
/// per target (prepared here, untimed) for the others.
std::vector<TimedJob> MakeJobs(const Method& method,
  vtkPolyData* input,
  const std::vector<vtkIdType>& targets,
  const Backends& smp)
{
  // Each job gets its own shallow copy: nothing a method builds on its input (cells, links)
  // carries over to the next method.
  auto makeInput = [input]() {
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->ShallowCopy(input);
    return copy;
  };
  std::vector<TimedJob> jobs;
  if (method.Hierarchy)
  {
    vtkSmartPointer<vtkPolyData> copy = makeInput();
    const auto make = method.Hierarchy;
    jobs.emplace_back([make, copy, targets]() { return make(copy, targets); });
  }
  else
  {
    for (vtkIdType target : targets)
    {
      vtkSmartPointer<vtkPolyData> copy = makeInput();
      UseAllCores(smp); // the untimed preparation may run the method many times
      const meshlod::benchmark::Job job = method.Prepare(copy, target);
      jobs.emplace_back([job, copy]() { return Outputs{ job() }; });
    }
  }
  return jobs;
}

std::string ShellQuoted(const std::string& text)
{
  std::string quoted = "'";
  for (const char c : text)
  {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

/// The peak memory growth of one timed job, measured in a fresh process (see the top of this
/// file); -1 with a note on stderr if that process fails.
long long ProbeMemory(const std::pair<meshlod::testing::Field, double>& mesh,
  const std::string& method,
  int threads,
  const std::vector<double>& fractions)
{
  std::string targets;
  for (const double fraction : fractions)
  {
    targets += (targets.empty() ? "" : ",") + Format("%.17g", fraction);
  }
  // This program's own file (in the shell that popen starts, /proc/self/exe is the shell).
  char self[4096];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof(self) - 1);
  if (length <= 0)
  {
    std::fprintf(stderr, "memory probe: cannot find this program's file\n");
    return -1;
  }
  self[length] = '\0';
  const std::string command = ShellQuoted(self) + " --memory-probe 1 --meshes " +
    ShellQuoted(std::string(meshlod::testing::FieldName(mesh.first)) + ":" +
      Format("%.17g", mesh.second)) +
    " --targets " + targets + " --threads " + std::to_string(threads) + " --methods " +
    ShellQuoted(method);
  std::fflush(stdout);
  FILE* probe = popen(command.c_str(), "r");
  long long bytes = -1;
  if (probe)
  {
    char line[256];
    while (std::fgets(line, sizeof(line), probe))
    {
      long long value = 0;
      if (std::sscanf(line, "memory-probe-bytes %lld", &value) == 1)
      {
        bytes = value;
      }
    }
    if (pclose(probe) != 0)
    {
      bytes = -1;
    }
  }
  if (bytes < 0)
  {
    std::fprintf(stderr, "memory probe failed: %s\n", command.c_str());
  }
  return bytes;
}

//------------------------------------------------------------------------------
class Benchmark
{
public:
  Benchmark(const Options& options, const Backends& backends)
    : Opts(options)
    , Smp(backends)
  {
    this->Yardstick.SamplesPerSurface = options.Samples;
    this->Yardstick.MaximumVertexSamples = options.Samples;
  }

  void MakeMeshes()
  {
    UseAllCores(this->Smp);
    for (const auto& spec : this->Opts.Meshes)
    {
      Mesh mesh;
      mesh.Field = meshlod::testing::FieldName(spec.first);
      const Clock::time_point start = Clock::now();
      mesh.Data = meshlod::benchmark::MakeBenchmarkMesh(
        spec.first, spec.second, mesh.Resolution, mesh.Dropped);
      mesh.Seconds = SecondsSince(start);
      mesh.Label = mesh.Field + " " + Thousands(mesh.Data->GetNumberOfPolys());
      std::printf("mesh %s: %d^3 volume, %lld triangles (%lld degenerate dropped), %.2f s\n",
        mesh.Label.c_str(),
        mesh.Resolution,
        static_cast<long long>(mesh.Data->GetNumberOfPolys()),
        static_cast<long long>(mesh.Dropped),
        mesh.Seconds);
      std::fflush(stdout);
      this->Meshes.push_back(mesh);
    }
  }

  void RunAll(const std::vector<Method>& methods)
  {
    for (size_t m = 0; m < this->Meshes.size(); ++m)
    {
      this->Reruns.clear();
      for (const Method& method : methods)
      {
        if (method.MaximumInputTriangles > 0 &&
          this->Meshes[m].Data->GetNumberOfPolys() > method.MaximumInputTriangles)
        {
          continue;
        }
        this->RunMethod(m, method, 1);
        if (method.Parallel && this->Opts.Threads > 1 && !this->Smp.Parallel.empty())
        {
          this->RunMethod(m, method, this->Opts.Threads);
        }
      }
      this->RepeatRuns();
    }
  }

  std::string Report(const std::vector<Method>& methods) const;

private:
  static std::string Thousands(long long value)
  {
    std::string digits = std::to_string(value), text;
    for (size_t i = 0; i < digits.size(); ++i)
    {
      if (i > 0 && (digits.size() - i) % 3 == 0)
      {
        text += ',';
      }
      text += digits[i];
    }
    return text;
  }

  void RunMethod(size_t meshIndex, const Method& method, int threads)
  {
    vtkPolyData* input = this->Meshes[meshIndex].Data;
    const vtkIdType inputTriangles = input->GetNumberOfPolys();
    const std::vector<vtkIdType> targets = TargetCounts(input, this->Opts.Targets);

    // The first run of each timed job here (its outputs are measured), the others in the later
    // passes (RepeatRuns).
    std::vector<Run> runs;
    const std::vector<TimedJob> jobs = MakeJobs(method, input, targets, this->Smp);
    const size_t firstRerun = this->Reruns.size();
    for (size_t j = 0; j < jobs.size(); ++j)
    {
      UseTimedBackend(this->Smp, threads);
      runs.push_back(Measure(jobs[j]));
      UseAllCores(this->Smp);
      if (this->Opts.FreshMemory)
      {
        // A hierarchy's one job makes every target; other methods have a job per target.
        const std::vector<double> fractions = method.Hierarchy
          ? this->Opts.Targets
          : std::vector<double>{ this->Opts.Targets[j] };
        runs.back().PeakBytes =
          ProbeMemory(this->Opts.Meshes[meshIndex], method.Name, threads, fractions);
      }
      this->Reruns.push_back(Rerun{ jobs[j], threads, {} });
    }

    UseAllCores(this->Smp);
    for (size_t t = 0; t < targets.size(); ++t)
    {
      const Run& run = method.Hierarchy ? runs[0] : runs[t];
      vtkPolyData* output = method.Hierarchy ? run.Results.at(t) : run.Results.at(0);
      Row row;
      row.MeshIndex = meshIndex;
      row.Method = method.Name;
      row.Threads = threads;
      row.Fraction = this->Opts.Targets[t];
      row.InputTriangles = inputTriangles;
      row.OutputTriangles = output->GetNumberOfPolys();
      row.Seconds = run.Seconds;
      row.CpuSeconds = run.CpuSeconds;
      row.PeakBytes = run.PeakBytes;
      row.WholeHierarchy = static_cast<bool>(method.Hierarchy);
      row.Repeats = 1;
      const Clock::time_point start = Clock::now();
      const meshlod::SurfaceDistance distance =
        meshlod::MeasureSurfaceDistance(input, output, this->Yardstick);
      const double yardstickSeconds = SecondsSince(start);
      this->LongestYardstick = std::max(this->LongestYardstick, yardstickSeconds);
      row.Hausdorff = distance.HausdorffPercent();
      row.Rms = distance.RmsPercent();
      std::printf(
        "  %-28s %d thread(s) %5.1f%%: %9lld triangles, %8.3f s (CPU %.3f s), %6.0f B/triangle, "
        "Hausdorff %.4f%%, RMS %.5f%% (yardstick %.1f s)\n",
        method.Name.c_str(),
        threads,
        100.0 * row.Fraction,
        static_cast<long long>(row.OutputTriangles),
        row.Seconds,
        row.CpuSeconds,
        row.BytesPerTriangle(),
        row.Hausdorff,
        row.Rms,
        yardstickSeconds);
      std::fflush(stdout);
      this->Rows.push_back(row);
      // A hierarchy's one job gives every target's row; other methods have a job per target.
      this->Reruns[firstRerun + (method.Hierarchy ? 0 : t)].Rows.push_back(this->Rows.size() - 1);
    }
  }

  // A timed job to run again in the later passes, and the rows its time goes to.
  struct Rerun
  {
    TimedJob Job;
    int Threads = 1;
    std::vector<size_t> Rows;
  };

  // The later passes over the mesh's timed jobs (see Passes), every other one in reverse order
  // so that no job always runs right after the same one. A row keeps its fastest time.
  void RepeatRuns()
  {
    for (int pass = 1; pass < Passes; ++pass)
    {
      for (size_t k = 0; k < this->Reruns.size(); ++k)
      {
        const Rerun& rerun = this->Reruns[pass % 2 == 1 ? this->Reruns.size() - 1 - k : k];
        Row& first = this->Rows[rerun.Rows.front()];
        if (pass == Passes - 1 && first.Seconds > LongRunSeconds)
        {
          continue;
        }
        const int times = first.Seconds < ShortRunSeconds ? ShortRunRepeats : 1;
        for (int time = 0; time < times; ++time)
        {
          UseTimedBackend(this->Smp, rerun.Threads);
          const Run run = Time(rerun.Job);
          UseAllCores(this->Smp);
          for (const size_t r : rerun.Rows)
          {
            Row& row = this->Rows[r];
            row.Seconds = std::min(row.Seconds, run.Seconds);
            row.CpuSeconds = std::min(row.CpuSeconds, run.CpuSeconds);
            ++row.Repeats;
          }
        }
      }
    }
    for (const Rerun& rerun : this->Reruns)
    {
      const Row& row = this->Rows[rerun.Rows.front()];
      std::printf("  %-28s %d thread(s): fastest of %d runs %.3f s\n", row.Method.c_str(),
        rerun.Threads, row.Repeats, row.Seconds);
    }
    std::fflush(stdout);
  }

  const Row* Find(size_t mesh, const std::string& method, int threads, double fraction) const
  {
    for (const Row& row : this->Rows)
    {
      if (row.MeshIndex == mesh && row.Fraction == fraction && row.Threads == threads &&
        row.Method == method)
      {
        return &row;
      }
    }
    return nullptr;
  }

  const Row* Reference(const Row& row) const
  {
    return this->Find(row.MeshIndex, "vtkQuadricDecimation", 1, row.Fraction);
  }

  std::string TargetSummary() const;

  const Options& Opts;
  Backends Smp;
  meshlod::SurfaceDistanceOptions Yardstick;
  std::vector<Mesh> Meshes;
  std::vector<Row> Rows;
  std::vector<Rerun> Reruns; // the current mesh's timed jobs
  double LongestYardstick = 0.0;
};

//------------------------------------------------------------------------------
// The report.

std::string ProcField(const char* file, const std::string& key)
{
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
  {
    if (line.compare(0, key.size(), key) == 0)
    {
      const size_t colon = line.find(':');
      if (colon != std::string::npos)
      {
        const size_t begin = line.find_first_not_of(" \t", colon + 1);
        return begin == std::string::npos ? "" : line.substr(begin);
      }
    }
  }
  return "unknown";
}

int LogicalCpus()
{
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  int count = 0;
  while (std::getline(in, line))
  {
    count += line.compare(0, 9, "processor") == 0 ? 1 : 0;
  }
  return count;
}

std::string Ratio(double value, double reference)
{
  return reference > 0.0 && value >= 0.0 ? Format("%.2f", value / reference) : "-";
}

// MeshLOD's hierarchy methods against the VTK filter each is meant to beat: the quality ratio
// per target, the time of the whole hierarchy on one thread against the reference's time for the
// largest target alone, the two-thread speed-up, and the memory.
std::string Benchmark::TargetSummary() const
{
  struct Pair
  {
    const char* Method;
    const char* Against;
  };
  const Pair pairs[] = { { "vtkTriangleCollapseDecimation", "vtkQuadricDecimation" },
    { "vtkTriangleCollapseDecimation flipped edges", "vtkQuadricDecimation" },
    { "vtkTriangleCollapseDecimation independent sets", "vtkQuadricDecimation" },
    { "vtkTriangleCollapseDecimation triangles only", "vtkQuadricDecimation" },
    { "vtkTriangleCollapseDecimation curvature", "vtkQuadricDecimation" },
    { "vtkTriangleCollapseDecimation curvature paper weight", "vtkQuadricDecimation" },
    { "vtkVertexClusterOctree", "vtkQuadricClustering" },
    { "vtkVertexClusterOctree flipped edges", "vtkQuadricClustering" },
    { "vtkVertexClusterOctree free topology", "vtkQuadricClustering" } };
  if (this->Opts.Targets.empty())
  {
    return std::string();
  }
  const double largest = this->Opts.Targets.front();
  std::ostringstream md;
  md << "## Against the reference filters\n\n"
     << "Ratios of the columns above (below 1: MeshLOD is better; *Two threads* is a speed-up, "
        "above 1 is better). *Quality*: Hausdorff and RMS "
        "over the reference's at each target. *Time, all levels*: the one-thread time of the "
        "whole hierarchy over the reference's one-thread time for its "
     << Format("%g", 100.0 * largest)
     << "% target alone. *Two threads*: one-thread time over two-thread time. *Memory*: bytes "
        "per input triangle, and over vtkQuadricDecimation's for the same target.\n\n"
     << "| mesh | method | against | ";
  for (double fraction : this->Opts.Targets)
  {
    md << Format("%g", 100.0 * fraction) << "%: Hausdorff, RMS | ";
  }
  md << "time, all levels | two threads | memory (B/triangle, x QD) |\n|---|---|---|";
  for (size_t i = 0; i < this->Opts.Targets.size(); ++i)
  {
    md << "---:|";
  }
  md << "---:|---:|---:|\n";
  for (size_t m = 0; m < this->Meshes.size(); ++m)
  {
    for (const Pair& pair : pairs)
    {
      const Row* one = this->Find(m, pair.Method, 1, largest);
      const Row* reference = this->Find(m, pair.Against, 1, largest);
      if (!one || !reference)
      {
        continue;
      }
      md << "| " << this->Meshes[m].Label << " | " << pair.Method << " | " << pair.Against
         << " | ";
      for (double fraction : this->Opts.Targets)
      {
        const Row* row = this->Find(m, pair.Method, 1, fraction);
        const Row* against = this->Find(m, pair.Against, 1, fraction);
        md << (row && against ? Ratio(row->Hausdorff, against->Hausdorff) + ", " +
                 Ratio(row->Rms, against->Rms)
                              : std::string("-"))
           << " | ";
      }
      const Row* two = this->Find(m, pair.Method, 2, largest);
      const Row* qd = this->Reference(*one);
      const double memory = one->BytesPerTriangle();
      const double qdMemory = qd ? qd->BytesPerTriangle() : -1.0;
      md << Ratio(one->Seconds, reference->Seconds) << " | "
         << (two ? Ratio(one->Seconds, two->Seconds) : "-") << " | "
         << (memory >= 0.0 ? Format("%.0f", memory) : "n/a") << ", "
         << Ratio(memory, qdMemory) << " |\n";
    }
  }
  md << "\n";
  return md.str();
}

std::string Benchmark::Report(const std::vector<Method>& methods) const
{
  std::ostringstream md;
  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M UTC", std::gmtime(&now));

  md << "# Benchmark results\n\n"
     << "Produced on " << date << " by\n\n```sh\n"
     << this->Opts.Command << "\n```\n\n"
     << "- Machine: " << ProcField("/proc/cpuinfo", "model name") << ", " << LogicalCpus()
     << " logical CPUs, "
     << Format(
          "%.1f", std::atof(ProcField("/proc/meminfo", "MemTotal").c_str()) / (1024.0 * 1024.0))
     << " GiB memory\n"
     << "- VTK " << vtkVersion::GetVTKVersion() << ", GCC " << __VERSION__ << ", Release build\n"
     << "- Single-thread rows: vtkSMPTools backend Sequential (the program started with "
     << "backend " << this->Smp.AtStart << ")";
  if (!this->Smp.Parallel.empty() && this->Opts.Threads > 1)
  {
    md << "; " << this->Opts.Threads << "-thread rows: backend " << this->Smp.Parallel
       << " initialised with " << this->Opts.Threads << " threads";
  }
  md << "\n\n";

  md << "## Columns\n\n"
     << "- *time*: wall time of the method alone (filter construction, Update, output), the "
        "fastest of its runs: one in each of three passes over all the methods of a mesh (two "
        "passes for runs of over ten seconds; runs under a second four times in each pass after "
        "the first), so that every method meets the slow and fast phases of a shared machine "
        "alike. Untimed: generating the input, searching a grid resolution, measuring the "
        "error.\n"
     << "- *CPU*: CPU time of the thread running the method, for single-thread rows (the whole "
        "method runs on it). Far below *time* means other programs were using the cores.\n"
     << "- *throughput*: input triangles per second (wall time).\n"
     << "- *memory*: peak growth of the resident set while the method runs (VmHWM after it "
        "minus VmRSS before it, with the peak reset through /proc/self/clear_refs and "
        "malloc_trim(0) first; the output is alive at the end), in bytes per input triangle"
     << (this->Opts.FreshMemory
            ? ", measured in a fresh process for each method (the program started again: it "
              "makes the same mesh, prepares the method and runs it once) so that the heap "
              "left by the methods run before does not count against it: in one process, "
              "vtkTriangleCollapseDecimation's growth on the 2.3M-triangle gyroid rose from 199 "
              "to 222 B per triangle after vtkQuadricDecimation and vtkDecimatePro had run"
            : ", measured in this process (--fresh-memory 0): the heap left by the methods "
              "run before it may count against it")
     << ".\n"
     << "- *Hausdorff*, *RMS*: symmetric surface distance between output and input "
        "(MeshLODSurfaceDistance: "
     << this->Yardstick.SamplesPerSurface << " area samples and up to "
     << this->Yardstick.MaximumVertexSamples
     << " vertices per surface, fixed seed, and from the "
     << this->Yardstick.RefinedSamples
     << " samples farthest from the other surface a search for the farthest point near each) in "
        "% of the input's bounding-box diagonal.\n"
     << "- *x QD*: ratio to single-thread vtkQuadricDecimation on the same mesh and target "
        "(below 1: faster, more accurate, less memory).\n\n";

  md << "## Meshes\n\nFlying-edges isosurfaces at 0 of analytic fields sampled on [-1, 1]^3 "
        "(Testing/Support/MeshLODTestMeshes), then cleaned with vtkCleanPolyData (exactly "
        "coincident points merged, collapsed triangles dropped): on the uncleaned 2.3M-triangle "
        "gyroid vtkQuadricDecimation stops after about 2000 collapses. Every method gets the "
        "same cleaned mesh.\n\n"
     << "| mesh | field | volume | triangles | points | degenerate dropped | generation and "
        "cleaning (s) |\n"
     << "|---|---|---:|---:|---:|---:|---:|\n";
  for (const Mesh& mesh : this->Meshes)
  {
    md << "| " << mesh.Label << " | " << mesh.Field << " | " << mesh.Resolution << "^3 | "
       << Thousands(mesh.Data->GetNumberOfPolys()) << " | "
       << Thousands(mesh.Data->GetNumberOfPoints()) << " | " << mesh.Dropped << " | "
       << Format("%.2f", mesh.Seconds) << " |\n";
  }
  md << "\n";

  for (size_t m = 0; m < this->Meshes.size(); ++m)
  {
    md << "## " << this->Meshes[m].Label << " triangles\n\n"
       << "| target | method | threads | input triangles | output triangles | time (s) | CPU (s) "
          "| throughput (triangles/s) | memory (B/triangle) | Hausdorff % | RMS % | time x QD | "
          "Hausdorff x QD | RMS x QD | memory x QD |\n"
       << "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (double fraction : this->Opts.Targets)
    {
      for (const Row& row : this->Rows)
      {
        if (row.MeshIndex != m || row.Fraction != fraction)
        {
          continue;
        }
        const Row* qd = this->Reference(row);
        const double memory = row.BytesPerTriangle();
        const double qdMemory = qd ? qd->BytesPerTriangle() : -1.0;
        md << "| " << Format("%g", 100.0 * fraction) << "% | " << row.Method
           << (row.WholeHierarchy ? " (whole hierarchy)" : "") << " | " << row.Threads << " | "
           << Thousands(row.InputTriangles) << " | " << Thousands(row.OutputTriangles) << " | "
           << Format(row.Seconds < 0.1 ? "%.4f" : "%.3f", row.Seconds) << " | "
           << (row.Threads == 1 ? Format(row.CpuSeconds < 0.1 ? "%.4f" : "%.3f", row.CpuSeconds)
                                : "-")
           << " | " << Thousands(std::llround(row.InputTriangles / std::max(row.Seconds, 1e-9)))
           << " | " << (memory >= 0.0 ? Format("%.0f", memory) : "n/a") << " | "
           << Format("%.4f", row.Hausdorff) << " | " << Format("%.5f", row.Rms) << " | "
           << (qd ? Ratio(row.Seconds, qd->Seconds) : "-") << " | "
           << (qd ? Ratio(row.Hausdorff, qd->Hausdorff) : "-") << " | "
           << (qd ? Ratio(row.Rms, qd->Rms) : "-") << " | " << (qd ? Ratio(memory, qdMemory) : "-")
           << " |\n";
      }
    }
    md << "\n";
  }

  md << this->TargetSummary();
  std::vector<std::string> labels;
  for (const Mesh& mesh : this->Meshes)
  {
    labels.push_back(mesh.Label);
  }
  md << meshlod::benchmark::TargetsReport(labels, this->Opts.Targets,
    [this](size_t mesh, const std::string& method, int threads, double fraction,
      meshlod::benchmark::Measurement& result) {
      const Row* row = this->Find(mesh, method, threads, fraction);
      if (!row)
      {
        return false;
      }
      result.Seconds = row->Seconds;
      result.Hausdorff = row->Hausdorff;
      result.Rms = row->Rms;
      result.BytesPerTriangle = row->BytesPerTriangle();
      return true;
    });

  md << "## Settings of the methods\n\n";
  for (const Method& method : methods)
  {
    md << "- **" << method.Name << "**" << (method.Parallel ? " (uses vtkSMPTools)" : "")
       << (method.Hierarchy ? " (hierarchy: one run makes every level; its time and memory are "
                              "those of the whole hierarchy)"
                            : "")
       << ": " << method.Settings;
    if (method.MaximumInputTriangles > 0)
    {
      md << " Run only on meshes of at most " << method.MaximumInputTriangles << " triangles.";
    }
    md << "\n";
  }
  md << "\nThe longest single error measurement took " << Format("%.1f", this->LongestYardstick)
     << " s.\n";
  return md.str();
}

/// The fresh process of ProbeMemory: the first timed job of the one method on the one mesh.
int RunMemoryProbe(const Options& options, const std::vector<Method>& methods, const Backends& smp)
{
  if (options.Meshes.size() != 1 || methods.size() != 1)
  {
    std::cerr << "--memory-probe wants one mesh and one method\n";
    return 2;
  }
  UseAllCores(smp);
  int resolution = 0;
  vtkIdType dropped = 0;
  vtkSmartPointer<vtkPolyData> input = meshlod::benchmark::MakeBenchmarkMesh(
    options.Meshes[0].first, options.Meshes[0].second, resolution, dropped);
  const std::vector<TimedJob> jobs =
    MakeJobs(methods[0], input, TargetCounts(input, options.Targets), smp);
  UseTimedBackend(smp, options.Threads);
  const Run run = Measure(jobs.front());
  std::printf("memory-probe-bytes %lld\n", run.PeakBytes);
  return run.PeakBytes >= 0 ? 0 : 1;
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  if (!ParseArguments(argc, argv, options))
  {
    std::cerr << "usage: " << argv[0]
              << " [--meshes field:triangles,...] [--targets fraction,...] [--threads N]"
                 " [--methods name,...] [--samples N] [--output FILE] [--command TEXT]\n";
    return 2;
  }

  const Backends backends = FindBackends();
  if (backends.AtStart != "Sequential")
  {
    std::cerr << "note: started with the " << backends.AtStart
              << " backend; single-thread rows switch to Sequential at run time. Start with "
                 "VTK_SMP_BACKEND_IN_USE=Sequential to match run-benchmarks.sh.\n";
  }

  std::vector<Method> registered, methods;
  meshlod::benchmark::RegisterVTKMethods(registered);
  meshlod::benchmark::RegisterMeshLODMethods(registered);
  for (const Method& method : registered)
  {
    if (options.Methods.empty() ||
      std::find(options.Methods.begin(), options.Methods.end(), method.Name) !=
        options.Methods.end())
    {
      methods.push_back(method);
    }
  }
  if (methods.empty())
  {
    std::cerr << "no registered method matches --methods\n";
    return 2;
  }

  if (options.MemoryProbe)
  {
    return RunMemoryProbe(options, methods, backends);
  }
  Benchmark benchmark(options, backends);
  benchmark.MakeMeshes();
  benchmark.RunAll(methods);
  const std::string report = benchmark.Report(methods);
  std::cout << "\n" << report;
  if (!options.Output.empty())
  {
    std::ofstream out(options.Output);
    out << report;
    out.close();
    if (out.fail())
    {
      std::cerr << "cannot write " << options.Output << "\n";
      return 1;
    }
  }
  return 0;
}
