// `import penumbra`: a scene held on the device, rendered any number of times from Python, the
// results as NumPy arrays over Penumbra's own buffers; the ground truth and the metrics
// `compare` writes. Errors are the CLI's one-line messages as Python exceptions (InputError is a
// ValueError, DeviceError a RuntimeError); parameters are checked before anything reaches the
// device. The GIL is released while the device or Embree works.
#include "arrays.h"
#include "cli_options.h"
#include "penumbra/error.h"
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "reference/field_refusal.h"
#include "report/blur_band.h"
#include "report/html_report.h"
#include "report/light_mask.h"
#include "scene/first_picture.h"
#include "shadows/technique.h"

#include <pybind11/stl.h>

#include <fmt/format.h>

#include <array>
#include <optional>

namespace penumbra::python {
namespace {

using Vec3 = std::array<float, 3>;

py::object fromJson(const nlohmann::json& j) {
    return py::module_::import("json").attr("loads")(j.dump());
}

glm::vec3 toVec(const Vec3& v) {
    return {v[0], v[1], v[2]};
}

std::vector<float> toList(const glm::vec3& v) {
    return {v.x, v.y, v.z};
}

struct PyScene {
    std::shared_ptr<Scene> scene;
    std::vector<std::string> warnings;
    bool noGround = false; // load's no_ground holds for every edit after it

    // As the CLI loads a scene without scene options: the automatic ground unless noGround.
    static PyScene load(const std::string& path, uint64_t maxFileSize, uint64_t maxTriangles,
                        bool noGround, std::optional<double> time, const std::string& animation) {
        PyScene s;
        s.scene = std::make_shared<Scene>(loadScene(path, {.maxFileSize = maxFileSize,
                                                           .maxTriangles = maxTriangles,
                                                           .warnings = &s.warnings,
                                                           .time = time,
                                                           .animation = animation}));
        s.noGround = noGround;
        applySceneEdits(*s.scene, {.noGround = noGround});
        if (s.scene->automaticGround)
            s.warnings.push_back(automaticGroundNote(*s.scene));
        return s;
    }
    static PyScene builtin(const std::string& name, bool noGround) {
        return load(name.starts_with("builtin:") ? name : "builtin:" + name, uint64_t{1} << 30,
                    100'000'000, noGround, std::nullopt, "");
    }

    // The CLI's scene options (--sun-dir, --light-pos, --light-dir, --camera-pos, --look-at,
    // --fov), applied in place; the same checks and messages.
    void edit(std::optional<Vec3> sunDir, std::map<std::string, Vec3> lightPos,
              std::map<std::string, Vec3> lightDir, std::optional<Vec3> cameraPos,
              std::optional<Vec3> lookAt, std::optional<float> fov,
              const std::vector<std::string>& addLight, std::optional<std::string> view,
              bool ground, bool doubleSided) {
        SceneEdits edits{
            .ground = ground, .noGround = noGround && !ground, .doubleSided = doubleSided};
        if (view)
            edits.view = parseViewChoice(*view);
        for (const std::string& text : addLight)
            edits.addedLights.push_back(parseAddedLight(text));
        if (sunDir)
            edits.sunDirection = toVec(*sunDir);
        for (const auto& [name, v] : lightPos)
            edits.lightPositions.emplace_back(name, toVec(v));
        for (const auto& [name, v] : lightDir)
            edits.lightDirections.emplace_back(name, toVec(v));
        if (cameraPos)
            edits.cameraPosition = toVec(*cameraPos);
        if (lookAt)
            edits.lookAt = toVec(*lookAt);
        edits.fovDegrees = fov;
        Scene edited = *scene; // all or nothing: a refused edit leaves the scene as it was
        applySceneEdits(edited, edits);
        *scene = std::move(edited);
    }

    py::list lights() const {
        py::list out;
        for (const Light& l : scene->lights) {
            py::dict d;
            d["name"] = l.name;
            d["type"] = std::string(lightTypeName(l.type));
            d["position"] = toList(l.position);
            d["direction"] = toList(l.direction);
            d["color"] = toList(l.color);
            d["intensity"] = l.intensity;
            d["radius"] = l.radius;
            d["angular_diameter"] = l.angularDiameter;
            d["casts_shadow"] = castsShadowMap(l);
            out.append(d);
        }
        return out;
    }
};

// A render: the C++ result, shared with the arrays that view it, and what it was made with.
struct PyResult {
    std::shared_ptr<RenderResult> result;
    std::shared_ptr<const Scene> lit; // the scene with the light sizes the render used
    RenderOptions options;
    std::string name; // the row, e.g. "pcf[box7]"

