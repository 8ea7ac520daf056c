#include "gltf_import.h"

#include "core/error.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <tiny_gltf.h>
#include <unordered_map>

namespace meadow {
namespace {

// tinygltf's own file reader takes a folder for a file: on Linux a folder opens, and its end lies
// at 2^63 - 1, which it then tries to allocate. Every file tinygltf reads (the glTF file itself, a
// buffer or an image named by URI) comes through this reader instead, which reads only regular
// files of at most kMaxGltfFileBytes.
constexpr uintmax_t kMaxGltfFileBytes = uintmax_t(512) << 20;
// tinygltf puts the path before the reason.
bool readRegularFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    auto refuse = [&](const std::string& why) {
        if (err)
            *err += why;
        return false;
    };
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        return refuse("is not a regular file (a folder or a device?)");
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec)
        return refuse("cannot read its size (" + ec.message() + ")");
    if (size == 0)
        return refuse("the file is empty");
    if (size > kMaxGltfFileBytes)
        return refuse("is larger than the " + std::to_string(kMaxGltfFileBytes >> 20) + " MiB meadow reads");
    std::ifstream in(path, std::ios::binary);
    out->resize(static_cast<size_t>(size));
    if (!in || !in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size)) ||
        in.peek() != std::char_traits<char>::eof())
        return refuse("cannot be read whole (did it change while being read?)");
    return true;
}

// tinygltf hands every image's bytes (from a data URI, a file or a buffer view) to this loader.
// They are kept undecoded: only the base-colour textures the plant uses are decoded, with
// OpenImageIO (decodeImage), so an unused image in a format meadow cannot read does no harm.
// tinygltf (2.7) does not check an image's buffer view against its buffer before pointing into it:
// `model` (the one being loaded) is used to check it here, before a byte is read.
bool keepImageBytes(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                    const unsigned char* bytes, int size, void* model) {
    if (image->bufferView >= 0) {
        const tinygltf::Model& m = *static_cast<const tinygltf::Model*>(model);
        const size_t view = static_cast<size_t>(image->bufferView);
        bool inside = view < m.bufferViews.size();
        if (inside) {
            const tinygltf::BufferView& v = m.bufferViews[view];
            inside = v.buffer >= 0 && static_cast<size_t>(v.buffer) < m.buffers.size();
            if (inside) {
                const size_t have = m.buffers[static_cast<size_t>(v.buffer)].data.size();
                inside = v.byteOffset <= have && v.byteLength <= have - v.byteOffset &&
                         static_cast<size_t>(std::max(size, 0)) <= v.byteLength;
            }
        }
        if (!inside) {
            if (err)
                *err += "image " + std::to_string(index) + "'s buffer view lies outside its buffer";
            return false;
        }
    }
    image->image.assign(bytes, bytes + std::max(size, 0));
    image->as_is = true;
    return true;
}

