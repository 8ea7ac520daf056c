#include "gltf_import.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <sstream>
#include <tiny_gltf.h>

namespace meadow {
namespace {

// Images are not imported; skip decoding them so an asset with textures loads without an
// image decoder and without failing on formats stb cannot read.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// tinygltf's message without trailing blank space, and cut short: it may quote a whole data URI.
std::string trimmed(std::string text) {
    constexpr size_t kMaxMessage = 300;
    if (text.size() > kMaxMessage)
        text = text.substr(0, kMaxMessage) + "...";
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' '))
        text.pop_back();
    return text;
}

const char* modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
    default: return "an unknown mode";
    }
}

class Importer {
  public:
    Importer(const std::filesystem::path& path, const tinygltf::Model& model) : file_(path.string()), model_(model) {}

    [[noreturn]] void fail(const std::string& what) const { throw Error("glTF " + file_ + ": " + what); }

    // Walks the node forest from `roots` depth first (children in order), with every node's world
    // transform. Iterative, so a deep hierarchy cannot exhaust the stack; each node is visited at
    // most once, so a cycle or a node shared by two parents (both invalid glTF) is refused instead
    // of recursing forever or multiplying the walk.
    void walk(const std::vector<int>& roots) {
        std::vector<bool> visited(model_.nodes.size(), false);
        std::vector<std::pair<int, glm::mat4>> pending;
        for (auto root = roots.rbegin(); root != roots.rend(); ++root)
            pending.emplace_back(*root, glm::mat4(1.0f));
        while (!pending.empty()) {
            const auto [nodeIndex, parent] = pending.back();
            pending.pop_back();
            if (nodeIndex < 0 || static_cast<size_t>(nodeIndex) >= model_.nodes.size())
                fail("node " + std::to_string(nodeIndex) + " does not exist");
            if (visited[static_cast<size_t>(nodeIndex)])
                fail("node " + std::to_string(nodeIndex) +
                     " is reached twice: the node hierarchy has a cycle or a shared node (glTF requires a forest)");
            visited[static_cast<size_t>(nodeIndex)] = true;
            const tinygltf::Node& node = model_.nodes[static_cast<size_t>(nodeIndex)];
            if (node.skin >= 0)
                fail("node '" + node.name + "' uses skinning, which meadow cannot use");
            const glm::mat4 world = parent * localTransform(node);
            if (node.mesh >= 0) {
                if (static_cast<size_t>(node.mesh) >= model_.meshes.size())
                    fail("node '" + node.name + "' names mesh " + std::to_string(node.mesh) + ", which does not exist");
                const tinygltf::Mesh& mesh = model_.meshes[static_cast<size_t>(node.mesh)];
                for (size_t p = 0; p < mesh.primitives.size(); ++p)
                    addPrimitive(mesh, p, world);
            }
            for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
                pending.emplace_back(*child, world);
        }
    }

    PlantMesh& mesh() { return mesh_; }

