#include "plants/iris.h"
#include "sim/clump_sim.h"
#include "sim/rod_system.h"
#include "sim/segment_distance.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>

using namespace meadow;

namespace {

// A straight upright rod of `nodes` nodes, `length` metres, at (x, 0, z).
Rod uprightRod(glm::vec3 base, float length, uint32_t nodes, RodKind kind = RodKind::Leaf, uint32_t plant = 0) {
    Rod rod;
    rod.kind = kind;
    rod.plant = plant;
    for (uint32_t i = 0; i < nodes; ++i) {
        rod.restNodes.push_back(base + glm::vec3(0.0f, length * float(i) / float(nodes - 1), 0.0f));
        rod.width.push_back(kind == RodKind::Leaf ? 0.03f : 0.006f);
    }
    rod.thickness = 0.002f;
    return rod;
}

AirCoupling uniformWind(glm::vec3 velocity) {
    AirCoupling air;
    air.velocityAt = [velocity](glm::vec3) { return velocity; };
    return air;
}

glm::vec3 tip(const RodSystem& s, uint32_t rod) {
    return s.positions()[s.firstNode(rod) + s.nodeCount(rod) - 1];
}

void run(RodSystem& s, const AirCoupling& air, float seconds) {
    const float dt = 1.0f / 600.0f;
    for (int frame = 0; frame < int(seconds * 30.0f); ++frame) {
        s.updateContactCandidates(0.05f);
        for (int i = 0; i < 20; ++i)
            s.step(dt, air, 0.05f);
    }
}

} // namespace

TEST(RodSystem, StandsUnderGravityAndSettles) {
    RodSystem s({uprightRod({0, 0, 0}, 0.7f, 10)}, RodMaterial{});
    run(s, uniformWind(glm::vec3(0.0f)), 3.0f);
    // An upright blade barely moves under its own weight, and the motion dies out.
    EXPECT_LT(glm::length(tip(s, 0) - glm::vec3(0, 0.7f, 0)), 0.02f);
    EXPECT_LT(s.kineticEnergy(), 1e-6);
}

TEST(RodSystem, WindBendsDownwindMoreWhenStronger) {
    float previous = 0.0f;
    for (float speed : {1.0f, 3.0f, 6.0f}) {
        RodSystem s({uprightRod({0, 0, 0}, 0.7f, 10)}, RodMaterial{});
        run(s, uniformWind({speed, 0.0f, 0.0f}), 3.0f);
        float dx = tip(s, 0).x;
        EXPECT_GT(dx, previous) << "at " << speed << " m/s";
        EXPECT_NEAR(tip(s, 0).z, 0.0f, 1e-4f); // the wind has no z component
        previous = dx;
        // Segments keep their lengths (XPBD stretch) within half a percent.
        for (uint32_t i = 0; i + 1 < s.nodeCount(0); ++i)
            EXPECT_NEAR(glm::length(s.positions()[i + 1] - s.positions()[i]), 0.7f / 9.0f, 0.7f / 9.0f * 5e-3f);
    }
    EXPECT_GT(previous, 0.1f); // a 6 m/s wind bends a blade visibly
}

TEST(RodSystem, ContactsKeepRodsApart) {
    // A blade upwind of a taller stem, 3 cm apart; a strong wind presses the blade onto it.
    RodMaterial material;
    Rod blade = uprightRod({-0.03f, 0, 0}, 0.5f, 10, RodKind::Leaf, 0);
    Rod stem = uprightRod({0.0f, 0, 0}, 0.8f, 10, RodKind::Stem, 1);
    RodSystem s({blade, stem}, material);
    run(s, uniformWind({6.0f, 0.0f, 0.0f}), 2.0f);
    float deepest = s.takeMaxPenetration();
    EXPECT_GT(deepest, 0.0f);   // they did touch
    EXPECT_LT(deepest, 0.003f); // and never sank more than a few millimetres into each other
    // Without contacts the blade would pass through the stem; with them the blade's tip stays
    // upwind of the stem at the blade tip's height (the stem is a straight-ish line there).
    glm::vec3 bladeTip = tip(s, 0);
    float stemXAtHeight = s.positions()[s.firstNode(1) + 5].x; // node 5 of the stem is at ~0.44 m
    EXPECT_LT(bladeTip.x, stemXAtHeight + 0.02f);
    EXPECT_GT(bladeTip.x, 0.02f); // and it is bent downwind, resting against the stem
}