constexpr int kWrapRepeat = TINYGLTF_TEXTURE_WRAP_REPEAT;
constexpr int kWrapMirror = TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
constexpr int kWrapClamp = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;

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
    std::vector<ImportedMaterial>& materials() { return materials_; }
    std::vector<uint32_t>& vertexMaterial() { return vertexMaterial_; }

  private:
    // The material of a primitive (-1: none), one entry per (material, whether the primitive has
    // TEXCOORD_0): without texture coordinates a texture cannot be placed, so the factor alone.
    uint32_t materialSlot(int materialIndex, bool hasUv) {
        const auto key = std::make_pair(materialIndex, hasUv || materialIndex < 0);
        auto found = slots_.find(key);
        if (found != slots_.end())
            return found->second;
        const uint32_t slot = static_cast<uint32_t>(materials_.size());
        materials_.push_back(readMaterial(materialIndex, key.second));
        slots_.emplace(key, slot);
        return slot;
    }

    ImportedMaterial readMaterial(int materialIndex, bool hasUv) const {
        ImportedMaterial out;
        if (materialIndex < 0) {
            out.name = "no material";
            out.leafGreen = true;
            return out;
        }
        if (static_cast<size_t>(materialIndex) >= model_.materials.size())
            fail("a primitive names material " + std::to_string(materialIndex) + ", which does not exist");
        const tinygltf::Material& material = model_.materials[static_cast<size_t>(materialIndex)];
        out.name = material.name.empty() ? "material " + std::to_string(materialIndex) : "'" + material.name + "'";
        const std::vector<double>& factor = material.pbrMetallicRoughness.baseColorFactor;
        if (factor.size() == 4)
            out.factor = glm::vec4(static_cast<float>(factor[0]), static_cast<float>(factor[1]),
                                   static_cast<float>(factor[2]), static_cast<float>(factor[3]));
        for (int c = 0; c < 4; ++c)
            if (!(out.factor[c] >= 0.0f && out.factor[c] <= 1.0f))
                fail("material " + out.name + " has a baseColorFactor outside 0..1");
        out.mask = material.alphaMode == "MASK";
        out.alphaCutoff = static_cast<float>(material.alphaCutoff);
        if (!std::isfinite(out.alphaCutoff))
            fail("material " + out.name + " has an alphaCutoff that is not finite");
        const tinygltf::TextureInfo& info = material.pbrMetallicRoughness.baseColorTexture;
        if (info.index < 0 || !hasUv)
            return out;
        const std::string what = "material " + out.name + " base colour texture";
        if (info.texCoord != 0)
            fail(what + " uses TEXCOORD_" + std::to_string(info.texCoord) + "; meadow reads only TEXCOORD_0");
        if (static_cast<size_t>(info.index) >= model_.textures.size())
            fail(what + " names texture " + std::to_string(info.index) + ", which does not exist");
        const tinygltf::Texture& texture = model_.textures[static_cast<size_t>(info.index)];
        if (texture.source < 0 || static_cast<size_t>(texture.source) >= model_.images.size())
            fail(what + " (texture " + std::to_string(info.index) +
                 ") has no image meadow can read (a PNG or JPEG source is needed)");
        if (texture.sampler >= 0) {
            if (static_cast<size_t>(texture.sampler) >= model_.samplers.size())
                fail(what + " names sampler " + std::to_string(texture.sampler) + ", which does not exist");
            const tinygltf::Sampler& sampler = model_.samplers[static_cast<size_t>(texture.sampler)];
            auto wrap = [](int mode) { return mode == kWrapMirror || mode == kWrapClamp ? mode : kWrapRepeat; };
            out.wrapS = wrap(sampler.wrapS);
            out.wrapT = wrap(sampler.wrapT);
        }
        decodeImage(static_cast<size_t>(texture.source), what, out);
        return out;
    }

    // The image's bytes (PNG or JPEG) decoded to 8-bit sRGB RGBA through OpenImageIO, read from
    // memory.
    void decodeImage(size_t imageIndex, const std::string& what, ImportedMaterial& out) const {
        const tinygltf::Image& image = model_.images[imageIndex];
        std::string name = "image " + std::to_string(imageIndex);
        if (!image.uri.empty())
            name += " ('" + image.uri + "')";
        else if (!image.name.empty())
            name += " '" + image.name + "'";
        const std::vector<unsigned char>& bytes = image.image;
        if (bytes.empty())
            fail(what + ": " + name + " cannot be read" + (image.uri.empty() ? "" : " (no such file?)"));
        const char* format = nullptr;
        if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0)
            format = "png";
        else if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff)
            format = "jpg";
        if (format == nullptr)
            fail(what + ": " + name + " is neither PNG nor JPEG, which are what meadow decodes");
        OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
        OIIO::Filesystem::IOProxy* proxy = &reader;
        OIIO::ImageSpec config;
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        config.attribute("oiio:UnassociatedAlpha", 1); // keep PNG colours as stored, not premultiplied
        const std::string decoder = std::string("meadow-texture.") + format; // the name picks the decoder
        std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(decoder, &config);
        if (!in)
            fail(what + ": " + name + " cannot be decoded: " + trimmed(OIIO::geterror()));
        const OIIO::ImageSpec& spec = in->spec();
        constexpr int kMaxSide = 16384;
        if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxSide || spec.height > kMaxSide ||
            spec.nchannels <= 0 || spec.depth != 1)
            fail(what + ": " + name + " is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                 " texels; meadow reads 2D images of 1 to " + std::to_string(kMaxSide) + " texels a side");
        const size_t w = static_cast<size_t>(spec.width), h = static_cast<size_t>(spec.height);
        const size_t channels = static_cast<size_t>(spec.nchannels);
        std::vector<uint8_t> pixels(w * h * channels);
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()))
            fail(what + ": " + name + " cannot be decoded: " + trimmed(in->geterror()));
        in->close();
        out.width = static_cast<uint32_t>(w);
        out.height = static_cast<uint32_t>(h);
        out.texels.resize(w * h * 4);
        for (size_t i = 0; i < w * h; ++i) {
            const uint8_t* p = &pixels[i * channels];
            uint8_t* q = &out.texels[i * 4];
            if (channels >= 3) {
                q[0] = p[0], q[1] = p[1], q[2] = p[2];
                q[3] = channels >= 4 ? p[3] : 255;
            } else { // grey, or grey and alpha
                q[0] = q[1] = q[2] = p[0];
                q[3] = channels == 2 ? p[1] : 255;
            }
        }
    }

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
        vertexMaterial_.resize(mesh_.positions.size(), materialSlot(primitive.material, uvAccessor >= 0));
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
    std::vector<ImportedMaterial> materials_;
    std::vector<uint32_t> vertexMaterial_;
    std::map<std::pair<int, bool>, uint32_t> slots_;
};

