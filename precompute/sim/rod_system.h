// Rod dynamics for one plant clump (docs/ARCHITECTURE.md, Wind and rods).
//
// Every leaf and stem is an elastic rod: a chain of point masses rooted at the rhizome (node 0
// is clamped at its rest position and the root segment is clamped in direction, a cantilever).
// Per substep:
//   forces  gravity; bending as angular springs that pull each segment towards its rest
//           direction relative to its parent segment (the parent's rest-to-current minimal
//           rotation applied to the rest direction, so twist is ignored), with damping; air drag
//           on each segment by its exposed area; friction along the ground
//   motion  symplectic Euler, then XPBD constraints (Macklin et al. 2016) on the predicted
//           positions: stretch with a small compliance, and penalty contacts between segment
//           capsules of different rods and against the ground, solved implicitly as constraints
//           with compliance 1/stiffness (stable for stiff contacts on light blade tips)
// Stiffness comes from a bending rigidity EI (N m^2), per kind (RodMaterial) or the rod's own
// (Rod::bendRigidity, imported plants): a segment of length L gets k = EI / L^3.
// Units: SI (m, s, kg, N).
#pragma once

#include "plants/plant.h"

#include <functional>
#include <glm/glm.hpp>
#include <vector>

namespace meadow {

struct RodMaterial {
    float leafBendRigidity = 1.2e-2f; // EI of a keeled iris blade, N m^2
    float stemBendRigidity = 3.0e-2f; // EI of a flower stem
    float leafArealDensity = 0.35f;   // kg/m^2 of blade
    float stemDensity = 700.0f;       // kg/m^3
    float bendDampingRatio = 0.3f;    // fraction of critical damping of each bending spring
    float stretchCompliance = 1e-7f;  // XPBD compliance of segment lengths, m/N
    float dragCoefficient = 1.2f;     // of a flat blade or a cylinder across the flow
    float airDensity = 1.2f;          // kg/m^3
    float flowerRadius = 0.035f;      // collision sphere and drag disc at each stem tip, m
    float contactStiffness = 2000.0f; // N/m per metre of interpenetration (implicit)
    float groundStiffness = 2000.0f;  // N/m (implicit), also sets the ground's sliding friction
    float leafCapsuleRadius = 0.006f; // a blade's collision capsule: its midrib with a margin, m
};

// The air around the clump: velocity at a point, and where the clump's drag pushes back on it.
struct AirCoupling {
    std::function<glm::vec3(glm::vec3)> velocityAt;
    std::function<void(glm::vec3 point, glm::vec3 force)> addForce; // may be empty: one-way coupling
};

class RodSystem {
  public:
    RodSystem(const std::vector<Rod>& rods, const RodMaterial& material);

    // Advances by dt (a substep, around 1/600 s). Forces on the air are reported scaled by
    // `airForceWeight` (the substep's share of the air solver's step) so that the air sees the
    // mean force over its own step.
    void step(float dt, const AirCoupling& air, float airForceWeight);

    // Rebuilds the candidate contact pairs from capsule bounds inflated by `margin` (m); call
    // once per frame with a margin that covers the motion until the next call.
    void updateContactCandidates(float margin);

    const std::vector<glm::vec3>& positions() const { return position_; }
    // Places every node (a recorded frame, for skinning); velocities are left as they are.
    void setPositions(const glm::vec3* nodes) { position_.assign(nodes, nodes + position_.size()); }
    const std::vector<glm::vec3>& velocities() const { return velocity_; }
    uint32_t rodCount() const { return uint32_t(rodFirst_.size()); }
    uint32_t firstNode(uint32_t rod) const { return rodFirst_[rod]; }
    uint32_t nodeCount(uint32_t rod) const { return rodNodes_[rod]; }

    double kineticEnergy() const;
    // Potential energy of the bending springs and gravity relative to the rest pose (J).
    double potentialEnergy() const;
    // Deepest capsule or ground interpenetration seen since the last call (m), then resets.
    float takeMaxPenetration();
    uint32_t contactCandidateCount() const { return uint32_t(candidates_.size()); }

  private:
    struct Capsule {
        uint32_t a, b; // node indices (a == b for a flower sphere)
        float radius;
        uint32_t rod;
    };
    struct Candidate {
        uint32_t first, second; // capsule indices
        float threshold;        // contact distance: r1 + r2, or less when the rest pose is closer
    };
    // The bending spring of the segment from `node` for a step of dt: bendStiffness_, capped for
    // rods of their own rigidity so that omega dt <= 0.5 (symplectic Euler needs omega dt < 2;
    // a node feels two springs). A stem that stiff already rings above 100 Hz: it looks rigid.
    float bendStiffness(uint32_t node, float dt) const;
    static constexpr float kBendStabilityLimit = 0.25f;
    float capsuleDistance(const Capsule& p, const Capsule& q, glm::vec3& pointP, glm::vec3& pointQ, float& s,
                          float& t) const;

    RodMaterial material_;
    std::vector<uint32_t> rodFirst_, rodNodes_;
    std::vector<uint8_t> rodIsStem_;
    std::vector<glm::vec3> rest_, position_, velocity_, predicted_;
    std::vector<float> inverseMass_, mass_;
    std::vector<float> restLength_;    // per node: length of the segment from this node to the next
    std::vector<float> bendStiffness_; // per node: spring pulling the next node, N/m
    // per node: the reduced mass of the segment from it when its rod has its own rigidity
    // (Rod::bendRigidity), else 0; caps the spring at kBendStabilityLimit * mass / dt^2
    std::vector<float> bendLimitMass_;
    std::vector<uint8_t> ownMaterial_; // per node: its rod has its own rigidity or density (Rod)
    std::vector<float> dragArea_;      // per node: area of the segment starting here, m^2
    std::vector<float> stretchLambda_;
    std::vector<float> contactLambda_;
    std::vector<glm::vec3> force_;
    std::vector<Capsule> capsules_;
    // Per capsule pair (i < j, of different rods): whether they touch in the rest pose, and so are
    // never kept apart (updateContactCandidates), at i * capsules + j. Fixed by the rest pose:
    // worked out once.
    std::vector<bool> restTouching_;
    // Per capsule: its predicted segment's bounds, this step's (step).
    std::vector<glm::vec3> boundsLo_, boundsHi_;
    // Per rod: its first capsule (and the capsule count at the end)
    std::vector<uint32_t> rodCapsuleFirst_;
    // updateContactCandidates': each rod's bounds, and whether one of them is NaN
    std::vector<glm::vec3> rodLo_, rodHi_;
    std::vector<uint8_t> rodNaN_;
    std::vector<Candidate> candidates_;
    std::vector<Candidate> active_; // of this step
    float maxPenetration_ = 0.0f;
};

// Moves a mesh with the rods: each vertex follows the frame of the rod segment it is bound to
// (parallel-transported rest-to-current rotations, blended across nodes so bends are smooth).
// `normals` may be null.
void skinPlantMesh(const PlantMesh& mesh, const std::vector<Rod>& rods, const RodSystem& system,
                   std::vector<glm::vec3>& positions, std::vector<glm::vec3>* normals);

} // namespace meadow
