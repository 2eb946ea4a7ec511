#pragma once
// hba's public API in one include: read a dataset, run the method, write
// and judge the result. The headers below are the library's surface; see
// docs/architecture.md for what each module does.
#include "hba/version.hpp"

// Data: poses, clouds, errors (hba::Error names the file and the problem).
#include "hba/core/error.hpp"
#include "hba/core/point_cloud.hpp"
#include "hba/core/pose.hpp"

// Input and output: datasets, scan files of every format, pose files, bags.
#include "hba/io/dataset.hpp"
#include "hba/io/pose_file.hpp"
#include "hba/io/scan_file.hpp"
#include "hba/io/scan_formats.hpp"
#include "hba/io/scan_source.hpp"
#include "hba/rec/recording.hpp"

// The method: settings, closures and priors, the run and its report.
#include "hba/pipeline/closure_inputs.hpp"
#include "hba/pipeline/hierarchical_ba.hpp"
#include "hba/pipeline/report.hpp"
#include "hba/settings/settings.hpp"
#include "hba/settings/settings_file.hpp"

// Judging a result: trajectory errors, merged maps, map entropy.
#include "hba/eval/map_entropy.hpp"
#include "hba/eval/merged_map.hpp"
#include "hba/eval/trajectory_error.hpp"

// Synthetic sequences with ground truth.
#include "hba/sim/simulation.hpp"
