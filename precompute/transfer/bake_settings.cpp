// The bake's settings per preset (transfer.h), apart from the bake itself: the scene parser needs
// them, and programs that read scenes without baking (the bench runner) must not link Embree.
#include "core/error.h"
#include "transfer/transfer.h"

#include <string>

namespace meadow::transfer {

BakeSettings bakeSettingsForPreset(const std::string& preset) {
    BakeSettings settings;
    if (preset == "full")
        return settings;
    if (preset == "ci") {
        settings.raysPerVertex = 128;
        settings.bounces = 1;
        settings.groundGridResolution = 12;
        settings.groundRaysPerPoint = 128;
        return settings;
    }
    throw Error("transfer bake: unknown preset '" + preset + "' (expected ci or full)");
}

} // namespace meadow::transfer