// --- Not a plant -------------------------------------------------------------------------------

// Whether the mesh is closed once welded by position, and what it encloses.
struct SolidMeasure {
    bool closed = false;
    double volume = 0.0; // |signed volume|, m^3
    double area = 0.0;   // one side, m^2
};

SolidMeasure measureSolid(const PlantMesh& mesh, glm::vec3 lo, glm::vec3 hi) {
    SolidMeasure out;
    const double weld = 1e-5 * std::max(double(glm::length(hi - lo)), 1e-9);
    struct KeyHash {
        size_t operator()(const std::array<int64_t, 3>& k) const {
            uint64_t h = 0xcbf29ce484222325ull;
            for (int64_t v : k)
                h = (h ^ static_cast<uint64_t>(v)) * 0x100000001b3ull;
            return static_cast<size_t>(h);
        }
    };
    std::unordered_map<std::array<int64_t, 3>, uint32_t, KeyHash> welded;
    std::vector<uint32_t> id(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const glm::dvec3 p = (glm::dvec3(mesh.positions[v]) - glm::dvec3(lo)) / weld;
        const std::array<int64_t, 3> key{std::llround(p.x), std::llround(p.y), std::llround(p.z)};
        id[v] = welded.emplace(key, static_cast<uint32_t>(welded.size())).first->second;
    }
    std::unordered_map<uint64_t, uint32_t> edges;
    double volume = 0.0;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t corner[3] = {mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]};
        const glm::dvec3 a = glm::dvec3(mesh.positions[corner[0]]) - glm::dvec3(lo);
        const glm::dvec3 b = glm::dvec3(mesh.positions[corner[1]]) - glm::dvec3(lo);
        const glm::dvec3 c = glm::dvec3(mesh.positions[corner[2]]) - glm::dvec3(lo);
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
        out.area += 0.5 * glm::length(glm::cross(b - a, c - a));
        for (int e = 0; e < 3; ++e) {
            uint64_t p = id[corner[e]], q = id[corner[(e + 1) % 3]];
            if (p == q)
                continue; // a degenerate triangle's collapsed edge
            ++edges[std::min(p, q) << 32 | std::max(p, q)];
        }
    }
    out.closed = !edges.empty() && std::all_of(edges.begin(), edges.end(), [](auto& e) { return e.second == 2; });
    out.volume = std::abs(volume);
    return out;
}

std::string fixed(double value, int digits) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(digits) << value;
    return text.str();
}

// --- Painting into the atlas ---------------------------------------------------------------------

// A texture in linear colour (alpha as stored), sampled with its wrap modes.
class LinearTexture {
  public:
    explicit LinearTexture(const ImportedMaterial& m)
        : width_(m.width), height_(m.height), wrapS_(m.wrapS), wrapT_(m.wrapT), texels_(size_t(m.width) * m.height) {
        for (size_t i = 0; i < texels_.size(); ++i) {
            const uint8_t* p = &m.texels[i * 4];
            texels_[i] = glm::vec4(srgbToLinear(p[0]), srgbToLinear(p[1]), srgbToLinear(p[2]), float(p[3]) / 255.0f);
        }
    }

