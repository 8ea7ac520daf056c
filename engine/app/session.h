// What every command that renders shares: opening the Vulkan context from the command line,
// turning scene + options into a camera and sky, and the validation verdict at exit.
#pragma once

#include "app/args.h"
#include "pipeline/build_library.h"
#include "render/camera.h"
#include "render/camera_path.h"
#include "render/field_content.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace meadow {

// The help lines of the options below (--preset, --seed; --device, --validation, --verbose).
extern const char* const kSceneAndEngineOptionsHelp;

// Options every rendering command accepts.
void addEngineOptions(CommandSpec& spec);
// Options of commands that take a scene (--preset, --seed).
void addSceneOptions(CommandSpec& spec);

// Options of commands that draw the field (render, bench, view): --far-radius PX, --lod0, --far-lod0,
// --lod-tolerance PX, --near-raster on|off.
extern const char* const kFieldOptionsHelp;
void addFieldOptions(CommandSpec& spec);
struct FieldOptions {
    float farRadius = 0.0f; // px; 0: no far field (the command line's default: defaultFarRadius)
    bool lod0 = false;      // every clump at full detail: the reference the LODs and the far field approximate
    bool farLod0 = false;   // the far field's clumps as LOD 0 meshes: the far field's own reference
    float lodTolerance = kDefaultLodTolerancePixels; // px of RMS error where each LOD takes over
    bool nearRaster = true; // the mesh LODs drawn by the near raster (near_raster.h), unless --lod0
};
// Read and checked before any work starts; fieldScenery takes lodTolerance, and applyFieldOptions
// applies the rest to the library's clumps and scenery.
FieldOptions fieldOptionsFromArgs(const ParsedArgs& args);
void applyFieldOptions(const FieldOptions& options, std::vector<FieldClump>& clumps, FieldScenery& scenery);

Scene sceneFromArgs(const ParsedArgs& args);
ContextOptions contextOptionsFromArgs(const ParsedArgs& args);

// The scene's camera, overridden by --camera EX,EY,EZ,TX,TY,TZ.
Camera cameraFromArgs(const ParsedArgs& args, const Scene& scene);

// --camera-path FILE, loaded and checked before any work (none without the option); it and
// --camera both set the camera, so giving both is an error.
std::optional<CameraPath> cameraPathFromArgs(const ParsedArgs& args);

// Prints the validation summary when validation ran; returns the exit status to use: 0, or 3
// when the layer reported anything.
int validationExitStatus(const Context& context);

inline constexpr int kExitValidationFailed = 3;

} // namespace meadow