TEST(RodSystem, EnergyStaysBoundedInGustyWind) {
    RodSystem s({uprightRod({0, 0, 0}, 0.7f, 10), uprightRod({0.05f, 0, 0}, 0.8f, 10, RodKind::Stem, 1)},
                RodMaterial{});
    float time = 0.0f;
    AirCoupling air;
    air.velocityAt = [&time](glm::vec3 p) {
        return glm::vec3(6.0f + 4.0f * std::sin(3.0f * time + p.y * 4.0f), 0.0f, 2.0f * std::cos(5.0f * time));
    };
    double maxEnergy = 0.0;
    for (int frame = 0; frame < 30 * 20; ++frame) {
        s.updateContactCandidates(0.05f);
        for (int i = 0; i < 20; ++i) {
            s.step(1.0f / 600.0f, air, 0.05f);
            time += 1.0f / 600.0f;
        }
        double e = s.kineticEnergy();
        ASSERT_TRUE(std::isfinite(e));
        if (frame > 30 * 10) {
            EXPECT_LT(e, 2.0 * maxEnergy + 1e-3) << "energy grows without bound at frame " << frame;
        } else {
            maxEnergy = std::max(maxEnergy, e);
        }
    }
}

TEST(RodSystem, SkinningFollowsTheRods) {
    Rod rod = uprightRod({0, 0, 0}, 0.6f, 7);
    PlantMesh mesh;
    // Two vertices across the blade at each node, bound with their offsets.
    for (uint32_t i = 0; i + 1 < rod.restNodes.size(); ++i)
        for (float side : {-0.015f, 0.015f}) {
            glm::vec3 p = rod.restNodes[i] + glm::vec3(0, 0, side);
            mesh.positions.push_back(p);
            mesh.normals.push_back({1, 0, 0});
            mesh.skin.push_back({0, i, 0.0f, glm::vec3(0, 0, side)});
        }
    std::vector<Rod> rods{rod};
    RodSystem s(rods, RodMaterial{});
    std::vector<glm::vec3> skinned, normals;
    skinPlantMesh(mesh, rods, s, skinned, &normals);
    for (size_t v = 0; v < skinned.size(); ++v)
        EXPECT_LT(glm::length(skinned[v] - mesh.positions[v]), 1e-6f); // the rest pose is reproduced
    run(s, uniformWind({5.0f, 0.0f, 0.0f}), 2.0f);
    skinPlantMesh(mesh, rods, s, skinned, &normals);
    for (size_t v = 0; v < skinned.size(); ++v) {
        // Each vertex stays at its offset from its node, and the width direction (z) survives a
        // bend in the x-y plane.
        const SkinBinding& b = mesh.skin[v];
        glm::vec3 node = s.positions()[b.segment];
        EXPECT_NEAR(glm::length(skinned[v] - node), 0.015f, 1e-5f);
        EXPECT_NEAR(skinned[v].z, b.offset.z, 1e-4f);
        EXPECT_NEAR(glm::length(normals[v]), 1.0f, 1e-5f);
    }
    // Bent downwind: the normals of upper vertices tilt towards -y.
    EXPECT_LT(normals.back().y, -0.05f);
}

TEST(RodSystem, Deterministic) {
    auto once = [] {
        RodSystem s({uprightRod({0, 0, 0}, 0.7f, 10), uprightRod({0.02f, 0, 0}, 0.7f, 10, RodKind::Leaf, 1)},
                    RodMaterial{});
        run(s, uniformWind({4.0f, 0.0f, 1.0f}), 1.0f);
        return s.positions();
    };
    std::vector<glm::vec3> a = once(), b = once();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)));
}