    // The mean of up to 8 x 8 bilinear samples over a footprint `size` (UV) around `uv`, so that
    // a texel covering many of the texture's texels averages them instead of aliasing.
    glm::vec4 filtered(glm::dvec2 uv, glm::dvec2 size) const {
        const int nx = static_cast<int>(std::clamp(std::ceil(size.x * double(width_)), 1.0, 8.0));
        const int ny = static_cast<int>(std::clamp(std::ceil(size.y * double(height_)), 1.0, 8.0));
        glm::vec4 sum(0.0f);
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x)
                sum += bilinear(uv + size * glm::dvec2((x + 0.5) / nx - 0.5, (y + 0.5) / ny - 0.5));
        return sum / float(nx * ny);
    }

  private:
    static int64_t wrap(int64_t i, int64_t n, int mode) {
        if (mode == kWrapClamp)
            return std::clamp<int64_t>(i, 0, n - 1);
        if (mode == kWrapMirror) {
            const int64_t j = ((i % (2 * n)) + 2 * n) % (2 * n);
            return j < n ? j : 2 * n - 1 - j;
        }
        return ((i % n) + n) % n;
    }
    glm::vec4 texel(int64_t x, int64_t y) const {
        return texels_[size_t(wrap(y, height_, wrapT_)) * width_ + size_t(wrap(x, width_, wrapS_))];
    }
    // Repeating modes repeat every 2 (mirrored: every 2, plain: every 1), and clamping is the same
    // everywhere beyond [-1, 2]: reducing UVs there keeps the texel indices small.
    static double reduce(double u, int mode) {
        return mode == kWrapClamp ? std::clamp(u, -1.0, 2.0) : u - 2.0 * std::floor(0.5 * u);
    }
    glm::vec4 bilinear(glm::dvec2 uv) const {
        const double x = reduce(uv.x, wrapS_) * double(width_) - 0.5;
        const double y = reduce(uv.y, wrapT_) * double(height_) - 0.5;
        const double x0 = std::floor(x), y0 = std::floor(y);
        const float fx = float(x - x0), fy = float(y - y0);
        const auto ix = static_cast<int64_t>(x0), iy = static_cast<int64_t>(y0);
        const glm::vec4 top = glm::mix(texel(ix, iy), texel(ix + 1, iy), fx);
        const glm::vec4 bottom = glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), fx);
        return glm::mix(top, bottom, fy);
    }

    int64_t width_, height_;
    int wrapS_, wrapT_;
    std::vector<glm::vec4> texels_;
};

} // namespace