    // Per pass, and "total" as metrics.json sums it: the passes' medians (not the median of
    // the frames' sums).
    py::dict gpuMs() const {
        py::dict d;
        double total = 0.0;
        for (const PassTime& p : result->passes) {
            d[py::str(p.pass)] = p.medianMs;
            total += p.medianMs;
        }
        d["total"] = total;
        return d;
    }
    // Per pass, and "total": each frame's passes summed.
    py::dict gpuMsPerFrame() const {
        py::dict d;
        std::vector<double> total;
        for (const PassTime& p : result->passes) {
            d[py::str(p.pass)] = p.frameMs;
            total.resize(std::max(total.size(), p.frameMs.size()), 0.0);
            for (size_t f = 0; f < p.frameMs.size(); ++f) // checked: a bound off by one throws
                total.at(f) += p.frameMs.at(f);
        }
        d["total"] = total;
        return d;
    }
    py::dict parameters() const {
        py::dict d;
        for (const auto& [key, value] : options.parameters.all())
            d[py::str(key)] = options.parameters.text(key);
        return d;
    }
    py::list lights() const {
        py::list out;
        for (const LightShadow& s : result->lights) {
            py::dict d;
            d["name"] = lit->lights[s.sceneLight].name;
            d["visibility_index"] = s.visibilityIndex;
            d["projection"] = s.projection;
            out.append(d);
        }
        return out;
    }
};

struct PyTruth {
    std::shared_ptr<ReferenceResult> truth;
    uint32_t samples = 0;
};

// "pcf_size" -> "pcf.size", "msm_soft_bias" -> "msm-soft.bias": the longest family whose name
// (with '_' for '-') starts the keyword.
std::string parameterKey(const std::string& keyword) {
    std::string best;
    for (const ParameterInfo& p : allParameters()) {
        std::string family(p.key.substr(0, p.key.find('.')));
        std::string spelled = family;
        std::replace(spelled.begin(), spelled.end(), '-', '_');
        if (keyword.size() > spelled.size() && keyword.starts_with(spelled + "_") &&
            family.size() > best.size())
            best = family;
    }
    if (best.empty())
        throw InputError(keyword, "not a parameter keyword (family_name, e.g. pcf_size; "
                                  "penumbra.techniques() lists them)");
    return best + "." + keyword.substr(best.size() + 1);
}

// A Python value as `--set` would spell it.
std::string parameterText(const py::handle& value) {
    if (py::isinstance<py::bool_>(value))
        return value.cast<bool>() ? "true" : "false";
    return py::str(value).cast<std::string>();
}

class PyRenderer {
public:
    PyRenderer(const PyScene& scene, uint32_t width, uint32_t height, int device, bool validation,
               uint32_t shadowMapSize, std::string camera, std::optional<float> lightRadius,
               std::optional<float> lightAngle) {
        mBase.width = width;
        mBase.height = height;
        mBase.shadowMapSize = shadowMapSize;
        mBase.camera = std::move(camera);
        if (lightRadius && !(*lightRadius >= 0.0f))
            throw InputError("light_radius", "must be at least 0");
        if (lightAngle && !(*lightAngle >= 0.0f && *lightAngle <= 30.0f))
            throw InputError("light_angle", "must be 0 to 30 degrees");
        mBase.lightRadiusOverride = lightRadius.value_or(-1.0f);
        mBase.lightAngleOverride = lightAngle.value_or(-1.0f);
        validate(mBase); // sizes and the rest, before any device work
        auto lit = std::make_shared<Scene>(*scene.scene);
        applyLightSizeOverrides(*lit, mBase.lightRadiusOverride, mBase.lightAngleOverride);
        mLit = std::move(lit);
        py::gil_scoped_release release;
        mRenderer = std::make_unique<Renderer>(
            DeviceOptions{.deviceIndex = device, .validation = validation});
        mRenderer->check(*scene.scene, mBase);
        mScene = std::make_unique<SceneRenderer>(*mRenderer, *scene.scene);
    }

    PyResult render(const std::string& technique, const py::dict& params, uint32_t frames,
                    const py::kwargs& keywords) {
        const TechniqueRow row = cli::rowNamed(technique, "technique");
        std::vector<std::string> sets;
        for (const auto& [key, value] : params)
            sets.push_back(py::str(key).cast<std::string>() + "=" + parameterText(value));
        for (const auto& [key, value] : keywords)
            sets.push_back(parameterKey(py::str(key).cast<std::string>()) + "=" +
                           parameterText(value));
        RenderOptions base = mBase;
        base.frames = frames;
        RenderOptions options = cli::optionsFor(base, row, sets); // checked: InputError
        if (!row.layers.empty()) // the layers it names, as compare runs them (the others off)
            applyRow(row, options.parameters, mScene->scene().bounds().radius());
        mScene->check(options);
        auto result = std::make_shared<RenderResult>();
        {
            py::gil_scoped_release release;
            *result = mScene->render(options);
            refuseUnheldField(*mScene, options, *result); // sdf.refuse: an InputError
        }
        failOnValidation();
        return {result, mLit, options, row.name};
    }

