#include "commands.h"
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "penumbra/settings.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace penumbra::cli {

Action addInfoCommand(CLI::App& app, const GlobalOptions&) {
    app.add_subcommand("info", "Vulkan devices, drivers and the limits Penumbra relies on");
    return [] {
        const std::vector<DeviceInfo> devices = listDevices();
        if (devices.empty())
            fmt::print("no Vulkan device found\n");
        int best = -1;
        for (const DeviceInfo& d : devices)
            if (d.suitable && (best < 0 || d.type == "discrete GPU"))
                best = static_cast<int>(d.index);
        for (const DeviceInfo& d : devices) {
            fmt::print("device {}{}: {} ({})\n", d.index,
                       static_cast<int>(d.index) == best ? " [default]" : "", d.name, d.type);
            fmt::print("  driver:                {} {}\n", d.driverName, d.driverInfo);
            fmt::print("  Vulkan:                {}\n", d.apiVersion);
            fmt::print("  maxImageDimension2D:   {}  (largest shadow map and image side)\n",
                       d.maxImageDimension2D);
            fmt::print("  compute invocations:   {} per workgroup\n",
                       d.maxComputeWorkGroupInvocations);
            fmt::print("  device-local memory:   {:.1f} GiB\n",
                       static_cast<double>(d.deviceLocalBytes) / (1 << 30));
            fmt::print("  timestamp period:      {} ns\n", d.timestampPeriodNs);
            fmt::print("  D32 linear filtering:  {}\n", d.depthLinearFilter ? "yes" : "no");
            fmt::print("  anisotropic filtering: {}\n",
                       d.maxSamplerAnisotropy > 0 ? fmt::format("up to {}x", d.maxSamplerAnisotropy)
                                                  : std::string("no"));
            fmt::print("  cube-map arrays:       {}\n", d.imageCubeArray ? "yes" : "no");
            fmt::print("  usable by penumbra:    {}\n",
                       d.suitable ? "yes" : "no: " + d.unsuitableReason);
        }
        fmt::print("embree: {}\n", embreeVersion());
        return 0;
    };
}

Action addTechniquesCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("techniques", "every technique and its parameters");
    auto json = std::make_shared<bool>(false);
    cmd->add_flag("--json", *json, "machine-readable output");
    return [json] {
        const nlohmann::json out = techniquesJson();
        if (*json) {
            fmt::print("{}\n", out.dump(2));
            return 0;
        }
        for (const auto& t : out) {
            fmt::print("{}  {}\n  [{}]\n", t["name"].get<std::string>(),
                       t["summary"].get<std::string>(), t["reference"].get<std::string>());
            for (const auto& p : t["parameters"]) {
                std::string range = p.contains("min")
                                        ? fmt::format("[{}, {}]", p["min"].dump(), p["max"].dump())
                                    : p.contains("choices") ? p["choices"].dump()
                                                            : "true|false";
                fmt::print("    --set {}={}  {} {}\n        {}{}\n", p["key"].get<std::string>(),
                           (p["default"].is_string() ? p["default"].get<std::string>()
                                                     : p["default"].dump()),
                           p["type"].get<std::string>(), range, p["description"].get<std::string>(),
                           p["unit"].get<std::string>().empty()
                               ? ""
                               : " (" + p["unit"].get<std::string>() + ")");
            }
        }
        return 0;
    };
}

} // namespace penumbra::cli
