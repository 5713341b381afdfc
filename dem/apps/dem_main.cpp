// demcal-dem: runs the DEM scenes: one run, a resumable batch over a design
// (local processes, MPI ranks or a shard of a job array), and the merge of shards.
#include <CLI/CLI.hpp>

#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include <omp.h>

#include "released_run.hpp"

#include "demcal/core/atomic_file.hpp"
#include "demcal/core/cli_main.hpp"
#include "demcal/core/executable_dir.hpp"
#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/core/table.hpp"
#include "demcal/core/progress.hpp"
#include "demcal/jobs/batch.hpp"
#include "demcal/jobs/batch_mpi.hpp"
#include "demcal/dem/describe.hpp"
#include "demcal/dem/lammps_data.hpp"
#include "demcal/dem3d/sphere_export.hpp"
#include "demcal/dem3d/sphere_scene.hpp"
#include "demcal/jobs/merge.hpp"
#include "demcal/dem/result_json.hpp"
#include "demcal/dem/scene_set.hpp"
#include "demcal/dem/disk_scene.hpp"
#include "demcal/dem/scene.hpp"
#include "demcal/dem/lab_test.hpp"

namespace {

using namespace demcal;
using json = nlohmann::json;

std::map<std::string, double> parse_sets(const std::vector<std::string>& sets) {
  std::map<std::string, double> values;
  for (const std::string& item : sets) {
    auto [name, value] = parse_name_value(item, "--set");
    values[name] = value;
  }
  return values;
}

// The curve of a run (dem::curve_json's columns, `prefix` before each name
// in a test list's), in a fixed order; false when it has none of them.
bool write_curve(const nlohmann::json& curve, const std::string& prefix, const std::string& path) {
  Table table;
  const std::vector<std::string> first = {"axial_strain", "stress_MPa", "lateral_strain", "cracks", "confining_stress_MPa"};
  for (const std::string& column : first)
    if (curve.contains(prefix + column)) table.add_column(column, curve.at(prefix + column).get<std::vector<double>>());
  // A test's own series (a wave strip's time and velocities), in name order.
  if (table.names().empty())
    for (auto it = curve.begin(); it != curve.end(); ++it)
      if (it.key().rfind(prefix, 0) == 0 && (prefix.empty() || it.key().find('.', prefix.size()) == std::string::npos))
        table.add_column(it.key().substr(prefix.size()), it.value().get<std::vector<double>>());
  if (table.names().empty()) return false;
  table.write(path, "/curve");
  return true;
}

// One file for a scene; for a test list one per test that ran, named
// STEM.LABEL.EXT (the curves differ in length).
void write_curves(const dem::SceneSet& set, const nlohmann::json& curve, const std::string& path) {
  if (set.size() == 1) {
    write_curve(curve, "", path);
    return;
  }
  const std::size_t dot = path.find_last_of('.');
  const std::string stem = dot == std::string::npos ? path : path.substr(0, dot);
  const std::string ext = dot == std::string::npos ? "" : path.substr(dot);
  for (std::size_t k = 0; k < set.size(); ++k) {
    const std::string file = stem + "." + set.label(k) + ext;
    if (write_curve(curve, set.label(k) + ".", file)) log::info("wrote the " + set.label(k) + " curve to " + file);
  }
}

// The scene's packed specimen at its default parameters (from the cache, or packed now).
dem::Specimen packed_specimen(const dem::Scene& scene, std::uint64_t seed, const std::string& cache_dir) {
  if (scene.lab_test().dimension() != 2 || !scene.has_section("specimen"))
    throw Error(scene.origin() + ": its test (" + scene.test() + ") has no packed 2D specimen of ours");
  return dem::cached_specimen(dem::specimen_spec(scene, scene.resolve({}), seed), cache_dir);
}

// A 3D scene's packed specimen at its default parameters (from the cache, or packed now).
dem3d::SphereSpecimen packed_sphere_specimen(const dem::Scene& scene, std::uint64_t seed, const std::string& cache_dir) {
  if (!scene.has_section("specimen"))
    throw Error(scene.origin() + ": its test (" + scene.test() + ") has no packed specimen of ours");
  return dem3d::cached_sphere_specimen(dem3d::sphere_specimen_spec(scene, scene.resolve({}), seed), cache_dir);
}

}  // namespace