    PyTruth reference(uint32_t samples, const std::string& embreeConfig, const PyResult* gbuffer) {
        const ReferenceOptions options{.samples = samples, .embreeConfig = embreeConfig};
        validate(options);
        auto truth = std::make_shared<ReferenceResult>();
        py::gil_scoped_release release;
        std::shared_ptr<RenderResult> view;
        if (gbuffer) {
            if (gbuffer->lit != mLit)
                throw InputError("gbuffer", "a render of another renderer");
            view = gbuffer->result;
        } else {
            RenderOptions o = mBase;
            o.frames = 1;
            view = std::make_shared<RenderResult>(mScene->render(o));
        }
        *truth = computeReference(*mLit, *view, options);
        {
            py::gil_scoped_acquire acquire;
            failOnValidation();
        }
        return {truth, samples};
    }

    py::dict device() const {
        const DeviceInfo& d = mRenderer->device();
        py::dict out;
        out["index"] = d.index;
        out["name"] = d.name;
        out["type"] = d.type;
        out["driver"] = d.driverName + " " + d.driverInfo;
        out["vulkan"] = d.apiVersion;
        out["device_local_bytes"] = d.deviceLocalBytes;
        return out;
    }
    uint64_t deviceMemoryInUse() const { return mRenderer->deviceMemoryInUse().bytes; }

private:
    void failOnValidation() {
        if (mRenderer->validationErrors() > mValidationErrors) {
            mValidationErrors = mRenderer->validationErrors();
            throw DeviceError(fmt::format("vulkan validation: {} error(s), see messages above",
                                          mValidationErrors));
        }
    }

    RenderOptions mBase;
    std::shared_ptr<const Scene> mLit;
    std::unique_ptr<Renderer> mRenderer;
    std::unique_ptr<SceneRenderer> mScene;
    uint32_t mValidationErrors = 0;
};

// The metrics `compare` writes for a row (metrics.json's entry), from the arrays as they are.
py::object metrics(const PyResult& r, const PyTruth& t) {
    const RenderResult& result = *r.result;
    const ReferenceResult& truth = *t.truth;
    if (truth.width != result.width || truth.height != result.height ||
        truth.visibility.size() != result.visibility.size())
        throw InputError("metrics",
                         fmt::format("the truth ({}x{}, {} light(s)) is not of this "
                                     "render's view ({}x{}, {} light(s))",
                                     truth.width, truth.height, truth.visibility.size(),
                                     result.width, result.height, result.visibility.size()));
    std::vector<std::vector<uint8_t>> masks;
    for (const LightShadow& s : result.lights)
        if (s.visibilityIndex >= 0)
            masks.push_back(lightMask(r.lit->lights[s.sceneLight], result));
    const shadows::TechniqueModule& module = shadows::moduleOf(r.options.technique);
    const double blur =
        module.blurRadiusTexels ? module.blurRadiusTexels(r.options.parameters) : 0.0;
    ReportRow row{.name = r.name,
                  .technique = std::string(techniqueName(r.options.technique)),
                  .metrics = metricsAgainstTruth(*r.lit, result, truth.visibility, masks, blur,
                                                 truth.occluderDistance)};
    row.gpuMs = result.passes;
    row.rmsePerChannel = firstLightRmsePerChannel(result, truth.transmittance, masks);
    return fromJson(metricsRowJson(row));
}

} // namespace
} // namespace penumbra::python

