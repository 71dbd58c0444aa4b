// The cluster jobs (emit.h).
#include "sweep/emit.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra::sweep {
namespace {

// A YAML double-quoted scalar.
std::string yamlQuote(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\')
            out += '\\';
        out += c;
    }
    return out + "\"";
}

} // namespace

std::string shellQuote(const std::string& word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) ||
               std::string_view("/._-+=:@,").find(c) != std::string_view::npos;
    });
    if (plain)
        return word;
    std::string out = "'";
    for (char c : word)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string slurmScript(const EmitOptions& o) {
    std::string text = "#!/bin/bash\n";
    text += fmt::format("#SBATCH --job-name={}\n", o.jobName);
    text += fmt::format("#SBATCH --array=0-{}\n", o.shards - 1);
    text += fmt::format("#SBATCH --output={}/slurm-%A_%a.log\n", o.output);
    if (o.gpus > 0)
        text += fmt::format("#SBATCH --gres=gpu:{}\n", o.gpus);
    text += "# One shard of the plan per array task; sweep reads SLURM_ARRAY_TASK_ID. A task that\n"
            "# is resubmitted redoes only what its shard has not finished.\n";
    text += "set -euo pipefail\n";
    text += fmt::format("exec {} sweep {} -o {} --task-count {}{}\n", shellQuote(o.penumbra),
                        shellQuote(o.plan), shellQuote(o.output), o.shards,
                        o.truthCache.empty() ? "" : " --truth-cache " + shellQuote(o.truthCache));
    return text;
}

std::string kubernetesManifest(const EmitOptions& o) {
    std::string args = fmt::format("[{}, {}, {}, {}, {}, {}", yamlQuote("sweep"), yamlQuote(o.plan),
                                   yamlQuote("-o"), yamlQuote(o.output), yamlQuote("--task-count"),
                                   yamlQuote(std::to_string(o.shards)));
    if (!o.truthCache.empty())
        args += fmt::format(", {}, {}", yamlQuote("--truth-cache"), yamlQuote(o.truthCache));
    args += "]";
    std::string text;
    text +=
        "# An Indexed Job: completion index i runs shard i (sweep reads JOB_COMPLETION_INDEX).\n";
    text += "apiVersion: batch/v1\n";
    text += "kind: Job\n";
    text += "metadata:\n";
    text += fmt::format("  name: {}\n", o.jobName);
    text += "spec:\n";
    text += "  completionMode: Indexed\n";
    text += fmt::format("  completions: {}\n", o.shards);
    text += fmt::format("  parallelism: {}\n", o.shards);
    text += fmt::format("  backoffLimit: {}\n", 3 * o.shards);
    text += "  template:\n";
    text += "    spec:\n";
    text += "      restartPolicy: Never\n";
    text += "      containers:\n";
    text += "        - name: penumbra\n";
    text += fmt::format("          image: {}\n", yamlQuote(o.image));
    text += fmt::format("          command: [{}]\n", yamlQuote(o.penumbra));
    text += fmt::format("          args: {}\n", args);
    if (o.gpus > 0) {
        text += "          resources:\n";
        text += "            limits:\n";
        text += fmt::format("              nvidia.com/gpu: {}\n", o.gpus);
    }
    text += "          volumeMounts:\n";
    text += "            - name: data\n";
    text += fmt::format("              mountPath: {}\n", yamlQuote(o.mount));
    text += "      volumes:\n";
    text += "        - name: data\n";
    text += "          persistentVolumeClaim:\n";
    text += fmt::format("            claimName: {}\n", yamlQuote(o.volumeClaim));
    return text;
}

} // namespace penumbra::sweep