// A procedural iris clump in the real wind solver at the strongest default level: the
// simulation stays finite and bounded, and contacts keep interpenetration to millimetres.
TEST(ClumpSimulation, IrisClumpInStrongWindStaysBounded) {
    std::vector<PlantClump> clumps = makeIrisClumps(7, 1, irisParamsForPreset("ci"));
    ClumpSimSettings settings;
    settings.settleSeconds = 1.0f;
    settings.recordSeconds = 2.0f;
    LevelSimulation run = simulateClumpLevel(clumps[0], WindLevelSpec{7.0f, 0.3f}, 3, settings, 99);
    ASSERT_EQ(run.frames, 60u);
    ASSERT_EQ(run.nodeFrames.size(), size_t(run.frames) * run.nodesPerFrame);
    for (const glm::vec3& p : run.nodeFrames)
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    EXPECT_LT(run.maxPenetration, 0.01f) << "interpenetration deeper than a centimetre";
    // Stationary, not growing: the second half moves no more than twice the first.
    EXPECT_GT(run.firstHalfKineticEnergy, 0.0);
    EXPECT_LT(run.secondHalfKineticEnergy, 2.0 * run.firstHalfKineticEnergy + 1e-4);
    EXPECT_LT(run.maxAirDivergence * settings.grid.cellSize / 7.0, 1e-3);
    // The clump bends downwind (+x): its mean node position moves that way.
    float restX = 0.0f, windX = 0.0f;
    RodSystem rest(clumps[0].rods, settings.material);
    for (const glm::vec3& p : rest.positions())
        restX += p.x;
    for (uint32_t i = 0; i < run.nodesPerFrame; ++i)
        windX += run.nodeFrames[size_t(run.frames - 1) * run.nodesPerFrame + i].x;
    EXPECT_GT(windX / float(run.nodesPerFrame), restX / float(run.nodesPerFrame) + 0.02f);
    std::printf("iris clump at 7 m/s: max penetration %.2f mm, kinetic energy %.4f / %.4f J, %u contact pairs\n",
                double(run.maxPenetration) * 1000.0, run.firstHalfKineticEnergy, run.secondHalfKineticEnergy,
                run.contactCandidates);
}

// An imported plant's stem (plants/gltf_import.h) brings its own rigidity and mass per length.
TEST(RodSystem, OwnRigidityStiffensAndIsCappedWhereTheStepWouldBeUnstable) {
    float previous = INFINITY;
    for (float rigidity : {0.05f, 0.2f, 5.0e5f}) {
        Rod rod = uprightRod({0, 0, 0}, 0.7f, 8, RodKind::Stem);
        rod.width.assign(8, 0.05f);
        rod.bendRigidity = rigidity;
        rod.linearDensity = 0.1f;
        RodSystem s({rod}, RodMaterial{});
        run(s, uniformWind({4.0f, 0.0f, 0.0f}), 3.0f);
        const glm::vec3 t = tip(s, 0);
        ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << rigidity;
        EXPECT_LT(t.x, previous) << rigidity;                          // stiffer bends less
        EXPECT_LT(std::abs(glm::length(t) - 0.7f), 0.02f) << rigidity; // and stays whole
        previous = t.x;
    }
    // 5e5 N m^2 is far beyond what a 1/600 s step carries: capped, it stands nearly upright and
    // settles instead of blowing up.
    EXPECT_LT(previous, 0.03f);
    // Light stems, stiff and very stiff, in gusty wind for 10 s stay finite and bounded.
    for (float rigidity : {1.0f, 1.0e3f, 1.0e7f}) {
        Rod rod = uprightRod({0, 0, 0}, 0.3f, 8, RodKind::Stem);
        rod.bendRigidity = rigidity;
        rod.linearDensity = 0.001f;
        rod.nodeMass.assign(8, 0.0005f);
        RodSystem s({rod}, RodMaterial{});
        AirCoupling air;
        float time = 0.0f;
        air.velocityAt = [&time](glm::vec3) { return glm::vec3(6.0f + 4.0f * std::sin(7.0f * time), 0.0f, 0.0f); };
        for (int frame = 0; frame < 300; ++frame) {
            s.updateContactCandidates(0.05f);
            for (int i = 0; i < 20; ++i, time += 1.0f / 600.0f)
                s.step(1.0f / 600.0f, air, 0.05f);
        }
        const glm::vec3 t = tip(s, 0);
        ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << rigidity;
        EXPECT_LT(glm::length(t), 0.32f) << rigidity;
        EXPECT_LT(s.kineticEnergy(), 1.0) << rigidity;
    }
}

