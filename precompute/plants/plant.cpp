#include "plant.h"

#include "core/error.h"

#include <cmath>

namespace meadow {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::vec2& v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}

} // namespace

glm::vec3 boundRestPosition(const std::vector<Rod>& rods, const SkinBinding& binding) {
    const Rod& rod = rods[binding.rod];
    return glm::mix(rod.restNodes[binding.segment], rod.restNodes[binding.segment + 1], binding.t) + binding.offset;
}

float rodLength(const Rod& rod) {
    float length = 0.0f;
    for (size_t i = 1; i < rod.restNodes.size(); ++i)
        length += glm::length(rod.restNodes[i] - rod.restNodes[i - 1]);
    return length;
}

void checkPlantClump(const PlantClump& clump, const std::string& what) {
    const PlantMesh& mesh = clump.mesh;
    size_t n = mesh.positions.size();
    if (mesh.normals.size() != n || mesh.uvs.size() != n || mesh.skin.size() != n || mesh.parts.size() != n)
        throw Error(what + ": per-vertex arrays differ in size (" + std::to_string(n) + " positions)");
    if (mesh.indices.size() % 3 != 0)
        throw Error(what + ": index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    for (uint32_t index : mesh.indices)
        if (index >= n)
            throw Error(what + ": index " + std::to_string(index) + " is out of range (" + std::to_string(n) +
                        " vertices)");
    for (size_t i = 0; i < n; ++i)
        if (!finite(mesh.positions[i]) || !finite(mesh.normals[i]) || !finite(mesh.uvs[i]) ||
            !finite(mesh.skin[i].offset) || !std::isfinite(mesh.skin[i].t))
            throw Error(what + ": vertex " + std::to_string(i) + " has a value that is not finite");
    for (size_t r = 0; r < clump.rods.size(); ++r) {
        const Rod& rod = clump.rods[r];
        std::string name = what + ": rod " + std::to_string(r);
        if (rod.restNodes.size() < 3)
            throw Error(name + " has " + std::to_string(rod.restNodes.size()) + " nodes (at least 3 needed)");
        if (rod.width.size() != rod.restNodes.size())
            throw Error(name + " has " + std::to_string(rod.width.size()) + " widths for " +
                        std::to_string(rod.restNodes.size()) + " nodes");
        if (!rod.nodeMass.empty() && rod.nodeMass.size() != rod.restNodes.size())
            throw Error(name + " has " + std::to_string(rod.nodeMass.size()) + " node masses for " +
                        std::to_string(rod.restNodes.size()) + " nodes");
        if (rod.plant >= clump.plants)
            throw Error(name + " belongs to plant " + std::to_string(rod.plant) + " of " +
                        std::to_string(clump.plants));
        for (const glm::vec3& node : rod.restNodes)
            if (!finite(node))
                throw Error(name + " has a node that is not finite");
        if (!(rod.thickness > 0.0f) || !std::isfinite(rod.tipMass) || rod.tipMass < 0.0f)
            throw Error(name + " has a thickness or tip mass out of range");
        if (!(rod.bendRigidity >= 0.0f) || !std::isfinite(rod.bendRigidity) || !(rod.linearDensity >= 0.0f) ||
            !std::isfinite(rod.linearDensity))
            throw Error(name + " has a bending rigidity or linear density out of range");
        for (float m : rod.nodeMass)
            if (!(m >= 0.0f) || !std::isfinite(m))
                throw Error(name + " has a node mass out of range");
    }
    for (size_t i = 0; i < n; ++i) {
        const SkinBinding& b = mesh.skin[i];
        if (b.rod >= clump.rods.size() || b.segment + 1 >= clump.rods[b.rod].restNodes.size() || b.t < 0.0f ||
            b.t > 1.0f)
            throw Error(what + ": vertex " + std::to_string(i) + " is bound to rod " + std::to_string(b.rod) +
                        " segment " + std::to_string(b.segment) + ", which does not exist");
    }
}

} // namespace meadow
