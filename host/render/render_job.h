// A render as one value: the scene (loaded, with the command line's overrides applied), how its
// samples are taken (RenderOptions) and when the session stops and what it writes
// (SessionOptions). Built by the command line (cli/commands.cpp) or by a test, and passed whole
// through the pipeline:
//   buildSceneBvh(job.scene, job.bvh) -> packGpuArrays (render/gpu_arrays.h, the CPU packing step and the
//   device-limit check) -> Renderer (upload, dispatch) -> runSession (batches, dumps, outputs)
//   -> runStats (render/run_stats.h).
#pragma once
#include <filesystem>

#include "bvh/build.h"
#include "render/render_options.h"
#include "render/session.h"
#include "scene/scene.h"

namespace vkp {

struct RenderJob {
    std::filesystem::path sceneFile;  ///< as given (messages, stats)
    Scene scene;                      ///< overrides applied; scene.render.spp is the session's spp
    BvhBuildOptions bvh;              ///< how its BVH is built (--spatial-splits)
    RenderOptions options;
    SessionOptions session;
};

}  // namespace vkp
