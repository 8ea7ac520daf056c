#include "sim/rod_system.h"

#include "core/error.h"
#include "sim/segment_distance.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <limits>

namespace meadow {
namespace {

constexpr glm::vec3 kGravity{0.0f, -9.81f, 0.0f};
// Nodes stay this far above the ground plane (m): the blades' half thickness and a margin.
constexpr float kGroundClearance = 0.004f;
constexpr int kSolverIterations = 4;
constexpr float kMinNodeMassFraction = 0.4f;

// The rotation taking unit vector `from` onto unit vector `to` by the smallest angle.
glm::quat minimalRotation(glm::vec3 from, glm::vec3 to) {
    float c = glm::dot(from, to);
    if (c < -0.9999f) {
        // Opposite: any axis perpendicular to `from` will do.
        glm::vec3 axis = glm::cross(from, glm::abs(from.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
        return glm::angleAxis(glm::pi<float>(), glm::normalize(axis));
    }
    glm::vec3 axis = glm::cross(from, to);
    // Half-angle formula: q = (1 + c, axis) normalised.
    return glm::normalize(glm::quat(1.0f + c, axis.x, axis.y, axis.z));
}

} // namespace

RodSystem::RodSystem(const std::vector<Rod>& rods, const RodMaterial& material) : material_(material) {
    for (uint32_t r = 0; r < rods.size(); ++r) {
        const Rod& rod = rods[r];
        size_t n = rod.restNodes.size();
        if (n < 2 || rod.width.size() != n)
            throw Error("rod " + std::to_string(r) + ": needs at least two nodes and one width per node");
        uint32_t first = uint32_t(rest_.size());
        rodFirst_.push_back(first);
        rodNodes_.push_back(uint32_t(n));
        rodIsStem_.push_back(rod.kind == RodKind::Stem);
        for (size_t i = 0; i < n; ++i) {
            rest_.push_back(rod.restNodes[i]);
            float len = i + 1 < n ? glm::length(rod.restNodes[i + 1] - rod.restNodes[i]) : 0.0f;
            if (i + 1 < n && !(len > 1e-5f))
                throw Error("rod " + std::to_string(r) + ": nodes " + std::to_string(i) + " and " +
                            std::to_string(i + 1) + " coincide");
            restLength_.push_back(len);
        }
        // Lumped masses: each node carries half of each adjacent segment.
        std::vector<float> m(n, 0.0f);
        std::vector<float> area(n, 0.0f);
        for (size_t i = 0; i + 1 < n; ++i) {
            float len = restLength_[first + i];
            float w = 0.5f * (rod.width[i] + rod.width[i + 1]);
            float segmentMass = rod.linearDensity > 0.0f ? rod.linearDensity * len
                                : rod.kind == RodKind::Stem
                                    ? material.stemDensity * glm::pi<float>() * 0.25f * w * w * len
                                    : material.leafArealDensity * w * len;
            m[i] += 0.5f * segmentMass;
            m[i + 1] += 0.5f * segmentMass;
            area[i] = w * len;
        }
        // Tapered blades put almost no mass at their tips; a node lighter than a fraction of its
        // rod's mean would need a far smaller time step for the same bending stiffness.
        float meanMass = 0.0f;
        for (float x : m)
            meanMass += x / float(n);
        for (float& x : m)
            x = std::max(x, kMinNodeMassFraction * meanMass);
        m[n - 1] += rod.tipMass;
        for (size_t i = 0; i < rod.nodeMass.size() && i < n; ++i)
            m[i] += rod.nodeMass[i]; // a second flower lower on a stem
        const bool ownRigidity = rod.bendRigidity > 0.0f;
        float rigidity = ownRigidity                 ? rod.bendRigidity
                         : rod.kind == RodKind::Stem ? material.stemBendRigidity
                                                     : material.leafBendRigidity;
        for (size_t i = 0; i < n; ++i) {
            mass_.push_back(std::max(m[i], 1e-6f));
            inverseMass_.push_back(i == 0 ? 0.0f : 1.0f / std::max(m[i], 1e-6f));
            float len = restLength_[first + i];
            bendStiffness_.push_back(i + 1 < n ? rigidity / (len * len * len) : 0.0f);
            dragArea_.push_back(area[i]);
        }
        // A rod of its own rigidity (an imported plant's stem) may be stiffer than the explicit
        // bending step can carry: its springs are capped by the segment's reduced mass (step()).
        for (size_t i = 0; i < n; ++i) {
            size_t a = first + i, b = a + 1;
            bendLimitMass_.push_back(ownRigidity && i + 1 < n ? 1.0f / (inverseMass_[a] + inverseMass_[b]) : 0.0f);
            ownMaterial_.push_back(ownRigidity || rod.linearDensity > 0.0f);
        }
        // Collision capsules: one per segment, plus a flower sphere at each stem tip, listed rod
        // by rod (updateContactCandidates relies on it).
        rodCapsuleFirst_.push_back(uint32_t(capsules_.size()));
        for (size_t i = 0; i + 1 < n; ++i) {
            float radius = rod.kind == RodKind::Stem ? 0.5f * std::max(rod.width[i], rod.width[i + 1])
                                                     : material.leafCapsuleRadius;
            capsules_.push_back({uint32_t(first + i), uint32_t(first + i + 1), radius, r});
        }
        if (rod.kind == RodKind::Stem && rod.tipMass > 0.0f)
            capsules_.push_back({uint32_t(first + n - 1), uint32_t(first + n - 1), material.flowerRadius, r});
    }
    position_ = rest_;
    predicted_ = rest_;
    velocity_.assign(rest_.size(), glm::vec3(0.0f));
    force_.assign(rest_.size(), glm::vec3(0.0f));
    stretchLambda_.assign(rest_.size(), 0.0f);
    rodCapsuleFirst_.push_back(uint32_t(capsules_.size()));
    const size_t count = capsules_.size();
    restTouching_.assign(count * count, false);
    for (size_t i = 0; i < count; ++i)
        for (size_t j = i + 1; j < count; ++j) {
            const Capsule& a = capsules_[i];
            const Capsule& b = capsules_[j];
            if (a.rod == b.rod)
                continue;
            float s, t;
            restTouching_[i * count + j] =
                segmentDistance(rest_[a.a], rest_[a.b], rest_[b.a], rest_[b.b], s, t) < a.radius + b.radius;
        }
    boundsLo_.resize(count);
    boundsHi_.resize(count);
    updateContactCandidates(0.05f);
}

float RodSystem::capsuleDistance(const Capsule& p, const Capsule& q, glm::vec3& pointP, glm::vec3& pointQ, float& s,
                                 float& t) const {
    glm::vec3 p0 = position_[p.a], p1 = position_[p.b], q0 = position_[q.a], q1 = position_[q.b];
    float d = segmentDistance(p0, p1, q0, q1, s, t);
    pointP = p0 + (p1 - p0) * s;
    pointQ = q0 + (q1 - q0) * t;
    return d;
}

void RodSystem::updateContactCandidates(float margin) {
    candidates_.clear();
    size_t count = capsules_.size();
    std::vector<glm::vec3> lo(count), hi(count);
    for (size_t i = 0; i < count; ++i) {
        const Capsule& c = capsules_[i];
        glm::vec3 extent(c.radius + margin);
        lo[i] = glm::min(position_[c.a], position_[c.b]) - extent;
        hi[i] = glm::max(position_[c.a], position_[c.b]) + extent;
    }
    // Each rod's capsules (listed together, in rod order: the constructor) bounded as a whole, so
    // that a capsule meets the capsules of a rod only where it meets the rod's bounds. A rod with
    // a NaN bound meets every capsule, as each of its capsules would. The pairs come in the same
    // order as when every pair is tested (i, then j, ascending), the order the contacts are solved.
    const uint32_t rods = uint32_t(rodFirst_.size());
    rodLo_.assign(rods, glm::vec3(std::numeric_limits<float>::max()));
    rodHi_.assign(rods, glm::vec3(std::numeric_limits<float>::lowest()));
    rodNaN_.assign(rods, 0);
    for (size_t i = 0; i < count; ++i) {
        const uint32_t r = capsules_[i].rod;
        rodLo_[r] = glm::min(rodLo_[r], lo[i]);
        rodHi_[r] = glm::max(rodHi_[r], hi[i]);
        if (glm::any(glm::isnan(lo[i])) || glm::any(glm::isnan(hi[i])))
            rodNaN_[r] = 1;
    }
    const auto apart = [](glm::vec3 loA, glm::vec3 hiA, glm::vec3 loB, glm::vec3 hiB) {
        return glm::any(glm::greaterThan(loA, hiB)) || glm::any(glm::greaterThan(loB, hiA));
    };
    for (uint32_t i = 0; i < count; ++i) {
        const Capsule& a = capsules_[i];
        // A blade does not fold onto itself at these curvatures: the pairs start at the next rod.
        for (uint32_t r = a.rod + 1; r < rods; ++r) {
            if (!rodNaN_[r] && apart(lo[i], hi[i], rodLo_[r], rodHi_[r]))
                continue;
            for (uint32_t j = rodCapsuleFirst_[r]; j < rodCapsuleFirst_[r + 1]; ++j) {
                if (apart(lo[i], hi[i], lo[j], hi[j]))
                    continue;
                // Parts that already touch in the rest pose (iris leaves sheathe one another at
                // the base of a fan) are not kept apart: they are modelled as grown together
                // there (restTouching_, worked out once).
                if (restTouching_[size_t(i) * count + j])
                    continue;
                candidates_.push_back({i, j, a.radius + capsules_[j].radius});
            }
        }
    }
}

float RodSystem::bendStiffness(uint32_t node, float dt) const {
    const float k = bendStiffness_[node];
    if (bendLimitMass_[node] == 0.0f)
        return k;
    return std::min(k, kBendStabilityLimit * bendLimitMass_[node] / (dt * dt));
}

void RodSystem::step(float dt, const AirCoupling& air, float airForceWeight) {
    const size_t nodes = position_.size();
    std::fill(force_.begin(), force_.end(), glm::vec3(0.0f));
    for (size_t i = 0; i < nodes; ++i)
        force_[i] = mass_[i] * kGravity;

    for (uint32_t r = 0; r < rodFirst_.size(); ++r) {
        uint32_t first = rodFirst_[r], n = rodNodes_[r];
        // Bending: segment i wants the direction its rest direction has after the parent
        // segment's rest-to-current rotation; the root segment's parent is the clamped rhizome.
        glm::quat transport(1.0f, 0.0f, 0.0f, 0.0f);
        for (uint32_t i = 0; i + 1 < n; ++i) {
            uint32_t a = first + i, b = a + 1;
            glm::vec3 restDir = transport * ((rest_[b] - rest_[a]) / restLength_[a]);
            glm::vec3 target = position_[a] + restDir * restLength_[a];
            float k = bendStiffness(a, dt);
            glm::vec3 f = k * (target - position_[b]);
            force_[b] += f;
            force_[a] -= f;
            // The same parallel transport as skinPlantMesh: rest-to-current, twist-free.
            glm::vec3 d = position_[b] - position_[a];
            float len = glm::length(d);
            if (len > 1e-7f)
                transport = minimalRotation(restDir, d / len) * transport;
        }
        // Air drag on each segment (and the flowers at stem tips), by exposed area.
        for (uint32_t i = 0; i + 1 < n; ++i) {
            uint32_t a = first + i, b = a + 1;
            glm::vec3 mid = 0.5f * (position_[a] + position_[b]);
            glm::vec3 axis = position_[b] - position_[a];
            float len = glm::length(axis);
            if (len < 1e-6f)
                continue;
            axis /= len;
            glm::vec3 relative = air.velocityAt(mid) - 0.5f * (velocity_[a] + velocity_[b]);
            glm::vec3 across = relative - glm::dot(relative, axis) * axis;
            glm::vec3 f =
                0.5f * material_.airDensity * material_.dragCoefficient * dragArea_[a] * glm::length(across) * across;
            force_[a] += 0.5f * f;
            force_[b] += 0.5f * f;
            if (air.addForce)
                air.addForce(mid, -f * airForceWeight);
        }
        if (rodIsStem_[r]) {
            uint32_t tip = first + n - 1;
            glm::vec3 relative = air.velocityAt(position_[tip]) - velocity_[tip];
            float area = glm::pi<float>() * material_.flowerRadius * material_.flowerRadius;
            glm::vec3 f =
                0.5f * material_.airDensity * material_.dragCoefficient * area * glm::length(relative) * relative;
            force_[tip] += f;
            if (air.addForce)
                air.addForce(position_[tip], -f * airForceWeight);
        }
    }

    // The ground: friction damps sliding along it (its normal force is a constraint below).
    for (size_t i = 0; i < nodes; ++i) {
        if (inverseMass_[i] == 0.0f || position_[i].y > kGroundClearance + 0.002f || rest_[i].y < kGroundClearance)
            continue;
        float damping = 2.0f * std::sqrt(material_.groundStiffness * mass_[i]);
        // On the light nodes of a rod of its own material (an imported plant's soft stem lying on
        // the ground) that explicit dashpot would overshoot: the exact decay over the step instead.
        if (ownMaterial_[i])
            damping = mass_[i] / dt * (1.0f - std::exp(-damping * dt / mass_[i]));
        force_[i].x -= damping * velocity_[i].x;
        force_[i].z -= damping * velocity_[i].z;
    }

    // Symplectic Euler, then XPBD stretch constraints on the predicted positions.
    for (size_t i = 0; i < nodes; ++i) {
        velocity_[i] += dt * inverseMass_[i] * force_[i];
        predicted_[i] = position_[i] + dt * velocity_[i];
    }
    std::fill(stretchLambda_.begin(), stretchLambda_.end(), 0.0f);
    // The contacts this step can touch: candidates within a few millimetres after prediction
    // (the solver's corrections are far smaller than that).
    // A pair whose predicted segments' bounds lie apart by more than that (segmentBoundsApart) is
    // passed over before its distance: the same pairs are active as when every distance is
    // computed, so the simulation gives the same bytes.
    for (size_t i = 0; i < capsules_.size(); ++i) {
        const Capsule& c = capsules_[i];
        boundsLo_[i] = glm::min(predicted_[c.a], predicted_[c.b]);
        boundsHi_[i] = glm::max(predicted_[c.a], predicted_[c.b]);
    }
    active_.clear();
    for (const Candidate& cand : candidates_) {
        const float limit = cand.threshold + 0.005f;
        if (segmentBoundsApart(boundsLo_[cand.first], boundsHi_[cand.first], boundsLo_[cand.second],
                               boundsHi_[cand.second], limit))
            continue;
        const Capsule& p = capsules_[cand.first];
        const Capsule& q = capsules_[cand.second];
        float s, t;
        if (segmentDistance(predicted_[p.a], predicted_[p.b], predicted_[q.a], predicted_[q.b], s, t) < limit)
            active_.push_back(cand);
    }
    contactLambda_.assign(active_.size(), 0.0f);
    const float alpha = material_.stretchCompliance / (dt * dt);
    // Contacts are penalty springs of stiffness k solved implicitly, as XPBD constraints with
    // compliance 1/k (Macklin et al. 2016): an explicit spring that holds a blade pressed on by a
    // strong wind would need a far smaller time step than a light blade tip allows.
    const float contactAlpha = 1.0f / (material_.contactStiffness * dt * dt);
    const float groundAlpha = 1.0f / (material_.groundStiffness * dt * dt);
    for (int iteration = 0; iteration < kSolverIterations; ++iteration) {
        for (uint32_t r = 0; r < rodFirst_.size(); ++r) {
            uint32_t first = rodFirst_[r], n = rodNodes_[r];
            for (uint32_t i = 0; i + 1 < n; ++i) {
                uint32_t a = first + i, b = a + 1;
                glm::vec3 d = predicted_[b] - predicted_[a];
                float len = glm::length(d);
                float w = inverseMass_[a] + inverseMass_[b];
                if (len < 1e-9f || w == 0.0f)
                    continue;
                float constraint = len - restLength_[a];
                float deltaLambda = (-constraint - alpha * stretchLambda_[a]) / (w + alpha);
                stretchLambda_[a] += deltaLambda;
                glm::vec3 correction = deltaLambda * (d / len);
                predicted_[a] -= inverseMass_[a] * correction;
                predicted_[b] += inverseMass_[b] * correction;
            }
        }
        for (size_t c = 0; c < active_.size(); ++c) {
            const Candidate& cand = active_[c];
            const Capsule& p = capsules_[cand.first];
            const Capsule& q = capsules_[cand.second];
            float s, t;
            float dist = segmentDistance(predicted_[p.a], predicted_[p.b], predicted_[q.a], predicted_[q.b], s, t);
            float constraint = dist - cand.threshold; // <= 0 when the capsules overlap
            if (constraint >= 0.0f && contactLambda_[c] == 0.0f)
                continue;
            glm::vec3 pp = glm::mix(predicted_[p.a], predicted_[p.b], s);
            glm::vec3 pq = glm::mix(predicted_[q.a], predicted_[q.b], t);
            glm::vec3 normal = dist > 1e-7f ? (pp - pq) / dist : glm::vec3(0.0f, 1.0f, 0.0f);
            float wpa = (1.0f - s) * inverseMass_[p.a], wpb = s * inverseMass_[p.b];
            float wqa = (1.0f - t) * inverseMass_[q.a], wqb = t * inverseMass_[q.b];
            float w = (1.0f - s) * wpa + s * wpb + (1.0f - t) * wqa + t * wqb;
            if (w == 0.0f)
                continue;
            // Push only: the accumulated multiplier never pulls the capsules together.
            float deltaLambda = (-constraint - contactAlpha * contactLambda_[c]) / (w + contactAlpha);
            deltaLambda = std::max(deltaLambda, -contactLambda_[c]);
            contactLambda_[c] += deltaLambda;
            glm::vec3 push = deltaLambda * normal;
            predicted_[p.a] += wpa * push;
            predicted_[p.b] += wpb * push;
            predicted_[q.a] -= wqa * push;
            predicted_[q.b] -= wqb * push;
        }
        for (size_t i = 0; i < nodes; ++i) {
            float constraint = predicted_[i].y - kGroundClearance;
            if (inverseMass_[i] == 0.0f || constraint >= 0.0f || rest_[i].y < kGroundClearance)
                continue;
            predicted_[i].y -= inverseMass_[i] * constraint / (inverseMass_[i] + groundAlpha);
        }
    }
    // What remains after the solve is the interpenetration this step leaves.
    for (const Candidate& cand : active_) {
        const Capsule& p = capsules_[cand.first];
        const Capsule& q = capsules_[cand.second];
        float s, t;
        float dist = segmentDistance(predicted_[p.a], predicted_[p.b], predicted_[q.a], predicted_[q.b], s, t);
        maxPenetration_ = std::max(maxPenetration_, cand.threshold - dist);
    }
    for (size_t i = 0; i < nodes; ++i)
        if (inverseMass_[i] != 0.0f && rest_[i].y >= kGroundClearance)
            maxPenetration_ = std::max(maxPenetration_, kGroundClearance - predicted_[i].y);
    for (size_t i = 0; i < nodes; ++i) {
        if (inverseMass_[i] == 0.0f) {
            predicted_[i] = rest_[i];
            velocity_[i] = glm::vec3(0.0f);
        } else {
            velocity_[i] = (predicted_[i] - position_[i]) / dt;
        }
        position_[i] = predicted_[i];
    }
    // Bending damping, applied implicitly: the relative velocity of each segment's two nodes
    // decays exponentially at the rate of a dashpot with the given fraction of critical
    // damping. Explicitly, a dashpot that stiff would be unstable on light blade tips, and
    // underdamped segment-scale vibration (tens of hertz) would alias into the 30 Hz frames.
    for (uint32_t r = 0; r < rodFirst_.size(); ++r) {
        uint32_t first = rodFirst_[r], n = rodNodes_[r];
        for (uint32_t i = 0; i + 1 < n; ++i) {
            uint32_t a = first + i, b = a + 1;
            float w = inverseMass_[a] + inverseMass_[b];
            if (w == 0.0f)
                continue;
            float c = material_.bendDampingRatio * 2.0f * std::sqrt(bendStiffness(a, dt) * mass_[b]);
            float keep = std::exp(-c * w * dt);
            glm::vec3 relative = velocity_[b] - velocity_[a];
            glm::vec3 change = (1.0f - keep) * relative / w;
            velocity_[a] += inverseMass_[a] * change;
            velocity_[b] -= inverseMass_[b] * change;
        }
    }
}

double RodSystem::kineticEnergy() const {
    double e = 0.0;
    for (size_t i = 0; i < position_.size(); ++i)
        e += 0.5 * double(mass_[i]) * double(glm::dot(velocity_[i], velocity_[i]));
    return e;
}

double RodSystem::potentialEnergy() const {
    double e = 0.0;
    for (size_t i = 0; i < position_.size(); ++i)
        e += double(mass_[i]) * 9.81 * double(position_[i].y - rest_[i].y);
    return e;
}

float RodSystem::takeMaxPenetration() {
    float m = maxPenetration_;
    maxPenetration_ = 0.0f;
    return m;
}

void skinPlantMesh(const PlantMesh& mesh, const std::vector<Rod>& rods, const RodSystem& system,
                   std::vector<glm::vec3>& positions, std::vector<glm::vec3>* normals) {
    // Per rod: the rest-to-current rotation of each segment, parallel-transported from the root,
    // then per node the blend of its two segments.
    std::vector<std::vector<glm::quat>> nodeRotations(rods.size());
    const std::vector<glm::vec3>& x = system.positions();
    for (uint32_t r = 0; r < rods.size(); ++r) {
        const Rod& rod = rods[r];
        uint32_t first = system.firstNode(r), n = system.nodeCount(r);
        std::vector<glm::quat> segment(n - 1);
        glm::quat transport(1.0f, 0.0f, 0.0f, 0.0f);
        for (uint32_t i = 0; i + 1 < n; ++i) {
            glm::vec3 restDir = glm::normalize(rod.restNodes[i + 1] - rod.restNodes[i]);
            glm::vec3 dir = x[first + i + 1] - x[first + i];
            float len = glm::length(dir);
            glm::vec3 transported = transport * restDir;
            if (len > 1e-7f)
                transport = minimalRotation(transported, dir / len) * transport;
            segment[i] = transport;
        }
        std::vector<glm::quat>& node = nodeRotations[r];
        node.resize(n);
        node[0] = segment[0];
        for (uint32_t i = 1; i + 1 < n; ++i)
            node[i] = glm::normalize(glm::slerp(segment[i - 1], segment[i], 0.5f));
        node[n - 1] = segment[n - 2];
    }
    positions.resize(mesh.positions.size());
    if (normals)
        normals->resize(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const SkinBinding& b = mesh.skin[v];
        uint32_t first = system.firstNode(b.rod);
        glm::quat q =
            glm::normalize(glm::slerp(nodeRotations[b.rod][b.segment], nodeRotations[b.rod][b.segment + 1], b.t));
        glm::vec3 base = glm::mix(x[first + b.segment], x[first + b.segment + 1], b.t);
        positions[v] = base + q * b.offset;
        if (normals)
            (*normals)[v] = q * mesh.normals[v];
    }
}

} // namespace meadow