TEST(RodSystem, LinearDensitySetsTheWeight) {
    // A level cantilever 0.5 m long sags under its own weight in proportion to it.
    auto sag = [](float density) {
        Rod rod;
        rod.kind = RodKind::Stem;
        for (uint32_t i = 0; i < 8; ++i) {
            rod.restNodes.emplace_back(0.5f * float(i) / 7.0f, 0.6f, 0.0f);
            rod.width.push_back(0.01f);
        }
        rod.thickness = 0.01f;
        rod.bendRigidity = 0.05f;
        rod.linearDensity = density;
        RodSystem s({rod}, RodMaterial{});
        run(s, uniformWind(glm::vec3(0.0f)), 4.0f);
        return 0.6f - tip(s, 0).y;
    };
    const float light = sag(0.05f), heavy = sag(0.1f);
    // Twice the weight, twice the sag (small deflections); the order of beam theory's
    // q L^4 / 8 EI = 7.7 cm for 0.05 kg/m (the segment springs k = EI / L^3 are somewhat stiffer).
    EXPECT_GT(light, 0.25f * 0.05f * 9.81f * std::pow(0.5f, 4.0f) / (8.0f * 0.05f));
    EXPECT_LT(light, 0.05f * 9.81f * std::pow(0.5f, 4.0f) / (8.0f * 0.05f));
    EXPECT_NEAR(heavy / light, 2.0f, 0.25f);
}

// The candidate refresh passes over rods whose bounds a capsule does not meet (rod_system.cpp):
// it must find every pair that testing each pair of capsules finds. Counted here by testing every
// pair, from the rods' own capsules (a leaf's segments, leafCapsuleRadius), for a fan of leaning
// leaves that cross and touch one another, at rest (where the leaves grown together at the base
// are left out) and as a wind moves them, at two margins.
TEST(RodSystem, ContactCandidatesAreEveryPairOfOverlappingBounds) {
    std::vector<Rod> rods;
    const uint32_t nodes = 8;
    for (uint32_t r = 0; r < 12; ++r) {
        const float angle = 0.55f * float(r), lean = 0.15f + 0.05f * float(r % 3);
        Rod rod = uprightRod({0.01f * std::cos(angle), 0.0f, 0.01f * std::sin(angle)}, 0.5f + 0.03f * float(r % 4),
                             nodes, RodKind::Leaf, r);
        for (uint32_t i = 0; i < nodes; ++i) {
            const float h = rod.restNodes[i].y;
            rod.restNodes[i] += glm::vec3(lean * h * std::cos(angle), 0.0f, lean * h * std::sin(angle));
        }
        rods.push_back(rod);
    }
    const RodMaterial material;
    RodSystem s(rods, material);
    const float radius = material.leafCapsuleRadius;
    const auto bruteForce = [&](float margin, bool leaveOutGrownTogether = true) {
        uint32_t count = 0;
        for (uint32_t ra = 0; ra < rods.size(); ++ra)
            for (uint32_t rb = ra + 1; rb < rods.size(); ++rb)
                for (uint32_t i = 0; i + 1 < nodes; ++i)
                    for (uint32_t j = 0; j + 1 < nodes; ++j) {
                        const uint32_t a = s.firstNode(ra) + i, b = s.firstNode(rb) + j;
                        const glm::vec3 extent(radius + margin);
                        const auto& p = s.positions();
                        const glm::vec3 loA = glm::min(p[a], p[a + 1]) - extent,
                                        hiA = glm::max(p[a], p[a + 1]) + extent;
                        const glm::vec3 loB = glm::min(p[b], p[b + 1]) - extent,
                                        hiB = glm::max(p[b], p[b + 1]) + extent;
                        if (glm::any(glm::greaterThan(loA, hiB)) || glm::any(glm::greaterThan(loB, hiA)))
                            continue;
                        float u, v;
                        const auto& restA = rods[ra].restNodes;
                        const auto& restB = rods[rb].restNodes;
                        if (leaveOutGrownTogether &&
                            segmentDistance(restA[i], restA[i + 1], restB[j], restB[j + 1], u, v) < 2.0f * radius)
                            continue; // grown together at rest
                        ++count;
                    }
        return count;
    };
    AirCoupling air = uniformWind({4.0f, 0.0f, 1.0f});
    // Some pairs overlap at rest but grew together there: the rest test is exercised.
    EXPECT_GT(bruteForce(0.05f, false), bruteForce(0.05f));
    uint32_t checked = 0;
    for (int frame = 0; frame < 60; ++frame) {
        for (float margin : {0.015f, 0.05f}) {
            s.updateContactCandidates(margin);
            const uint32_t expected = bruteForce(margin);
            ASSERT_EQ(s.contactCandidateCount(), expected) << "frame " << frame << ", margin " << margin;
            checked += expected;
        }
        for (int i = 0; i < 20; ++i)
            s.step(1.0f / 600.0f, air, 0.05f);
    }
    EXPECT_GT(checked, 1000u); // the fan's leaves do meet
}