ImportedPlant importGltfPlantWithMaterials(const std::filesystem::path& path, const GltfImportOptions& options) {
    std::string file = path.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error("glTF " + file +
                    (std::filesystem::exists(path, ec) ? ": is not a regular file (a folder or a device?)"
                                                       : ": cannot open (no such file)"));
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keepImageBytes, &model);
    loader.SetFsCallbacks(
        {&tinygltf::FileExists, &tinygltf::ExpandFilePath, &readRegularFile, &tinygltf::WriteWholeFile, nullptr});
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

    ImportedPlant imported;
    imported.materials = std::move(importer.materials());
    imported.vertexMaterial = std::move(importer.vertexMaterial());
    PlantClump& clump = imported.clump;
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

    // Not a plant: a closed solid that fills much of its box and is thick for its size.
    const SolidMeasure solid = measureSolid(mesh, lo, hi);
    const glm::dvec3 extent = glm::dvec3(hi) - glm::dvec3(lo);
    const double boxVolume = extent.x * extent.y * extent.z;
    const double longest = std::max({extent.x, extent.y, extent.z});
    if (solid.closed && boxVolume > 0.0 && solid.area > 0.0) {
        const double fill = solid.volume / boxVolume;
        const double thickness = 2.0 * solid.volume / solid.area;
        if (fill > kImportSolidMaxFill && thickness > kImportSolidMaxThickness * longest)
            importer.fail("is a closed solid enclosing " + fixed(100.0 * fill, 0) + "% of its bounding box (" +
                          fixed(boxVolume, 2) + " m³) with a mean thickness of " + fixed(thickness, 2) + " m (" +
                          fixed(100.0 * thickness / longest, 0) + "% of its " + fixed(longest, 2) +
                          " m extent), not a plant: meadow simulates thin blades and stems on elastic rods");
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
    auto nodeAt = [&](float y) {
        return std::min(static_cast<uint32_t>(std::lround(std::max(y - lo.y, 0.0f) / spacing)), kImportRodNodes - 1);
    };
    for (uint32_t k = 0; k < kImportRodNodes; ++k)
        rod.restNodes.emplace_back(axis.x, lo.y + spacing * static_cast<float>(k), axis.y);
    // The foliage, each triangle on the node at its height: its mass, and its drag. Per node the
    // width (drag area per length; a lone rod has no contacts, so it is no collision radius) is
    // half the band's one-sided area over the band's length (leaves face the wind at all angles),
    // at most the plant's horizontal extent there.
    rod.nodeMass.assign(kImportRodNodes, 0.0f);
    std::vector<float> bandArea(kImportRodNodes, 0.0f), reach(kImportRodNodes, 0.0f);
    double foliage = 0.0;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                        c = mesh.positions[mesh.indices[i + 2]];
        const float area = 0.5f * glm::length(glm::cross(b - a, c - a));
        const uint32_t k = nodeAt((a.y + b.y + c.y) / 3.0f);
        rod.nodeMass[k] += area * kImportLeafArealDensity;
        bandArea[k] += area;
        foliage += area * kImportLeafArealDensity;
    }
    for (const glm::vec3& p : mesh.positions) {
        uint32_t k = nodeAt(p.y);
        reach[k] = std::max(reach[k], 2.0f * glm::length(glm::vec2(p.x, p.z) - axis));
    }
    rod.width.assign(kImportRodNodes, 0.0f);
    for (uint32_t k = 0; k < kImportRodNodes; ++k) {
        const float band = k == 0 || k + 1 == kImportRodNodes ? 0.5f * spacing : spacing;
        rod.width[k] = std::max(std::min(0.5f * bandArea[k] / band, reach[k]), 0.002f);
    }
    // The stem: its diameter from the scene, or the one whose rigidity bends the plant held out
    // level by kImportDefaultSag of its length under its own weight, stem included (a fixed
    // point: the stem's mass grows as the square root of the rigidity asks).
    constexpr double kGravity = 9.81;
    auto rigidityOf = [](double d) { return double(kImportStemModulus) * glm::pi<double>() * std::pow(d, 4.0) / 64.0; };
    auto stemMass = [&](double d) { return double(kImportStemDensity) * glm::pi<double>() * 0.25 * d * d * height; };
    double diameter = options.stemDiameter ? double(*options.stemDiameter) : 0.01 * double(height);
    if (!options.stemDiameter)
        for (int iteration = 0; iteration < 16; ++iteration) {
            const double rigidity = (foliage + stemMass(diameter)) * kGravity * double(height) * double(height) /
                                    (8.0 * double(kImportDefaultSag));
            diameter = std::pow(64.0 * rigidity / (double(kImportStemModulus) * glm::pi<double>()), 0.25);
        }
    if (!(diameter > 0.0) || !std::isfinite(diameter))
        importer.fail("has no usable stem diameter (" + std::to_string(diameter) + " m)");
    rod.thickness = static_cast<float>(diameter);
    rod.bendRigidity = static_cast<float>(rigidityOf(diameter));
    rod.linearDensity = static_cast<float>(stemMass(diameter) / double(height));
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
    if (imported.vertexMaterial.size() != mesh.positions.size())
        importer.fail("lost track of its materials (" + std::to_string(imported.vertexMaterial.size()) + " for " +
                      std::to_string(mesh.positions.size()) + " vertices)");
    return imported;
}

PlantClump importGltfPlant(const std::filesystem::path& path, const GltfImportOptions& options) {
    return importGltfPlantWithMaterials(path, options).clump;
}