PYBIND11_MODULE(penumbra, m) {
    using namespace penumbra;
    using namespace penumbra::python;
    m.doc() = "Penumbra: shadow techniques rendered on the device and measured against a "
              "ray-traced truth, as NumPy arrays (docs/python.md).";
    py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
    py::register_exception<DeviceError>(m, "DeviceError", PyExc_RuntimeError);

    py::class_<PyScene>(m, "Scene", "A scene in memory: a glTF file or a built-in scene.")
        .def_static("load", &PyScene::load, py::arg("path"),
                    py::arg("max_file_size") = uint64_t{1} << 30,
                    py::arg("max_triangles") = uint64_t{100'000'000}, py::arg("no_ground") = false,
                    py::arg("time") = py::none(), py::arg("animation") = "",
                    "Loads a glTF 2.0 file (.gltf, .glb) as the CLI does: a ground is added "
                    "when it puts a cast shadow in view (warnings says so) unless no_ground; "
                    "time (seconds) poses it in the animation named or numbered by animation "
                    "(the first by default), as --time and --animation do. Raises InputError "
                    "naming the file or the option.")
        .def_static("builtin", &PyScene::builtin, py::arg("name"), py::arg("no_ground") = false,
                    "A built-in scene: 'demo', 'showcase', ... (or 'builtin:demo').")
        .def("edit", &PyScene::edit, py::kw_only(), py::arg("sun_dir") = py::none(),
             py::arg("light_pos") = std::map<std::string, Vec3>{},
             py::arg("light_dir") = std::map<std::string, Vec3>{},
             py::arg("camera_pos") = py::none(), py::arg("look_at") = py::none(),
             py::arg("fov") = py::none(), py::arg("add_light") = std::vector<std::string>{},
             py::arg("view") = py::none(), py::arg("ground") = false,
             py::arg("double_sided") = false,
             "The CLI's scene options, in place: sun_dir adds a sun (or replaces the default "
             "light), light_pos / light_dir move and aim lights by name, camera_pos and look_at "
             "(with fov) make an ad-hoc camera, add_light adds lights as --add-light does "
             "('point:pos=0,3,0,radius=0.2'), view ('auto', 'exterior', 'interior'), ground and "
             "double_sided as --view, --ground and --double-sided do. All or nothing; InputError "
             "names the option.")
        .def_property_readonly("name", [](const PyScene& s) { return s.scene->name; })
        .def_property_readonly(
            "time", [](const PyScene& s) { return s.scene->time; },
            "The seconds into its animation the scene is posed at; None at rest.")
        .def_property_readonly(
            "animation", [](const PyScene& s) { return s.scene->animation; },
            "The animation time poses (its name, else its index); '' without animations.")
        .def_property_readonly(
            "animation_duration", [](const PyScene& s) { return s.scene->animationDuration; },
            "That animation's length in seconds (its last keyframe); 0 without animations.")
        .def_property_readonly("triangles",
                               [](const PyScene& s) { return s.scene->triangleCount(); })
        .def_property_readonly("lights", &PyScene::lights,
                               "Every light as a dict: name, type, position, direction, color, "
                               "intensity, radius, angular_diameter, casts_shadow.")
        .def_property_readonly("cameras",
                               [](const PyScene& s) {
                                   std::vector<std::string> names;
                                   for (const Camera& c : s.scene->cameras)
                                       names.push_back(c.name);
                                   return names;
                               })
        .def_property_readonly(
            "warnings", [](const PyScene& s) { return s.warnings; },
            "What the loader skipped, one line each.");

    py::class_<PyResult>(m, "Result", "One render: arrays over the renderer's own output.")
        .def_property_readonly(
            "image",
            [](const PyResult& r) {
                return viewOf(r.result->image, {r.result->height, r.result->width, py::ssize_t(4)},
                              r.result);
            },
            "(height, width, 4) uint8: the lit image, sRGB, rows top to bottom.")
        .def_property_readonly(
            "visibility",
            [](const PyResult& r) {
                return viewsOf(r.result->visibility, r.result->width, r.result->height, r.result);
            },
            "One (height, width) float32 array per shadow-casting light, in [0, 1] (1 lit), NaN "
            "where there is no geometry.")
        .def_property_readonly(
            "transmittance",
            [](const PyResult& r) {
                return rgbViewsOf(r.result->transmittance, r.result->width, r.result->height,
                                  r.result);
            },
            "With the translucent layer on a scene with translucent casters: one (height, width, "
            "3) float32 array per shadow-casting light, the light that arrives per channel "
            "(linear RGB), whose luminance is visibility; else empty.")
        .def_property_readonly(
            "position",
            [](const PyResult& r) {
                return viewOf(r.result->position,
                              {r.result->height, r.result->width, py::ssize_t(3)}, r.result);
            },
            "(height, width, 3) float32: world-space position, NaN for background.")
        .def_property_readonly(
            "normal",
            [](const PyResult& r) {
                return viewOf(r.result->normal, {r.result->height, r.result->width, py::ssize_t(3)},
                              r.result);
            },
            "(height, width, 3) float32: unit world-space normal, NaN for background.")
        .def_property_readonly("gpu_ms", &PyResult::gpuMs,
                               "GPU milliseconds per pass, the median of the timed frames, and "
                               "'total', their sum (metrics.json's total).")
        .def_property_readonly(
            "gpu_ms_by_cost",
            [](const PyResult& r) { return fromJson(gpuMsByCost(r.result->passes)); },
            "The medians summed by the cost group each pass declares: 'shadow_maps', "
            "'per_pixel', 'frame' (metrics.json's gpu_ms_by_cost).")
        .def_property_readonly("gpu_ms_per_frame", &PyResult::gpuMsPerFrame,
                               "Every timed frame's GPU milliseconds per pass, and 'total', "
                               "each frame's sum.")
        .def_property_readonly("parameters", &PyResult::parameters,
                               "Every parameter in effect, as --set would spell it.")
        .def_property_readonly("lights", &PyResult::lights)
        .def_property_readonly("name", [](const PyResult& r) { return r.name; })
        .def_property_readonly(
            "technique",
            [](const PyResult& r) { return std::string(techniqueName(r.options.technique)); })
        .def_property_readonly("width", [](const PyResult& r) { return r.result->width; })
        .def_property_readonly("height", [](const PyResult& r) { return r.result->height; });

    py::class_<PyTruth>(m, "Truth", "The ray-traced ground truth of a renderer's view.")
        .def_property_readonly(
            "visibility",
            [](const PyTruth& t) {
                return viewsOf(t.truth->visibility, t.truth->width, t.truth->height, t.truth);
            },
            "One (height, width) float32 array per shadow-casting light, as Result.visibility.")
        .def_property_readonly(
            "transmittance",
            [](const PyTruth& t) {
                return rgbViewsOf(t.truth->transmittance, t.truth->width, t.truth->height, t.truth);
            },
            "Where the scene has translucent casters: one (height, width, 3) float32 array per "
            "light, the light that arrives through them per channel; else empty.")
        .def_property_readonly(
            "occluder_distance",
            [](const PyTruth& t) {
                return viewsOf(t.truth->occluderDistance, t.truth->width, t.truth->height, t.truth);
            },
            "Per light: how far the occluder is along the ray to the light's centre (inf: none).")
        .def_property_readonly("samples", [](const PyTruth& t) { return t.samples; })
        .def_property_readonly("rays", [](const PyTruth& t) { return t.truth->rays; })
        .def_property_readonly("seconds", [](const PyTruth& t) { return t.truth->seconds; });

    py::class_<PyRenderer>(m, "Renderer",
                           "A scene uploaded once to a device; renders any number of frames.")
        .def(py::init<const PyScene&, uint32_t, uint32_t, int, bool, uint32_t, std::string,
                      std::optional<float>, std::optional<float>>(),
             py::arg("scene"), py::arg("width") = 1280, py::arg("height") = 720, py::kw_only(),
             py::arg("device") = -1, py::arg("validation") = false,
             py::arg("shadow_map_size") = 2048, py::arg("camera") = "",
             py::arg("light_radius") = py::none(), py::arg("light_angle") = py::none(),
             "Opens the device (-1: a GPU if any, else the software rasterizer) and uploads a "
             "copy of the scene (later edits to the Scene do not reach it). light_radius and "
             "light_angle override every spot/point light's radius and every sun's angular "
             "diameter (degrees), as --light-radius and --light-angle.")
        .def("render", &PyRenderer::render,
             py::arg("technique") = std::string(techniqueName(kDefaultTechnique)),
             py::arg("params") = py::dict(), py::arg("frames") = 5,
             "Renders with a technique or a compare row ('pcf[box7]', 'pcf[box3]+contact'). "
             "Parameters as params={'pcf.size': 7} or keywords pcf_size=7; checked before the "
             "device sees them (InputError). frames: timed frames after one warm-up.")
        .def("reference", &PyRenderer::reference, py::arg("samples") = 256,
             py::arg("embree_config") = "", py::arg("gbuffer") = nullptr,
             "The ray-traced truth of the view (Embree): samples rays per pixel and light for "
             "lights with a size. gbuffer: a render of this renderer whose positions to trace "
             "from (default: a fresh one).")
        .def_property_readonly("device", &PyRenderer::device)
        .def_property_readonly("device_memory_bytes", &PyRenderer::deviceMemoryInUse,
                               "Device memory Penumbra holds now, every renderer together.");

    m.def("metrics", &metrics, py::arg("result"), py::arg("truth"),
          "The metrics `penumbra compare` writes for a row (metrics.json), of the result's "
          "arrays as they are now against the truth.");
    m.def(
        "techniques", [] { return fromJson(cli::techniquesJson()); },
        "Every technique with its parameters, defaults and ranges (penumbra techniques --json).");
}
