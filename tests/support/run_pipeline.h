#pragma once
// Runs the whole pipeline on a soup, as the CLI does.
#include "crestline/mesh/repair.h"
#include "crestline/pipeline.h"

namespace crestline::testing {

inline Pipeline run_pipeline(const TriangleSoup& soup, const PipelineOptions& options = {}) {
  Pipeline pipeline(repair_mesh(soup).mesh);
  pipeline.set_options(options);
  pipeline.run();
  return pipeline;
}

}  // namespace crestline::testing