void paintImportedPlant(ImportedPlant& plant, TextureAtlas& atlas) {
    PlantMesh& mesh = plant.clump.mesh;
    if (plant.vertexMaterial.size() != mesh.uvs.size())
        throw Error("imported plant " + plant.clump.name + ": " + std::to_string(plant.vertexMaterial.size()) +
                    " vertex materials for " + std::to_string(mesh.uvs.size()) + " vertices");
    if (atlas.width == 0 || atlas.height != atlas.width || atlas.rgba.size() != size_t(atlas.width) * atlas.height * 4)
        throw Error("imported plant " + plant.clump.name + ": the atlas is empty or not square");
    for (uint32_t m : plant.vertexMaterial)
        if (m >= plant.materials.size())
            throw Error("imported plant " + plant.clump.name + ": a vertex names material " + std::to_string(m) +
                        " of " + std::to_string(plant.materials.size()));

    // Materials used by some vertex and not leaf green get a cell of the import region each.
    std::vector<uint8_t> used(plant.materials.size(), 0);
    for (uint32_t m : plant.vertexMaterial)
        used[m] = 1;
    std::vector<uint32_t> cellIndex(plant.materials.size(), UINT32_MAX);
    uint32_t cells = 0;
    for (size_t m = 0; m < plant.materials.size(); ++m)
        if (used[m] && !plant.materials[m].leafGreen)
            cellIndex[m] = cells++;

    const AtlasRegion leafRegion = irisAtlasRegion(PartKind::Leaf);
    const glm::vec2 leaf = 0.5f * (leafRegion.min + leafRegion.max);
    const AtlasCell importCell = importAtlasCell(atlas.width);
    const uint32_t columns = cells == 0 ? 1 : static_cast<uint32_t>(std::ceil(std::sqrt(double(cells))));
    const uint32_t rows = cells == 0 ? 1 : (cells + columns - 1) / columns;
    const float size = static_cast<float>(atlas.width);
    for (size_t m = 0; m < plant.materials.size(); ++m) {
        const ImportedMaterial& material = plant.materials[m];
        if (cellIndex[m] == UINT32_MAX) {
            if (used[m])
                for (size_t v = 0; v < mesh.uvs.size(); ++v)
                    if (plant.vertexMaterial[v] == m)
                        mesh.uvs[v] = leaf;
            continue;
        }
        const uint32_t col = cellIndex[m] % columns, row = cellIndex[m] / columns;
        const uint32_t cw = importCell.x1 - importCell.x0, ch = importCell.y1 - importCell.y0;
        const uint32_t x0 = importCell.x0 + cw * col / columns, x1 = importCell.x0 + cw * (col + 1) / columns;
        const uint32_t y0 = importCell.y0 + ch * row / rows, y1 = importCell.y0 + ch * (row + 1) / rows;
        // Painted a few texels beyond the UV rectangle, with its edge colours (as the iris parts).
        const uint32_t side = std::min(x1 - x0, y1 - y0);
        const uint32_t pad = std::min(std::max(2u, side / 32), (side - 1) / 2);
        const AtlasRegion region{glm::vec2(float(x0 + pad), float(y0 + pad)) / size,
                                 glm::vec2(float(x1 - pad), float(y1 - pad)) / size};
        const bool textured = material.width > 0 && material.height > 0 &&
                              material.texels.size() == size_t(material.width) * material.height * 4;

        // The texture's UV box: [0, 1] when every UV lies in it, else whole periods around them.
        glm::dvec2 boxMin(0.0), boxMax(1.0);
        if (textured) {
            glm::dvec2 lo(INFINITY), hi(-INFINITY);
            for (size_t v = 0; v < mesh.uvs.size(); ++v)
                if (plant.vertexMaterial[v] == m) {
                    lo = glm::min(lo, glm::dvec2(mesh.uvs[v]));
                    hi = glm::max(hi, glm::dvec2(mesh.uvs[v]));
                }
            if (lo.x < 0.0 || lo.y < 0.0 || hi.x > 1.0 || hi.y > 1.0) {
                boxMin = glm::floor(lo);
                boxMax = glm::max(glm::ceil(hi), boxMin + 1.0);
            }
        }
        const glm::dvec2 boxSize = boxMax - boxMin;

        std::optional<LinearTexture> texture;
        if (textured)
            texture.emplace(material);
        const glm::dvec2 regionSize = glm::dvec2(region.max - region.min);
        const glm::dvec2 footprint = boxSize / (regionSize * double(size)); // one atlas texel, in texture UV
        for (uint32_t y = y0; y < y1; ++y)
            for (uint32_t x = x0; x < x1; ++x) {
                const glm::dvec2 uv((x + 0.5) / size, (y + 0.5) / size);
                const glm::dvec2 local = glm::clamp((uv - glm::dvec2(region.min)) / regionSize, 0.0, 1.0);
                glm::vec4 colour = material.factor;
                if (texture)
                    colour *= texture->filtered(boxMin + local * boxSize, footprint);
                uint8_t* pixel = &atlas.rgba[(size_t(y) * atlas.width + x) * 4];
                pixel[0] = linearToSrgb(colour.r);
                pixel[1] = linearToSrgb(colour.g);
                pixel[2] = linearToSrgb(colour.b);
                pixel[3] = !material.mask || colour.a >= material.alphaCutoff ? 255 : 0;
            }
        for (size_t v = 0; v < mesh.uvs.size(); ++v) {
            if (plant.vertexMaterial[v] != m)
                continue;
            if (!textured) {
                mesh.uvs[v] = 0.5f * (region.min + region.max);
                continue;
            }
            const glm::dvec2 local = (glm::dvec2(mesh.uvs[v]) - boxMin) / boxSize;
            mesh.uvs[v] = region.map(glm::vec2(local));
        }
    }
}

} // namespace meadow
