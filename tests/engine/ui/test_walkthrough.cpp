// The walkthrough's CPU side: the fly and walk camera stepped by input frames, the ground height
// under the eye, the scripted input format and the keyboard shortcuts.
#include "core/error.h"
#include "library/terrain.h"
#include "render/field_content.h"
#include "ui/fly_camera.h"
#include "ui/ground_height.h"
#include "ui/input_script.h"
#include "ui/view_controls.h"

#include <GLFW/glfw3.h>
#include <cmath>
#include <gtest/gtest.h>

using namespace meadow;

namespace {

// Positions after a second of motion in float steps: well under a millimetre.
constexpr float kTolerance = 1e-4f;

InputFrame holding(std::initializer_list<int> keys) {
    InputFrame in;
    for (int k : keys)
        in.down[size_t(k)] = true;
    return in;
}

// A flat mesh at height h over [-s, s]^2 (two triangles).
Mesh flatGround(float h, float s) {
    Mesh m;
    for (glm::vec2 c : {glm::vec2(-s, -s), glm::vec2(s, -s), glm::vec2(-s, s), glm::vec2(s, s)})
        m.vertices.push_back({glm::vec4(c.x, h, c.y, 0.0f), glm::vec4(0, 1, 0, 0)});
    m.indices = {0, 2, 1, 1, 2, 3};
    return m;
}

std::string scriptError(const std::string& text) {
    try {
        parseInputScript(text, "script.txt");
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "parsed: " << text;
    return "";
}

} // namespace

TEST(FlyCamera, HoldingWMovesAlongTheViewAtTheSpeed) {
    FlyCamera fly({{0, 5, 0}, {3, 1, 4}}); // looking down a little
    const glm::vec3 start = fly.eye, forward = fly.forward();
    EXPECT_NEAR(glm::length(forward), 1.0f, 1e-6f);
    for (int i = 0; i < 30; ++i)
        fly.update(holding({GLFW_KEY_W}), false, true, 1.0f / 30.0f, nullptr);
    const glm::vec3 moved = fly.eye - start;
    EXPECT_NEAR(glm::length(moved), fly.settings.speed, kTolerance); // 1 s at 5 m/s
    EXPECT_NEAR(glm::dot(glm::normalize(moved), forward), 1.0f, 1e-5f);
}

TEST(FlyCamera, ModifiersScaleTheSpeedAndStrafeIsLevel) {
    FlyCamera fly({{0, 5, 0}, {0, 5, 1}}); // looking along +z: right is -x
    fly.update(holding({GLFW_KEY_D, GLFW_KEY_LEFT_SHIFT}), false, true, 1.0f, nullptr);
    EXPECT_NEAR(fly.eye.x, -25.0f, kTolerance);
    EXPECT_NEAR(fly.eye.y, 5.0f, kTolerance);
    fly.update(holding({GLFW_KEY_E, GLFW_KEY_LEFT_CONTROL}), false, true, 1.0f, nullptr);
    EXPECT_NEAR(fly.eye.y, 6.0f, kTolerance); // up at a fifth of 5 m/s
    // Keys taken by the HUD move nothing.
    fly.update(holding({GLFW_KEY_W}), false, false, 1.0f, nullptr);
    EXPECT_NEAR(fly.eye.z, 0.0f, kTolerance);
}

TEST(FlyCamera, MouseLooksOnlyWhileLookingAndClampsThePitch) {
    FlyCamera fly({{0, 1, 0}, {0, 1, 1}});
    InputFrame in;
    in.mouseDelta = {100.0f, 0.0f};
    fly.update(in, false, true, 0.1f, nullptr);
    EXPECT_EQ(fly.yaw, 0.0f);
    fly.update(in, true, true, 0.1f, nullptr);
    EXPECT_NEAR(fly.yaw, -0.3f, 1e-6f); // dragging right turns right (towards -x)
    EXPECT_LT(fly.forward().x, 0.0f);
    in.mouseDelta = {0.0f, -10000.0f};
    fly.update(in, true, true, 0.1f, nullptr);
    EXPECT_EQ(fly.pitch, kMaxPitch);
    // The pose keeps a target that a camera path accepts.
    CameraPath p;
    p.keyframes = {{0.0, fly.pose().eye, fly.pose().target}};
    EXPECT_NO_THROW(validateCameraPath(p, "pose"));
}

TEST(FlyCamera, WheelScalesTheSpeedWithinLimits) {
    FlyCamera fly({{0, 1, 0}, {0, 1, 1}});
    InputFrame in;
    in.scroll = 2.0f;
    fly.update(in, false, true, 0.0f, nullptr);
    EXPECT_NEAR(fly.settings.speed, 5.0f * 1.5625f, 1e-5f);
    in.scroll = -100.0f;
    fly.update(in, false, true, 0.0f, nullptr);
    EXPECT_EQ(fly.settings.speed, kMinFlySpeed);
}

TEST(FlyCamera, WalkingKeepsEyeHeightOverTheGroundAndIgnoresPitch) {
    const Mesh ground = flatGround(2.0f, 50.0f);
    const GroundHeight height(ground);
    FlyCamera fly({{0, 10, 0}, {0, 0, 10}}); // looking down at 45 degrees
    fly.walk = true;
    fly.settle(&height);
    EXPECT_NEAR(fly.eye.y, 3.7f, kTolerance);
    for (int i = 0; i < 10; ++i)
        fly.update(holding({GLFW_KEY_W, GLFW_KEY_E}), false, true, 0.1f, &height);
    EXPECT_NEAR(fly.eye.z, 5.0f, kTolerance); // the full speed on the level, not cos(45) of it
    EXPECT_NEAR(fly.eye.y, 3.7f, kTolerance); // E does not lift a walker
}

TEST(FlyCamera, FlightStaysAboveTheGround) {
    const GroundHeight height(flatGround(0.0f, 50.0f));
    FlyCamera fly({{0, 1, 0}, {0, 1, 1}});
    fly.update(holding({GLFW_KEY_Q}), false, true, 10.0f, &height);
    EXPECT_NEAR(fly.eye.y, fly.settings.clearance, kTolerance);
    // Beyond the ground there is nothing to stay above.
    fly.eye = {100, 1, 0};
    fly.update(holding({GLFW_KEY_Q}), false, true, 1.0f, &height);
    EXPECT_NEAR(fly.eye.y, -4.0f, kTolerance);
}

TEST(GroundHeight, FollowsTheTerrainMeshAsDrawn) {
    TerrainParams params;
    params.amplitude = 1.0f;
    params.wavelength = 20.0f;
    params.seed = 5;
    const Mesh mesh = makeTerrainMesh(params, glm::vec2(10.0f), 5.0f, 1.0f);
    const GroundHeight ground(mesh);
    const Terrain terrain(params);
    // Exact at the grid's points inside the field (makeTerrainMesh), linear between them: within
    // the curvature over a 1 m cell of a 20 m wavelength hill, a few centimetres.
    for (float x = -9.5f; x <= 9.5f; x += 0.73f)
        for (float z = -9.5f; z <= 9.5f; z += 0.91f) {
            std::optional<float> h = ground.at(x, z);
            ASSERT_TRUE(h) << x << ", " << z;
            EXPECT_NEAR(*h, terrain.height(x, z), 0.05f) << x << ", " << z;
        }
    EXPECT_NEAR(*ground.at(3.0f, -4.0f), terrain.height(3.0f, -4.0f), 1e-5f); // a grid point
    // The plain at -amplitude - 5 cm, out to the horizon ring; nothing beyond it.
    EXPECT_NEAR(*ground.at(300.0f, 40.0f), -1.05f, 1e-5f);
    EXPECT_FALSE(ground.at(5000.0f, 0.0f));
}

// The terrain mesh's grid: a fifth of the finest octave's wavelength, within [0.5, 2] m, and at that
// spacing the bundled field's hills (amplitude 1 m, 40 m, 3 octaves) drawn within 2.5 cm of the
// height the clumps stand on, at three seeds.
TEST(TerrainMesh, SpacingFollowsTheFinestOctave) {
    TerrainParams params; // 1 m, 40 m, 3 octaves: the bundled field's
    EXPECT_FLOAT_EQ(terrainMeshSpacing(params), 2.0f);
    params.octaves = 4;
    EXPECT_FLOAT_EQ(terrainMeshSpacing(params), 1.0f);
    params.octaves = 12;
    EXPECT_FLOAT_EQ(terrainMeshSpacing(params), 0.5f);
    params.octaves = 1;
    params.wavelength = 400.0f;
    EXPECT_FLOAT_EQ(terrainMeshSpacing(params), 2.0f);
    for (uint64_t seed : {0u, 1u, 7u}) {
        TerrainParams bundled;
        bundled.seed = seed;
        const Mesh mesh = makeTerrainMesh(bundled, glm::vec2(30.0f), 20.0f, terrainMeshSpacing(bundled));
        const GroundHeight ground(mesh);
        const Terrain terrain(bundled);
        float worst = 0.0f;
        for (float x = -29.5f; x <= 29.5f; x += 0.173f)
            for (float z = -29.5f; z <= 29.5f; z += 0.191f)
                worst = std::max(worst, std::abs(*ground.at(x, z) - terrain.height(x, z)));
        EXPECT_LT(worst, 0.025f) << "seed " << seed;
        // A 1 m grid lies within about 5 mm: a departure above 8 mm says this is the 2 m one.
        EXPECT_GT(worst, 0.008f) << "seed " << seed;
    }
}

TEST(InputScript, ParsesEveryCommandInFrameOrder) {
    InputScript s = parseInputScript("# a comment\n"
                                     "0 down W   # walk\n"
                                     "0 tap F12\n"
                                     "1 mouse-down right\n"
                                     "1 move 10 -5.5\n"
                                     "2 scroll -2\n"
                                     "3 resize 320 200\n"
                                     "3 minimize 0.5\n"
                                     "4 log\n"
                                     "5 up w\n"
                                     "5 mouse-up right\n"
                                     "6 quit\n",
                                     "script.txt");
    using Kind = ScriptEvent::Kind;
    ASSERT_EQ(s.events.size(), 12u); // the tap is a press and a release
    EXPECT_EQ(s.events[0].kind, Kind::KeyDown);
    EXPECT_EQ(s.events[0].key, GLFW_KEY_W);
    EXPECT_EQ(s.events[1].key, GLFW_KEY_F12);
    EXPECT_EQ(s.events[2].kind, Kind::KeyUp); // the tap's release, at frame 1, before frame 1's lines
    EXPECT_EQ(s.events[2].frame, 1u);
    EXPECT_EQ(s.events[4].amount, glm::vec2(10.0f, -5.5f));
    EXPECT_EQ(s.events[6].width, 320u);
    EXPECT_EQ(s.events[7].seconds, 0.5);
    EXPECT_EQ(s.events[9].key, GLFW_KEY_W); // names are case-insensitive
    EXPECT_EQ(s.events[11].kind, Kind::Quit);

    // Played into an InputState: frame 0 holds W and has pressed F12; frame 1 released F12.
    ScriptPlayer player(s);
    InputState input;
    EXPECT_TRUE(player.advance(0, input).empty());
    InputFrame f0 = input.takeFrame();
    EXPECT_TRUE(f0.held(GLFW_KEY_W));
    EXPECT_TRUE(f0.tapped(GLFW_KEY_F12));
    player.advance(1, input);
    InputFrame f1 = input.takeFrame();
    EXPECT_FALSE(f1.held(GLFW_KEY_F12));
    EXPECT_FALSE(f1.tapped(GLFW_KEY_F12));
    EXPECT_TRUE(f1.button(MouseButton::Right));
    EXPECT_EQ(f1.mouseDelta, glm::vec2(10.0f, -5.5f));
    std::vector<ScriptEvent> window = player.advance(3, input);
    ASSERT_EQ(window.size(), 2u); // resize and minimise are the caller's
    EXPECT_EQ(window[0].kind, Kind::Resize);
    EXPECT_EQ(input.takeFrame().scroll, -2.0f);
    EXPECT_FALSE(player.finished());
    player.advance(100, input);
    EXPECT_TRUE(player.finished());
}

TEST(InputScript, NamesTheLineAndTheProblem) {
    EXPECT_NE(scriptError("0 down W\nfive tap W\n").find("script.txt:2: the frame 'five' is not a whole number"),
              std::string::npos);
    EXPECT_NE(scriptError("3 log\n2 log\n").find("script.txt:2: frame 2 comes after frame 3"), std::string::npos);
    EXPECT_NE(scriptError("0 jump\n").find("script.txt:1: unknown command 'jump'"), std::string::npos);
    EXPECT_NE(scriptError("0 down Hyper\n").find("unknown key 'Hyper'"), std::string::npos);
    EXPECT_NE(scriptError("0 down\n").find("a key name is missing"), std::string::npos);
    EXPECT_NE(scriptError("0 mouse-down thumb\n").find("unknown mouse button 'thumb'"), std::string::npos);
    EXPECT_NE(scriptError("0 move 1 x\n").find("DY 'x' is not a number"), std::string::npos);
    EXPECT_NE(scriptError("0 resize 0 10\n").find("W 0 is outside [1, 16384]"), std::string::npos);
    EXPECT_NE(scriptError("0 resize 10.5 10\n").find("whole numbers"), std::string::npos);
    EXPECT_NE(scriptError("0 quit now\n").find("unexpected 'now'"), std::string::npos);
    EXPECT_NE(scriptError("7\n").find("expected 'FRAME COMMAND [ARGS]'"), std::string::npos);
}

TEST(InputState, CursorMotionIsRelativeAndFramesStartAfresh) {
    InputState input;
    input.cursorEvent(100.0, 100.0); // the first position only sets the origin
    input.cursorEvent(110.0, 95.0);
    input.keyEvent(GLFW_KEY_A, GLFW_PRESS);
    input.keyEvent(GLFW_KEY_A, GLFW_RELEASE); // pressed and released within one frame
    InputFrame f = input.takeFrame();
    EXPECT_EQ(f.mouseDelta, glm::vec2(10.0f, -5.0f));
    EXPECT_TRUE(f.tapped(GLFW_KEY_A));
    EXPECT_FALSE(f.held(GLFW_KEY_A));
    InputFrame g = input.takeFrame();
    EXPECT_EQ(g.mouseDelta, glm::vec2(0.0f));
    EXPECT_FALSE(g.tapped(GLFW_KEY_A));
    input.keyEvent(GLFW_KEY_W, GLFW_PRESS);
    input.releaseAll(); // focus lost
    EXPECT_FALSE(input.takeFrame().held(GLFW_KEY_W));
}

TEST(ViewControls, ShortcutsStepAndToggleWithinRange) {
    ViewControls c;
    c.topWindLevel = 3.0f;
    c.wind.baseLevel = 2.9f;
    c.hours = 23.75;
    InputFrame in;
    for (int k : {GLFW_KEY_RIGHT_BRACKET, GLFW_KEY_PERIOD, GLFW_KEY_L, GLFW_KEY_C, GLFW_KEY_V, GLFW_KEY_F12})
        in.pressed[size_t(k)] = true;
    ViewRequests r = applyShortcuts(in, false, c);
    EXPECT_EQ(c.wind.baseLevel, 3.0f); // clamped to the top level
    EXPECT_NEAR(c.hours, 0.25, 1e-12); // wraps past midnight
    EXPECT_TRUE(c.lodColours && c.freezeCulling && !c.vsync && r.screenshot);
    // A HUD text field holding the keyboard keeps every key but Escape.
    ViewControls before = c;
    in.pressed[size_t(GLFW_KEY_ESCAPE)] = true;
    r = applyShortcuts(in, true, c);
    EXPECT_TRUE(r.quit);
    EXPECT_FALSE(r.screenshot);
    EXPECT_EQ(c.wind.baseLevel, before.wind.baseLevel);
    EXPECT_EQ(c.lodColours, before.lodColours);
    // The help lists every key the shortcuts use.
    const std::string help = keyHelpText();
    for (const char* key : {"W A S D", "F12", "F11", "[ / ]", "Esc", "G", "P", "R", "V", "L", "C"})
        EXPECT_NE(help.find(key), std::string::npos) << key;
}

TEST(ViewControls, TheDayPlaysOnlyWhenAsked) {
    ViewControls c;
    c.hours = 10.0;
    c.daySpeed = 2.0f;
    advanceDay(c, 1.0);
    EXPECT_EQ(c.hours, 10.0);
    c.playDay = true;
    advanceDay(c, 8.0);
    EXPECT_NEAR(c.hours, 2.0, 1e-12);
}
