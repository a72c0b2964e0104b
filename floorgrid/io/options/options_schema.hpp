#pragma once

#include "floorgrid/core/option_visitor.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/options/options_file.hpp"
#include "floorgrid/pipeline/align.hpp"

namespace floorgrid {

/// Every setting of a job on a dataset (`align`, `pairs`): how it is loaded, how the run is
/// localized, how the models are fitted and judged. Defaults are the structs' own.
struct JobOptions {
  io::PlanRasterOptions raster;  ///< how a DXF plan becomes a grid
  io::DatasetLimits limits;      ///< what loading may cost
  PlanUnitFitOptions units;      ///< how the run decides a DXF's ambiguous units
  AlignmentOptions align;        ///< the main job
};

/// The fields of each options struct, with units and a line of documentation, for
/// `config --dump` and `--config FILE` (io/options_file).
void visit(OptionVisitor& v, AlignmentOptions& o);
void visit(OptionVisitor& v, AutoOptions& o);
void visit(OptionVisitor& v, BeamModelOptions& o);
void visit(OptionVisitor& v, ConvergenceOptions& o);
void visit(OptionVisitor& v, CrossValidationOptions& o);
void visit(OptionVisitor& v, io::DatasetLimits& o);
void visit(OptionVisitor& v, SubmapCheckOptions& o);
void visit(OptionVisitor& v, DualCheckOptions& o);
void visit(OptionVisitor& v, ErrorModelOptions& o);
void visit(OptionVisitor& v, DualLocalizerOptions& o);
void visit(OptionVisitor& v, FilterRunnerOptions& o);
void visit(OptionVisitor& v, FreeSpaceOptions& o);
void visit(OptionVisitor& v, GaussianProcessOptions& o);
void visit(OptionVisitor& v, GpLatticeOptions& o);
void visit(OptionVisitor& v, GpPredictionOptions& o);
void visit(OptionVisitor& v, GpTuningOptions& o);
void visit(OptionVisitor& v, GridmapLocalizationOptions& o);
void visit(OptionVisitor& v, HypothesisSeedingOptions& o);
void visit(OptionVisitor& v, LikelihoodFieldOptions& o);
void visit(OptionVisitor& v, LinearCombinationOptions& o);
void visit(OptionVisitor& v, LocalTransformsOptions& o);
void visit(OptionVisitor& v, MapFilterOptions& o);
void visit(OptionVisitor& v, PlanUnitFitOptions& o);
void visit(OptionVisitor& v, MappingCommonOptions& o);
void visit(OptionVisitor& v, MappingOptions& o);
void visit(OptionVisitor& v, ModelComparisonOptions& o);
void visit(OptionVisitor& v, MotionNoise& o);
void visit(OptionVisitor& v, ObservationOptions& o);
void visit(OptionVisitor& v, PosePullOptions& o);
void visit(OptionVisitor& v, OutlierScanOptions& o);
void visit(OptionVisitor& v, PairExtractionOptions& o);
void visit(OptionVisitor& v, ParticleFilterOptions& o);
void visit(OptionVisitor& v, PlanLocationOptions& o);
void visit(OptionVisitor& v, io::PlanRasterOptions& o);
void visit(OptionVisitor& v, PlanRegistrationOptions& o);
void visit(OptionVisitor& v, RansacOptions& o);
void visit(OptionVisitor& v, RecoveryOptions& o);
void visit(OptionVisitor& v, ReductionOptions& o);
void visit(OptionVisitor& v, RpropOptions& o);
void visit(OptionVisitor& v, ScaleRange& o);
void visit(OptionVisitor& v, ScaleRefitOptions& o);
void visit(OptionVisitor& v, ScaleSearchOptions& o);
void visit(OptionVisitor& v, ScanMatchOptions& o);
void visit(OptionVisitor& v, SubmapOptions& o);
void visit(OptionVisitor& v, ThinPlateSplineLatticeOptions& o);
void visit(OptionVisitor& v, ThinPlateSplineModelOptions& o);
void visit(OptionVisitor& v, VisibleWallsOptions& o);
void visit(OptionVisitor& v, WallFieldOptions& o);
void visit(OptionVisitor& v, JobOptions& o);

namespace io {
/// The tree of `options` as config --dump prints it and --config FILE reads it.
OptionTree job_option_tree(JobOptions& options);
}  // namespace io

}  // namespace floorgrid