  private:
    glm::mat4 localTransform(const tinygltf::Node& node) const {
        if (node.matrix.size() == 16) {
            glm::mat4 m;
            for (int i = 0; i < 16; ++i)
                glm::value_ptr(m)[i] = static_cast<float>(node.matrix[static_cast<size_t>(i)]); // column-major
            return m;
        }
        glm::mat4 m(1.0f);
        if (node.translation.size() == 3)
            m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4) // glTF stores x, y, z, w
            m = m *
                glm::mat4_cast(glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                                         static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2])));
        if (node.scale.size() == 3)
            m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
        return m;
    }

    // The bytes of element i of an accessor, bounds-checked against its view and buffer.
    struct View {
        const uint8_t* data = nullptr;
        size_t stride = 0;
        size_t count = 0;
        int componentType = 0;
        bool normalized = false;
    };
    View view(int accessorIndex, const std::string& what, int type) const {
        if (accessorIndex < 0 || static_cast<size_t>(accessorIndex) >= model_.accessors.size())
            fail(what + " names accessor " + std::to_string(accessorIndex) + ", which does not exist");
        const tinygltf::Accessor& accessor = model_.accessors[static_cast<size_t>(accessorIndex)];
        if (accessor.sparse.isSparse)
            fail(what + " uses a sparse accessor, which meadow cannot read");
        if (accessor.type != type)
            fail(what + " has the wrong accessor type");
        if (accessor.bufferView < 0 || static_cast<size_t>(accessor.bufferView) >= model_.bufferViews.size())
            fail(what + " has no buffer view");
        const tinygltf::BufferView& bufferView = model_.bufferViews[static_cast<size_t>(accessor.bufferView)];
        if (bufferView.buffer < 0 || static_cast<size_t>(bufferView.buffer) >= model_.buffers.size())
            fail(what + " names a buffer that does not exist");
        const tinygltf::Buffer& buffer = model_.buffers[static_cast<size_t>(bufferView.buffer)];
        int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(accessor.componentType));
        int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
        int stride = accessor.ByteStride(bufferView);
        if (componentSize <= 0 || components <= 0 || stride <= 0)
            fail(what + " has an invalid component type or stride");
        // The view must lie in its buffer and the accessor's elements in its view; the counts and
        // offsets come from the file, so every step is checked against overflow by comparing with
        // what is left rather than adding.
        const size_t elementSize = static_cast<size_t>(componentSize) * static_cast<size_t>(components);
        const size_t bufferBytes = buffer.data.size();
        if (bufferView.byteOffset > bufferBytes || bufferView.byteLength > bufferBytes - bufferView.byteOffset)
            fail(what + " reads past the end of its buffer (its buffer view does not fit in the buffer)");
        const size_t viewBytes = bufferView.byteLength;
        if (accessor.byteOffset > viewBytes)
            fail(what + " reads past the end of its buffer (its offset is outside its buffer view)");
        const size_t left = viewBytes - accessor.byteOffset;
        if (accessor.count > 0 &&
            (elementSize > left || accessor.count - 1 > (left - elementSize) / static_cast<size_t>(stride)))
            fail(what + " reads past the end of its buffer (" + std::to_string(accessor.count) +
                 " elements do not fit in its buffer view)");
        const size_t start = bufferView.byteOffset + accessor.byteOffset;
        return View{buffer.data.data() + start, static_cast<size_t>(stride), accessor.count, accessor.componentType,
                    accessor.normalized};
    }

    float component(const View& v, size_t element, size_t index, const std::string& what) const {
        const uint8_t* p = v.data + element * v.stride;
        switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, p + index * 4, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            if (v.normalized)
                return static_cast<float>(p[index]) / 255.0f;
            break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            if (v.normalized) {
                uint16_t s;
                std::memcpy(&s, p + index * 2, 2);
                return static_cast<float>(s) / 65535.0f;
            }
            break;
        default: break;
        }
        fail(what + " has a component type meadow cannot read (float or normalized unsigned byte/short expected)");
    }

    uint32_t index(const View& v, size_t element) const {
        const uint8_t* p = v.data + element * v.stride;
        switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t s;
            std::memcpy(&s, p, 2);
            return s;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t i;
            std::memcpy(&i, p, 4);
            return i;
        }
        default: fail("indices have a component type other than unsigned byte, short or int");
        }
    }

    void addPrimitive(const tinygltf::Mesh& mesh, size_t primitiveIndex, const glm::mat4& world) {
        const tinygltf::Primitive& primitive = mesh.primitives[primitiveIndex];
        std::string what = "mesh '" + mesh.name + "' primitive " + std::to_string(primitiveIndex);
        // tinygltf reports an absent mode as TRIANGLES (the glTF default); -1 is kept for safety.
        if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1)
            fail(what + " draws " + modeName(primitive.mode) + "; meadow imports only TRIANGLES primitives");
        auto attribute = [&](const char* name) {
            auto it = primitive.attributes.find(name);
            return it == primitive.attributes.end() ? -1 : it->second;
        };
        int positionAccessor = attribute("POSITION");
        if (positionAccessor < 0)
            fail(what + " has no POSITION attribute");
        View positions = view(positionAccessor, what + " POSITION", TINYGLTF_TYPE_VEC3);
        size_t count = positions.count;

        std::vector<uint32_t> indices;
        if (primitive.indices >= 0) {
            View indexView = view(primitive.indices, what + " indices", TINYGLTF_TYPE_SCALAR);
            for (size_t i = 0; i < indexView.count; ++i) {
                uint32_t idx = index(indexView, i);
                if (idx >= count)
                    fail(what + " has index " + std::to_string(idx) + " but only " + std::to_string(count) +
                         " vertices");
                indices.push_back(idx);
            }
        } else {
            for (size_t i = 0; i < count; ++i)
                indices.push_back(static_cast<uint32_t>(i));
        }
        if (indices.size() % 3 != 0)
            fail(what + " has " + std::to_string(indices.size()) + " indices, not a multiple of 3");

        glm::mat3 linear(world);
        glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
        // A mirroring transform turns the triangles inside out; swap two corners to undo it.
        bool flip = glm::determinant(linear) < 0.0f;
        uint32_t base = static_cast<uint32_t>(mesh_.positions.size());
        for (size_t i = 0; i < count; ++i) {
            glm::vec3 p(component(positions, i, 0, what), component(positions, i, 1, what),
                        component(positions, i, 2, what));
            mesh_.positions.push_back(glm::vec3(world * glm::vec4(p, 1.0f)));
        }
        int normalAccessor = attribute("NORMAL");
        if (normalAccessor >= 0) {
            View normals = view(normalAccessor, what + " NORMAL", TINYGLTF_TYPE_VEC3);
            if (normals.count != count)
                fail(what + " has " + std::to_string(normals.count) + " normals for " + std::to_string(count) +
                     " positions");
            for (size_t i = 0; i < count; ++i) {
                glm::vec3 n(component(normals, i, 0, what), component(normals, i, 1, what),
                            component(normals, i, 2, what));
                n = normalMatrix * n;
                float length = glm::length(n);
                // A degenerate transform (a zero scale) has no normal matrix: such normals point up.
                mesh_.normals.push_back(std::isfinite(length) && length > 1e-12f ? n / length
                                                                                 : glm::vec3(0.0f, 1.0f, 0.0f));
            }
        }
        int uvAccessor = attribute("TEXCOORD_0");
        if (uvAccessor >= 0) {
            View uvs = view(uvAccessor, what + " TEXCOORD_0", TINYGLTF_TYPE_VEC2);
            if (uvs.count != count)
                fail(what + " has " + std::to_string(uvs.count) + " texture coordinates for " + std::to_string(count) +
                     " positions");
            for (size_t i = 0; i < count; ++i)
                mesh_.uvs.emplace_back(component(uvs, i, 0, what), component(uvs, i, 1, what));
        } else {
            mesh_.uvs.resize(mesh_.positions.size(), glm::vec2(0.0f));
        }
        for (size_t i = 0; i < indices.size(); i += 3) {
            uint32_t a = base + indices[i], b = base + indices[i + 1], c = base + indices[i + 2];
            if (flip)
                std::swap(b, c);
            mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
        }
        if (normalAccessor < 0) {
            // Area-weighted face normals; a vertex on no triangle points up.
            std::vector<glm::vec3> sum(count, glm::vec3(0.0f));
            for (size_t i = mesh_.indices.size() - indices.size(); i < mesh_.indices.size(); i += 3) {
                uint32_t a = mesh_.indices[i], b = mesh_.indices[i + 1], c = mesh_.indices[i + 2];
                glm::vec3 n =
                    glm::cross(mesh_.positions[b] - mesh_.positions[a], mesh_.positions[c] - mesh_.positions[a]);
                sum[a - base] += n;
                sum[b - base] += n;
                sum[c - base] += n;
            }
            for (const glm::vec3& n : sum) {
                float length = glm::length(n);
                mesh_.normals.push_back(length > 1e-20f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f));
            }
        }
    }

    std::string file_;
    const tinygltf::Model& model_;
    PlantMesh mesh_;
};

} // namespace

