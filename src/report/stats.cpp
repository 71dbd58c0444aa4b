#include "report/stats.h"

#include "core/virtual_maps.h"

#include "report/html_report.h"
#include "scene/first_picture.h"
#include "shadows/layer.h"

#include <fmt/format.h>

namespace penumbra {
namespace {

nlohmann::json vec(const glm::vec3& v) {
    return {v.x, v.y, v.z};
}

} // namespace

std::string visibilityFileStem(size_t index) {
    return index == 0 ? "visibility" : fmt::format("visibility_{}", index);
}

nlohmann::json deviceJson(const DeviceInfo& device) {
    return {{"index", device.index},
            {"name", device.name},
            {"type", device.type},
            {"driver", device.driverName},
            {"driver_info", device.driverInfo},
            {"vulkan", device.apiVersion},
            // pcf.filter=hardware runs by hand (same maths) without linear depth filtering.
            {"hardware_depth_filter", device.depthLinearFilter}};
}

// The command line's scene control, as given (stats.json's scene.edits; empty: none).
nlohmann::json sceneEditsJson(const SceneEdits& e) {
    nlohmann::json j = nlohmann::json::object();
    if (e.sunDirection)
        j["sun_dir"] = vec(*e.sunDirection);
    for (const auto& [name, position] : e.lightPositions)
        j["light_pos"][name] = vec(position);
    for (const auto& [name, direction] : e.lightDirections)
        j["light_dir"][name] = vec(direction);
    if (e.cameraPosition)
        j["camera_pos"] = vec(*e.cameraPosition);
    if (e.lookAt)
        j["look_at"] = vec(*e.lookAt);
    if (e.fovDegrees)
        j["fov_degrees"] = *e.fovDegrees;
    for (const AddedLight& added : e.addedLights)
        j["add_light"].push_back(added.text);
    if (e.view)
        j["view"] = viewChoiceName(*e.view);
    if (e.ground)
        j["ground"] = true;
    if (e.noGround)
        j["no_ground"] = true;
    if (e.doubleSided)
        j["double_sided"] = true;
    return j;
}

nlohmann::json viewJson(const Scene& scene, const Camera& camera) {
    const PictureMeasure view = measurePicture(scene, camera);
    return {{"cast_shadow", view.castShadow}, {"subject", view.subject}};
}

nlohmann::json renderStats(const RenderRun& run) {
    const RenderOptions& o = run.options;
    const Bounds bounds = run.scene.bounds();
    const Camera camera = run.scene.camera(o.camera);
    nlohmann::json j;
    j["device"] = deviceJson(run.device);
    j["scene"] = {{"source", run.sceneSpec},
                  {"name", run.scene.name},
                  {"triangles", run.scene.triangleCount()},
                  {"vertices", run.scene.vertices.size()},
                  {"lights", run.scene.lights.size()},
                  {"bounds", {{"min", vec(bounds.min)}, {"max", vec(bounds.max)}}}};
    j["camera"] = {{"name", camera.name},
                   {"position", vec(camera.position)},
                   {"target", vec(camera.target)},
                   {"yfov_degrees", glm::degrees(camera.yfov)}};
    j["scene"]["default_light"] = run.scene.defaultLight;
    j["scene"]["automatic_ground"] = run.scene.automaticGround;
    // The pose (issue 59): the animation and the time it is posed at (null: at rest).
    j["scene"]["animation"] = run.scene.animation;
    j["scene"]["animation_duration"] = run.scene.animationDuration;
    j["scene"]["time"] = run.scene.time ? nlohmann::json(*run.scene.time) : nlohmann::json();
    j["view"] = run.view ? *run.view : viewJson(run.scene, camera);
    j["scene"]["edits"] = sceneEditsJson(run.scene.edits);
    j["image"] = {{"width", o.width}, {"height", o.height}};
    j["shadow_map_size"] = o.shadowMapSize;
    j["technique"] = techniqueName(o.technique);
    nlohmann::json params = nlohmann::json::object();
    for (const ParameterInfo& p : allParameters()) {
        if (p.type == ParameterType::Choice || p.type == ParameterType::Bool)
            params[std::string(p.key)] = o.parameters.text(p.key);
        else
            params[std::string(p.key)] = o.parameters.number(p.key);
    }
    j["parameters"] = params;
    j["exposure_ev"] = run.result.exposure;
    j["exposure"] = o.parameters.isSet("composite.exposure") ? "composite.exposure" : "automatic";
    if (const auto& f = run.result.field) {
        nlohmann::json passes = nlohmann::json::object();
        for (const PassTime& p : f->buildPasses)
            passes[p.pass] = p.medianMs;
        j["distance_field"] = {{"voxels", {f->voxels.x, f->voxels.y, f->voxels.z}},
                               {"voxel_size", f->voxelSize},
                               {"origin", vec(f->origin)},
                               {"bytes", f->bytes},
                               {"triangles", f->triangles},
                               {"field_triangles", f->fieldTriangles},
                               {"open_field_triangles", f->openTriangles},
                               {"alpha_tested_triangles", f->alphaTriangles},
                               {"alpha_tested_pieces", f->alphaPieces},
                               {"build_gpu_ms", f->buildGpuMs},
                               {"build_cpu_ms", f->buildCpuMs},
                               {"build_passes_ms", passes},
                               {"built_for_this_render", f->built}};
    }
    if (const auto& v = run.result.virtualMaps)
        j["virtual_maps"] = {
            {"pages_requested", v->requested},
            {"pages_resident", v->resident},
            {"pages_rendered", v->rendered},
            {"pages_cached", v->cached},
            {"pages_static_held", v->staticHeld},
            {"pages_dropped", v->dropped},
            {"pages_evicted", v->evicted},
            {"pool_pages", v->poolPages},
            {"pool_occupancy", v->poolPages ? double(v->resident) / v->poolPages : 0.0},
            {"pool_bytes", v->poolBytes},
            {"page_table_bytes", v->tableBytes},
            {"page_size", v->pageSize},
            {"virtual_size", v->virtualSize},
            {"level_bias", v->levelBias},
            {"pages_rendered_per_frame", v->renderedPerFrame},
            {"frames_short_of_pool", v->droppedFrames}};
    nlohmann::json lights = nlohmann::json::array();
    for (const LightShadow& s : run.result.lights) {
        const Light& l = run.scene.lights[s.sceneLight];
        nlohmann::json light = {{"name", l.name},
                                {"type", lightTypeName(l.type)},
                                {"casts_shadow", s.visibilityIndex >= 0},
                                {"projection", s.projection}};
        if (l.type != LightType::Point)
            light["direction"] = vec(l.direction); // the direction light travels
        if (l.type != LightType::Directional)
            light["position"] = vec(l.position);
        if (l.type == LightType::Directional)
            light["angular_diameter_degrees"] =
                o.lightAngleOverride >= 0 ? o.lightAngleOverride : l.angularDiameter;
        else
            light["radius"] = o.lightRadiusOverride >= 0 ? o.lightRadiusOverride : l.radius;
        if (s.visibilityIndex >= 0) {
            light["visibility_file"] = visibilityFileStem(static_cast<size_t>(s.visibilityIndex)) +
                                       "." + std::string(run.floatExtension);
            // The first view's (the only one's for suns and spots), as before views were listed.
            light["near"] = s.views.front().nearPlane;
            light["far"] = s.views.front().farPlane;
            light["texel_world_size"] = s.views.front().texelWorldSize;
            if (l.type == LightType::Point)
                light["guard_texels"] = s.guardTexels;
            nlohmann::json views = nlohmann::json::array();
            for (const ShadowViewInfo& v : s.views) {
                nlohmann::json view = {{"layer", v.layer},
                                       {"projection", v.projection},
                                       {"near", v.nearPlane},
                                       {"far", v.farPlane},
                                       {"texel_world_size", v.texelWorldSize}};
                if (!v.name.empty())
                    view["face"] = v.name;
                if (v.projection == "perspective")
                    view["fov_degrees"] = v.fovDegrees;
                if (v.cascade) // camera view distances: the slice this cascade serves
                    view["cascade"] = {{"split_near", v.splitNear},
                                       {"split_far", v.splitFar},
                                       {"blend_start", v.blendStart},
                                       {"kernel_scale", v.kernelScale}};
                // Column-major, as GLM and GLSL store it: world -> (u, v, depth) * w.
                nlohmann::json matrix = nlohmann::json::array();
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r)
                        matrix.push_back(v.worldToShadow[c][r]);
                view["world_to_shadow"] = matrix;
                views.push_back(view);
            }
            light["views"] = views;
        }
        lights.push_back(light);
    }
    j["lights"] = lights;
    j["frames"] = {
        {"timed", o.frames},
        {"warm_up", shadows::warmUpFrames(o.parameters, run.result.virtualMaps.has_value())}};
    if (run.fps > 0.0) // each timed frame a pose of its own; the first warmed up, the rest not
        j["frames"]["fps"] = run.fps;
    nlohmann::json gpu = nlohmann::json::object(), perFrame = nlohmann::json::object();
    double total = 0.0;
    for (const PassTime& p : run.result.passes) {
        gpu[p.pass] = p.medianMs;
        perFrame[p.pass] = p.frameMs;
        total += p.medianMs;
    }
    gpu["total"] = total;
    j["gpu_ms"] = gpu;
    j["gpu_ms_by_cost"] = gpuMsByCost(run.result.passes);
    j["gpu_ms_per_frame"] = perFrame;
    j["transient_memory"] = {{"separate_bytes", run.result.transientMemory.separateBytes},
                             {"shared_bytes", run.result.transientMemory.sharedBytes}};
    return j;
}

} // namespace penumbra
