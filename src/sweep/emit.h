#pragma once
// `penumbra sweep --emit slurm|kubernetes`: the job a cluster runs for a plan, as text. Each
// array task or Job index runs `penumbra sweep PLAN -o DIR --task-count N`, and sweep reads its
// index from the engine's environment (SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX). The engine
// schedules and retries; nothing of ours runs beside it.
#include <cstdint>
#include <string>

namespace penumbra::sweep {

struct EmitOptions {
    std::string penumbra = "penumbra"; // the command on the nodes / in the image
    std::string plan, output;          // as the nodes or the container see them
    std::string truthCache;            // "" = DIR/truth
    uint32_t shards = 1;
    uint32_t gpus = 1; // per task; 0: none asked for
    std::string jobName = "penumbra-sweep";
    // Kubernetes: the image, and the PersistentVolumeClaim mounted at `mount` holding the plan,
    // its scenes and DIR.
    std::string image = "penumbra:latest";
    std::string volumeClaim = "penumbra-data";
    std::string mount = "/data";
};

// An sbatch script: a job array of `shards` tasks, each one shard, with its log in DIR.
std::string slurmScript(const EmitOptions& options);
// A batch/v1 Indexed Job of `shards` completions, all allowed to run at once.
std::string kubernetesManifest(const EmitOptions& options);

// A word for a shell command line (single-quoted unless plainly safe).
std::string shellQuote(const std::string& word);

} // namespace penumbra::sweep