PlantClump importGltfPlant(const std::filesystem::path& path) {
    std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error("glTF " + file +
                    (std::filesystem::exists(path, ec) ? ": is not a regular file (a folder or a device?)"
                                                       : ": cannot open (no such file)"));
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skipImage, nullptr);
    std::string err, warn;
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    bool ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                            : loader.LoadASCIIFromFile(&model, &err, &warn, file);
    if (!ok)
        throw Error("glTF " + file + ": cannot parse: " + trimmed(err.empty() ? warn : err));

    Importer importer(path, model);
    if (!model.skins.empty())
        importer.fail("uses skinning, which meadow cannot use");
    if (model.scenes.empty())
        importer.fail("has no scene, so there is no mesh to import");
    size_t sceneIndex = model.defaultScene >= 0 ? static_cast<size_t>(model.defaultScene) : 0;
    if (sceneIndex >= model.scenes.size())
        importer.fail("the default scene " + std::to_string(sceneIndex) + " does not exist");
    importer.walk(model.scenes[sceneIndex].nodes);

    PlantClump clump;
    clump.name = path.stem().string();
    clump.plants = 1;
    clump.mesh = std::move(importer.mesh());
    PlantMesh& mesh = clump.mesh;
    if (mesh.positions.empty() || mesh.indices.empty())
        importer.fail("has no mesh with triangles in its default scene");

    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : mesh.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            importer.fail("has a vertex position that is not finite");
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    float height = hi.y - lo.y;
    if (!(height >= kImportMinHeight && height <= kImportMaxHeight)) {
        std::ostringstream message;
        message << "wrong units? the plant is " << height << " m tall (glTF is in metres; meadow expects "
                << kImportMinHeight << " to " << kImportMaxHeight << " m)";
        importer.fail(message.str());
    }

    // Clump space: the base of the bounding box's centre axis at the origin, like the rhizomes
    // of the procedural clumps.
    glm::vec3 base(0.5f * (lo.x + hi.x), lo.y, 0.5f * (lo.z + hi.z));
    for (glm::vec3& p : mesh.positions)
        p -= base;
    lo -= base;

    // One rod up the centre of the bounding box: an imported plant sways as a whole.
    Rod rod;
    rod.kind = RodKind::Stem;
    rod.plant = 0;
    glm::vec2 axis(0.0f);
    float spacing = height / static_cast<float>(kImportRodNodes - 1);
    for (uint32_t k = 0; k < kImportRodNodes; ++k)
        rod.restNodes.emplace_back(axis.x, lo.y + spacing * static_cast<float>(k), axis.y);
    // Per node, the plant's horizontal extent in the band around it: its drag area and
    // collision radius.
    rod.width.assign(kImportRodNodes, 0.0f);
    for (const glm::vec3& p : mesh.positions) {
        uint32_t k = std::min(static_cast<uint32_t>(std::lround((p.y - lo.y) / spacing)), kImportRodNodes - 1);
        rod.width[k] = std::max(rod.width[k], 2.0f * glm::length(glm::vec2(p.x, p.z) - axis));
    }
    for (float& w : rod.width)
        w = std::max(w, 0.002f);
    // The asset says nothing about stiffness; a diameter of 1% of the height is a slender
    // herbaceous stem.
    rod.thickness = std::max(0.01f * height, 0.001f);
    clump.rods.push_back(std::move(rod));

    const Rod& r = clump.rods[0];
    for (const glm::vec3& p : mesh.positions) {
        float x = std::clamp((p.y - lo.y) / spacing, 0.0f, static_cast<float>(kImportRodNodes - 1));
        uint32_t segment = std::min(static_cast<uint32_t>(x), kImportRodNodes - 2);
        float t = x - static_cast<float>(segment);
        glm::vec3 onRod = glm::mix(r.restNodes[segment], r.restNodes[segment + 1], t);
        mesh.skin.push_back(SkinBinding{0, segment, t, p - onRod});
    }
    mesh.parts.assign(mesh.positions.size(), PartKind::Other);
    checkPlantClump(clump, "glTF " + file);
    return clump;
}

} // namespace meadow
