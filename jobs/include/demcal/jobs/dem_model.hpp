#pragma once
// The DEM itself as a model of macro values (DEM in the loop, Wang & Cao
// 2017): the inputs are the varied parameters of a space, the outputs macro
// values of a scene's test, and a prediction is a DEM run (the mean over
// `seeds` specimens). The optimisers of the inversion stage drive it through
// core's Model interface like any surrogate; a batch of points (a population,
// or parallel annealing trials) runs at once, one process per point.
//
// Every run is stored as it finishes under work_dir/points/ (numbered in the
// order the optimiser asks for points), and work_dir/evaluations.csv lists
// all of them; a deterministic optimiser rerun with the same seed asks for the
// same points in the same order, so an interrupted calibration resumes
// without repeating a finished DEM run. A point asked for again is answered
// from memory.
#include <map>
#include <string>
#include <vector>

#include "demcal/core/model.hpp"
#include "demcal/core/parameter_space.hpp"
#include "demcal/dem/scene_set.hpp"

namespace demcal::jobs {

struct DemModelOptions {
  std::string work_dir;   // required: where the runs are stored
  int seeds = 1;          // specimens per point; outputs are their mean
  int jobs = 1;           // points run at once
  std::string cache_dir;  // packed specimens
  bool progress = true;   // a line on stderr at most every 10 s
  std::string space_path = "the parameter space";  // for error messages
};

class DemModel : public BoxModel {
 public:
  // Throws when the space does not narrow the scene (Scene::check_space): a
  // varied, fixed or tied parameter that the scene lacks, or a range beyond its bounds.
  DemModel(const std::string& scene_path, const ParameterSpace& space, std::vector<std::string> outputs,
           DemModelOptions options);

  using Model::predict;
  void predict(const double* x, double* y) const override;
  // Failed runs give NaN outputs (the inversion then treats the point as no
  // solution). An output the scene's results do not have is an Error.
  void predict_batch(const std::vector<std::vector<double>>& xs, std::vector<std::vector<double>>& ys) const override;

  long points() const { return next_run_ - 1; }  // distinct points evaluated
  long runs_made() const { return runs_made_; }  // DEM runs made by this process
  long runs_reused() const { return runs_reused_; }  // found stored from an earlier, interrupted run
  long runs_failed() const { return runs_failed_; }
  double dem_wall_s() const { return dem_wall_s_; }
  std::string evaluations_csv() const { return options_.work_dir + "/evaluations.csv"; }

 private:
  void write_evaluations() const;

  std::string scene_path_;
  dem::SceneSet scene_;
  ParameterSpace space_;
  DemModelOptions options_;
  struct Evaluation {
    long run = 0;
    std::vector<double> x, y;
    int failed_seeds = 0;
    std::string reason;
  };
  mutable std::map<std::vector<double>, Evaluation> evaluated_;
  mutable std::vector<const Evaluation*> order_;
  mutable long next_run_ = 1;
  mutable long runs_made_ = 0, runs_reused_ = 0, runs_failed_ = 0;
  mutable double dem_wall_s_ = 0.0;
  mutable double last_report_s_ = 0.0;
};

}  // namespace demcal::jobs
