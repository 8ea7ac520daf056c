#include "app/session.h"

#include "core/error.h"

#include <cstdio>

namespace meadow {

const char* const kSceneAndEngineOptionsHelp = R"(  --preset ci|full      scene preset (default full)
  --seed S              override the scene's seed
  --device N|NAME       Vulkan device by index or part of its name (or MEADOW_DEVICE)
  --validation          run under the Khronos validation layer, synchronization validation
                        included (or MEADOW_VALIDATION=1); exits 3 if it reports anything
  --verbose             say which device is used
)";

const char* const kFieldOptionsHelp =
    R"(  --far-radius PX       the far field: below this projected radius (px) a clump is drawn as
                        surface-sample splats instead of its last mesh LOD, with the same
                        crossfade as the LODs; a radius above a LOD's switch skips that LOD
                        (default 28 at the default --lod-tolerance, scaled with it; 0: off)
  --lod0                every clump at full detail (LOD 0), no far field: the reference the
                        levels of detail and the far field approximate
  --far-lod0            the clumps the far field would take are drawn as LOD 0 meshes instead,
                        everything else as with the far field (the far field's own reference);
                        --debug-lod shows them in the far field's colour
  --lod-tolerance PX    the screen-space error at which each coarser LOD takes over: its RMS
                        distance from the full mesh, in pixels (default 0.3; 0.05 to 4). Larger
                        is faster and coarser: the switch radii scale with it
  --near-raster on|off  the mesh LODs of instances below 256 px drawn triangle by triangle in
                        compute passes instead of the graphics pipeline (default on; off: every
                        mesh through the graphics pipeline)
)";

void addFieldOptions(CommandSpec& spec) {
    spec.valueOptions.insert("--far-radius");
    spec.switchOptions.insert("--lod0");
    spec.switchOptions.insert("--far-lod0");
    spec.valueOptions.insert("--lod-tolerance");
    spec.valueOptions.insert("--near-raster");
}

FieldOptions fieldOptionsFromArgs(const ParsedArgs& args) {
    FieldOptions options;
    options.lodTolerance = args.f32("--lod-tolerance", kDefaultLodTolerancePixels, 0.05f, 4.0f);
    options.lod0 = args.has("--lod0");
    if (options.lod0 && args.has("--lod-tolerance"))
        throw Error("meadow " + args.command +
                    ": --lod0 draws every clump at full detail, so no LOD takes over: leave out --lod-tolerance");
    float farRadius = args.f32("--far-radius", 0.0f, 0.0f, 1000.0f);
    if (options.lod0 && farRadius > 0.0f)
        throw Error("meadow " + args.command +
                    ": --lod0 draws every clump at full detail, without a far field: "
                    "leave out --far-radius");
    // Left out: the default radius, which keeps its place among the LOD switches (field_content.h).
    options.farRadius = args.has("--far-radius") || options.lod0 ? farRadius : defaultFarRadius(options.lodTolerance);
    options.farLod0 = args.has("--far-lod0");
    if (options.lod0 && options.farLod0)
        throw Error("meadow " + args.command +
                    ": --lod0 draws every clump at full detail, without a far field: leave out --far-lod0");
    if (options.farLod0 && !(options.farRadius > 0.0f))
        throw Error("meadow " + args.command +
                    ": --far-lod0 draws the far field's clumps as LOD 0 meshes: it needs the far field, "
                    "which --far-radius 0 turns off");
    if (std::optional<std::string> near = args.value("--near-raster")) {
        if (*near != "on" && *near != "off")
            throw Error("meadow " + args.command + ": --near-raster '" + *near + "' is not on or off");
        options.nearRaster = *near == "on";
        if (options.lod0 && options.nearRaster)
            throw Error(
                "meadow " + args.command +
                ": --lod0 draws every clump at full detail through the graphics pipeline (the reference the near "
                "raster is checked against): leave out --near-raster");
    }
    return options;
}

void applyFieldOptions(const FieldOptions& options, std::vector<FieldClump>& clumps, FieldScenery& scenery) {
    scenery.lod.farRadius = options.farRadius;
    scenery.farAsLod0 = options.farLod0;
    scenery.nearRaster = options.nearRaster;
    if (options.lod0) {
        scenery.lodCount = 1;
        for (FieldClump& clump : clumps)
            clump.lods.resize(1);
    }
}

void addEngineOptions(CommandSpec& spec) {
    spec.valueOptions.insert("--device");
    spec.switchOptions.insert("--validation");
    spec.switchOptions.insert("--verbose");
}

void addSceneOptions(CommandSpec& spec) {
    spec.valueOptions.insert("--preset");
    spec.valueOptions.insert("--seed");
}

Scene sceneFromArgs(const ParsedArgs& args) {
    std::optional<uint64_t> seed;
    if (args.has("--seed"))
        seed = args.u64("--seed", 0);
    return loadScene(args.positionals.at(0), args.value("--preset").value_or("full"), seed);
}

ContextOptions contextOptionsFromArgs(const ParsedArgs& args) {
    ContextOptions options;
    options.validation = args.has("--validation") || validationRequestedByEnvironment();
    options.deviceOverride = args.value("--device").value_or("");
    options.verbose = args.has("--verbose");
    return options;
}

Camera cameraFromArgs(const ParsedArgs& args, const Scene& scene) {
    Camera camera;
    camera.eye = scene.camera.eye;
    camera.target = scene.camera.target;
    camera.fovYDegrees = scene.camera.fovYDegrees;
    if (auto v = args.floats("--camera", 6)) {
        camera.eye = {(*v)[0], (*v)[1], (*v)[2]};
        camera.target = {(*v)[3], (*v)[4], (*v)[5]};
        if (glm::length(camera.target - camera.eye) < 1e-3f)
            throw Error("meadow " + args.command + ": --camera: the target must differ from the eye");
    }
    return camera;
}

std::optional<CameraPath> cameraPathFromArgs(const ParsedArgs& args) {
    std::optional<std::string> file = args.value("--camera-path");
    if (!file)
        return std::nullopt;
    if (args.has("--camera"))
        throw Error("meadow " + args.command + ": --camera and --camera-path both set the camera; give one");
    return loadCameraPath(*file);
}

int validationExitStatus(const Context& ctx) {
    if (!ctx.validationEnabled)
        return 0;
    const ValidationCounter& v = *ctx.validation;
    std::fprintf(
        stderr,
        "meadow: validation layer on (synchronization validation included): %u messages (%u errors, %u warnings)\n",
        v.total(), v.errors.load(), v.warnings.load());
    return v.total() == 0 ? 0 : kExitValidationFailed;
}

} // namespace meadow