int main(int argc, char** argv) {
  log::set_program("demcal-dem");
  CLI::App app{"demcal-dem: bonded-particle DEM runs of a 2D or 3D scene (its lab test): one run, a resumable batch over a design, the merge of shards, or a description of the scene.", "demcal-dem"};
  app.require_subcommand(1);
  std::string scene_path, out, curve, cache_dir = default_cache_dir();
  std::vector<std::string> sets;
  std::uint64_t seed = 1;
  bool quiet = false;
  CLI::App* run = app.add_subcommand("run", "run one scene at one parameter set");
  run->add_option("--scene", scene_path, "scene JSON (data/scenes/...)")->required();
  run->add_option("--set", sets, "NAME=VALUE for a scene parameter (repeatable)");
  run->add_option("--seed", seed, "packing and bond-strength seed")->capture_default_str();
  run->add_option("--out", out, "result JSON (default: the result is printed on stdout only)");
  run->add_option("--curve", curve, "stress-strain curve, .csv or .h5");
  run->add_option("--cache", cache_dir, "folder of cached packed specimens (\"\" to disable)")->capture_default_str();
  std::string vtk_dir;
  run->add_option("--vtk", vtk_dir, "folder for VTK snapshots (disks and bonds, bond breaks, walls) for ParaView");
  std::string work_dir;
  run->add_option("--work", work_dir,
                  "folder for an external test's files (params.json, out.json, stdout.txt, stderr.txt; default: "
                  "OUT without .json + \".work\", or demcal_work_SEED)");
  int run_threads = 0;
  run->add_option("--threads", run_threads,
                  "threads of the run's force loop (0: OpenMP's default, OMP_NUM_THREADS or every core; "
                  "results do not depend on it)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  run->add_flag("--quiet", quiet, "no progress on stderr (and, with --out, no copy of the result on stdout)");
  jobs::BatchOptions batch_options;
  CLI::App* batch = app.add_subcommand("batch", "run every point of a design (x seeds), resumable");
  batch->add_option("--scene", batch_options.scene_path, "scene JSON")->required();
  batch->add_option("--design", batch_options.design_path, "design .csv or .h5 (columns named after scene parameters)")
      ->required();
  batch->add_option("--out", batch_options.out_path, "responses .h5 (point results also under OUT.points/)")->required();
  batch->add_option("--seeds", batch_options.seeds, "seeds per design point (first seed .. first seed + K - 1)")
      ->capture_default_str();
  batch->add_option("--first-seed", batch_options.first_seed, "first seed of each point")->capture_default_str();
  batch->add_option("--jobs", batch_options.jobs, "points run at once")->capture_default_str();
  batch->add_option("--threads", batch_options.threads,
                    "threads the points running at once share (0: OpenMP's default; with MPI: per rank, default 1)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  batch->add_option("--csv", batch_options.csv_path, "flat CSV export: design columns, seed, status, macro values");
  batch->add_option("--cache", cache_dir, "folder of cached packed specimens")->capture_default_str();
  std::string shard;
  batch->add_option("--shard", shard, "I/N: run only every N-th point, starting at the I-th (job arrays; join with merge)");
  batch->add_flag("--move-aside", batch_options.move_aside,
                  "OUT holds another scene's results: move them into OUT_STEM.moved-K/ first (else refused)");
  batch->add_flag("--quiet", quiet, "no progress on stderr (failed points are still reported)");
  std::string describe_scene, describe_space;
  bool describe_registries = false;
  CLI::App* describe = app.add_subcommand("describe", "print what a scene has (JSON): test, parameters, outputs, contacts");
  describe->add_option("--scene", describe_scene, "scene JSON");
  describe->add_option("--space", describe_space, "also check that this parameter space narrows the scene");
  describe->add_flag("--registries", describe_registries, "list the registered lab tests and contact models instead");
  std::string export_scene, export_lammps, export_yade;
  std::uint64_t export_seed = 1;
  CLI::App* export_cmd =
      app.add_subcommand("export", "write a scene's packed specimen (cached or packed now) for another engine");
  export_cmd->add_option("--scene", export_scene, "scene JSON")->required();
  export_cmd->add_option("--seed", export_seed, "packing seed")->capture_default_str();
  export_cmd->add_option("--lammps", export_lammps, "LAMMPS data file (atom_style sphere: a 2D scene's disks or a 3D scene's spheres)");
  export_cmd->add_option("--yade", export_yade, "text file of x y z r lines as YADE's ymport.text reads them (a 3D scene's spheres)");
  export_cmd->add_option("--cache", cache_dir, "folder of cached packed specimens")->capture_default_str();
  export_cmd->add_flag("--quiet", quiet, "no progress on stderr");
  std::string released_scene;
  std::uint64_t released_seed = 1;
  dem::ReleasedRunOptions released;
  CLI::App* released_cmd = app.add_subcommand(
      "released", "release a scene's packed specimen with fixed linear springs, no damping and no walls "
                  "(the peer run of make bench; JSON with timings and the kinetic energy history on stdout)");
  released_cmd->add_option("--scene", released_scene, "scene JSON (its specimen)")->required();
  released_cmd->add_option("--seed", released_seed, "packing seed")->capture_default_str();
  released_cmd->add_option("--cache", cache_dir, "folder of cached packed specimens")->capture_default_str();
  released_cmd->add_option("--kn", released.kn_n_m, "normal spring, N/m")->capture_default_str();
  released_cmd->add_option("--ks", released.ks_n_m, "shear spring, N/m")->capture_default_str();
  released_cmd->add_option("--friction", released.friction, "Coulomb friction coefficient")->capture_default_str();
  released_cmd->add_option("--dt", released.dt_s, "time step, s")->required();
  released_cmd->add_option("--steps", released.steps, "steps")->capture_default_str();
  released_cmd->add_option("--every", released.every, "kinetic energy every this many steps")->capture_default_str();
  released_cmd->add_flag("--quiet", quiet, "no progress on stderr");
  released_cmd->add_flag("--box", released.box, "fixed walls on the specimen's box (the packing stays nearly at rest)");
  released_cmd->add_option("--threads", released.threads, "threads (0: OpenMP's default)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  std::vector<std::string> merge_inputs;
  std::string merge_out, merge_csv;
  CLI::App* merge = app.add_subcommand("merge", "join the result files of batch shards into one (resumable by batch)");
  merge->add_option("inputs", merge_inputs, "responses .h5 of the shards")->required();
  merge->add_option("--out", merge_out, "merged responses .h5 (point results also under OUT.points/)")->required();
  merge->add_option("--csv", merge_csv, "flat CSV export of the merged results");
  return cli::run_main(app, argc, argv, [&]() {
    if (quiet) log::set_level(log::Level::Quiet);
    if (batch->parsed()) {
      batch_options.cache_dir = cache_dir;
      batch_options.progress = !quiet;
      if (!is_hdf5_path(batch_options.out_path)) throw Error("--out must be an .h5 file (the responses)");
      if (!shard.empty()) jobs::parse_shard(shard, batch_options);
      jobs::BatchSummary s;
      if (jobs::started_by_mpi_launcher()) {
        jobs::MpiSession mpi;
        if (mpi.size() > 1) {
          if (mpi.rank() > 0) log::set_level(log::Level::Quiet);
          s = jobs::run_batch_mpi(batch_options, mpi);
          if (mpi.rank() > 0) return 0;  // rank 0's exit status carries a failure (and says why)
        } else {
          s = jobs::run_batch(batch_options);
        }
      } else {
        s = jobs::run_batch(batch_options);
      }
      log::info(std::to_string(s.points) + " points: " + std::to_string(s.ok) + " ok, " + std::to_string(s.failed) +
                " failed, " + std::to_string(s.skipped) + " done before; " + format_duration(s.wall_s) + "; wrote " +
                batch_options.out_path);
      return s.failed > 0 ? 4 : 0;
    }
    if (describe->parsed()) {
      if (describe_registries) {
        std::cout << dem::describe_registries().dump(2) << "\n";
        return 0;
      }
      if (describe_scene.empty()) throw Error("describe: --scene is required (or --registries)");
      const dem::SceneSet scene = dem::SceneSet::load(describe_scene);
      if (!describe_space.empty()) scene.check_space(ParameterSpace::load(describe_space), describe_space);
      std::cout << dem::describe_scene_set(scene).dump(2) << "\n";
      return 0;
    }
    if (merge->parsed()) {
      if (!is_hdf5_path(merge_out)) throw Error("--out must be an .h5 file (the merged responses)");
      jobs::MergeSummary m = jobs::merge_results(merge_inputs, merge_out, merge_csv);
      log::info("merged " + std::to_string(m.inputs) + " file(s): " + std::to_string(m.points) + " points (" +
                std::to_string(m.failed) + " failed, " + std::to_string(m.duplicates) + " duplicate(s) dropped); wrote " +
                merge_out);
      if (m.points < m.design_points) {
        log::warn(std::to_string(m.design_points - m.points) + " of the design's " + std::to_string(m.design_points) +
                  " points are missing (a shard not given or not finished); a batch over the whole design into " +
                  merge_out + " runs only those");
        return 4;
      }
      return 0;
    }
    if (export_cmd->parsed()) {
      if (dem::SceneSet::is_test_list(export_scene))
        throw Error("export: " + export_scene + " is a test list; name one of its scenes");
      dem::Scene scene = dem::Scene::load(export_scene);
      if (scene.is_external()) throw Error("export: " + export_scene + " is an external test: it has no specimen of ours");
      if (export_lammps.empty() && export_yade.empty()) throw Error("export: give --lammps FILE or --yade FILE");
      const std::string title = scene.name() + ", seed " + std::to_string(export_seed);
      if (scene.lab_test().dimension() == 3) {
        const dem3d::SphereSpecimen s = packed_sphere_specimen(scene, export_seed, cache_dir);
        if (!export_lammps.empty()) {
          dem3d::write_lammps_data(s, export_lammps, title);
          log::info("wrote " + std::to_string(s.size()) + " spheres to " + export_lammps);
        }
        if (!export_yade.empty()) {
          dem3d::write_sphere_text(s, export_yade, title);
          log::info("wrote " + std::to_string(s.size()) + " spheres to " + export_yade);
        }
        return 0;
      }
      if (!export_yade.empty())
        throw Error("export --yade: " + export_scene + " is a 2D scene; YADE takes a 3D scene's spheres (its disks go to LAMMPS with --lammps)");
      const dem::Specimen s = packed_specimen(scene, export_seed, cache_dir);
      dem::write_lammps_data(s, export_lammps, title);
      log::info("wrote " + std::to_string(s.size()) + " disks to " + export_lammps);
      return 0;
    }
    if (released_cmd->parsed()) {
      if (dem::SceneSet::is_test_list(released_scene))
        throw Error("released: " + released_scene + " is a test list; name one of its scenes");
      const dem::Scene scene = dem::Scene::load(released_scene);
      if (scene.is_external())
        throw Error("released: " + released_scene + " is an external test: it has no specimen of ours");
      const dem::Specimen s = packed_specimen(scene, released_seed, cache_dir);
      std::cout << dem::run_released_specimen(s, released).dump() << "\n";
      return 0;
    }
    if (run_threads > 0) omp_set_num_threads(run_threads);
    const dem::SceneSet scene = dem::SceneSet::load(scene_path);
    std::map<std::string, double> parameters = scene.resolve(parse_sets(sets));
    dem::RunOptions options;
    options.seed = seed;
    options.cache_dir = cache_dir;
    options.progress = !quiet;
    options.vtk_dir = vtk_dir;
    options.work_dir = !work_dir.empty() ? work_dir
                       : !out.empty()    ? out.substr(0, out.size() - (out.size() > 5 && out.substr(out.size() - 5) == ".json" ? 5 : 0)) + ".work"
                                         : "demcal_work_" + std::to_string(seed);
    json summary = scene.run(parameters, options);
    const json curves = summary.at("curve");
    summary.erase("curve");
    if (!out.empty()) write_file_atomically(out, summary.dump(2) + "\n");
    if (!curve.empty()) write_curves(scene, curves, curve);
    // Without --out, stdout is where the result goes, --quiet or not.
    if (out.empty() || !quiet) std::cout << summary.dump(2) << "\n";
    if (summary.at("status") != "ok") {
      log::error("the run failed: " + summary.value("reason", std::string("no reason recorded")) +
                 (out.empty() ? "" : " (recorded in " + out + ")"));
      return 4;
    }
    return 0;
  }, "4 the run failed, a batch point failed (each reason on stderr and stored with the point) or a merge lacks points");
}
