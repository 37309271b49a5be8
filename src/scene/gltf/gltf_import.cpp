// glTF files to GltfContent (gltf_import.hpp): tinygltf parses, this file walks
// the node tree and converts images, cameras and lights; primitives are
// gltf_geometry.cpp's, material factors and modes gltf_materials.cpp's.
#include "scene/gltf/gltf_import.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <system_error>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tbb/parallel_for.h>
#include <tiny_gltf.h>

#include "io/input_file.hpp"
#include "io/memory_budget.hpp"
#include "scene/gltf/gltf_animation.hpp"
#include "scene/gltf/gltf_compression.hpp"
#include "scene/gltf/gltf_extensions.hpp"
#include "scene/gltf/gltf_geometry.hpp"
#include "scene/gltf/gltf_json_checks.hpp"
#include "scene/gltf/gltf_materials.hpp"
#include "scene/scene_validation.hpp"
#include "texture/texture.hpp"

namespace tessera {
namespace {

using gltf::fail;
namespace fs = std::filesystem;

constexpr float kRadiansToDegrees = 57.29577951308232f;

std::int64_t nanoseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count();
}

std::string one_line(std::string message) {
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    for (std::size_t at = message.find('\n'); at != std::string::npos; at = message.find('\n', at))
        message.replace(at, 1, "; ");
    return message.empty() ? std::string("unknown error") : message;
}

std::string quoted(const std::string& text) {
    std::string result(1, '\'');
    result += text;
    result += '\'';
    return result;
}

std::string indexed(const char* array, std::size_t index, const std::string& name) {
    std::string label = std::string(array) + "[" + std::to_string(index) + "]";
    if (!name.empty()) label += " " + quoted(name);
    return label;
}

// ---- Reading the file with tinygltf -------------------------------------------------------------

// What tinygltf's callbacks need: the model being filled (for image buffer views),
// whether files may be read, and from where.
struct LoadContext {
    const tinygltf::Model* model = nullptr;
    bool read_external_files = true;
    bool allow_external_uris = false;
    std::string base;         // the folder as given to tinygltf, which joins it and a URI with '/'
    fs::path folder;          // the same, canonical: every file read must resolve inside it
    std::string refusal;      // the first URI refused, why (reported even where tinygltf only warns)
};

// What a glTF file may hold whole (the format's 4 GB limit) within the memory budget.
std::uint64_t max_gltf_bytes() { return std::min<std::uint64_t>(io::memory_budget(), 0xFFFFFFFFull); }

// The whole file in one read of its size (a byte-wise istreambuf_iterator copy
// took 0.3 s per 2048² PNG of BoomBox on this machine); FIFOs, devices and files
// over the limit are refused before reading (io::InputFileError).
void read_file_bytes(const fs::path& path, std::vector<unsigned char>& bytes, std::string_view kind) {
    bytes = io::read_input_file(path, max_gltf_bytes(), kind);
}

// Why tinygltf's `path` (base + '/' + the percent-decoded URI, or "./" + URI as its
// fallback) must not be read, or "" if it may.
std::string uri_refusal(const std::string& path, const LoadContext& context) {
    const std::string prefix = context.base.back() == '/' ? context.base : context.base + "/";
    if (path.compare(0, prefix.size(), prefix) != 0) return "-";  // tinygltf's "." fallback: never
    const std::string uri = path.substr(prefix.size());
    const auto refuse = [&](const std::string& why) {
        return "the URI " + quoted(uri) + " " + why + "; only files inside the model's folder " +
               quoted(context.folder.string()) +
               " are read (--allow-external-uris, or allow_external_uris = true in the scene's [[models]] entry, "
               "allows others)";
    };
    if (uri.empty()) return "-";
    if (uri.front() == '/' || uri.front() == '\\') return refuse("is an absolute path");
    const std::size_t colon = uri.find(':');
    if (colon != std::string::npos && colon > 0 && uri.find('/') > colon &&
        std::all_of(uri.begin(), uri.begin() + std::ptrdiff_t(colon),
                    [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.'; }))
        return "the URI " + quoted(uri) + " has a scheme (" + uri.substr(0, colon) +
               ":); only relative file paths and data: URIs are read";
    const fs::path relative = fs::path(uri).lexically_normal();
    if (!relative.empty() && *relative.begin() == "..") return refuse("leaves the model's folder");
    std::error_code error;
    const fs::path resolved = fs::weakly_canonical(context.folder / relative, error);
    if (!error) {
        const fs::path inside = resolved.lexically_relative(context.folder);
        if (inside.empty() || *inside.begin() == "..")
            return refuse("resolves (through a symbolic link) outside the model's folder");
    }
    return "";
}

bool file_exists(const std::string& path, void* user) {
    auto* context = static_cast<LoadContext*>(user);
    if (!context->read_external_files) return false;
    if (!context->allow_external_uris) {
        const std::string why = uri_refusal(path, *context);
        if (why == "-") return false;
        if (!why.empty()) {
            if (context->refusal.empty()) context->refusal = why;
            return false;
        }
    }
    // A FIFO or device exists too: read_whole_file refuses it by name (io/input_file.hpp), saying so.
    std::error_code error;
    return fs::exists(path, error);
}

std::string expand_nothing(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    if (!file_exists(path, user)) {
        if (err) *err += "not a readable file";
        return false;
    }
    try {
        read_file_bytes(path, *out, "glTF buffer or image");
    } catch (const std::exception& e) {  // io::InputFileError, or no memory for it
        if (err) *err += e.what();
        return false;
    }
    return true;
}

bool write_nothing(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Images are kept encoded (as_is) and decoded later, only those materials use,
// each in the colour space its use needs. An image in a buffer view is checked
// against the buffer first: tinygltf hands over a pointer without checking.
bool keep_encoded_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                        const unsigned char* bytes, int size, void* user) {
    const auto* context = static_cast<const LoadContext*>(user);
    if (image->bufferView >= 0) {
        const tinygltf::Model& model = *context->model;
        const auto view_index = std::size_t(image->bufferView);
        const tinygltf::BufferView& view = model.bufferViews.at(view_index);  // tinygltf checked the index
        const tinygltf::Buffer& buffer = model.buffers.at(std::size_t(view.buffer));
        std::size_t end = 0;
        if (__builtin_add_overflow(view.byteOffset, view.byteLength, &end) || end > buffer.data.size() ||
            view.byteLength > std::size_t(std::numeric_limits<int>::max())) {
            if (err)
                *err += "images[" + std::to_string(index) + "]: bufferView " + std::to_string(view_index) +
                        " runs past the end of its buffer";
            return false;
        }
    }
    if (size < 0 || (size > 0 && bytes == nullptr)) {
        if (err) *err += "images[" + std::to_string(index) + "]: no data";
        return false;
    }
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

tinygltf::Model parse_model(std::span<const std::uint8_t> bytes, const std::string& source, const fs::path& base_dir,
                            const GltfReadOptions& options) {
    if (bytes.size() > std::numeric_limits<unsigned int>::max())
        fail(source, "file of " + std::to_string(bytes.size()) + " bytes is larger than glTF's 4 GB limit");
    tinygltf::Model model;
    LoadContext context{&model, options.read_external_files, options.allow_external_uris,
                        base_dir.empty() ? std::string(".") : base_dir.string(), {}, {}};
    std::error_code canonical_error;
    context.folder = fs::weakly_canonical(context.base, canonical_error);
    if (canonical_error) context.folder = fs::absolute(context.base).lexically_normal();
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keep_encoded_image, &context);
    loader.SetFsCallbacks({file_exists, expand_nothing, read_whole_file, write_nothing, &context});
    std::string err, warn;
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    gltf::check_json_before_parsing(bytes, binary, source);
    // Meshopt fallback buffers and Draco indices, which tinygltf would refuse (gltf_compression.hpp).
    const gltf::ParseInput input = gltf::prepare_for_tinygltf(bytes, binary);
    if (!input.bytes.empty()) bytes = input.bytes;
    if (bytes.size() > std::numeric_limits<unsigned int>::max())
        fail(source, "file of " + std::to_string(bytes.size()) + " bytes is larger than glTF's 4 GB limit");
    bool loaded = false;
    try {
        loaded = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()),
                                                      context.base)
                        : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                                     unsigned(bytes.size()), context.base);
    } catch (const std::exception& e) {
        err = e.what();
    }
    if (!context.refusal.empty()) fail(source, context.refusal);
    if (!loaded) {
        std::string message = (binary ? "invalid glTF binary (.glb): " : "invalid glTF: ") + one_line(err);
        if (err.find("File not found") != std::string::npos || err.find("File read error") != std::string::npos)
            message += options.read_external_files ? " (looked in " + quoted(base_dir.string()) + ")"
                                                   : " (external files are not read here)";
        fail(source, message);
    }
    gltf::decode_compressed_geometry(model, source, input.fallback_buffers);
    return model;
}

// ---- Converting the model ----------------------------------------------------------------------

bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

class GltfReader {
public:
    GltfReader(const tinygltf::Model& model, std::string source, fs::path base_dir, const GltfReadOptions& options)
        : model_(model), source_(std::move(source)), base_dir_(std::move(base_dir)), options_(options) {}

    GltfContent read() {
        auto start = std::chrono::steady_clock::now();
        gltf::check_extensions(model_, source_, content_.warnings);
        content_.cameras.resize(model_.cameras.size());
        for (std::size_t c = 0; c < model_.cameras.size(); ++c)
            content_.cameras[c].name = model_.cameras[c].name, content_.cameras[c].type = model_.cameras[c].type;
        walk_nodes();
        // The file's first camera is the one a viewer shows first: say when it is not the one used.
        if (!content_.cameras.empty() && !content_.cameras[0].view) {
            const std::string first = indexed("cameras", 0, content_.cameras[0].name);
            std::size_t used = 0;
            while (used < content_.cameras.size() && !content_.cameras[used].view) ++used;
            content_.warnings.push_back(first + " is skipped: no node of the scene places it; " +
                                        (used < content_.cameras.size()
                                             ? "using " + indexed("cameras", used, content_.cameras[used].name)
                                             : std::string("framing the model instead")));
        }
        content_.rig = gltf::read_rig(model_, source_, content_, object_nodes_, object_instances_, mesh_sources_);
        gltf_import_times().convert_ns += nanoseconds_since(start);
        start = std::chrono::steady_clock::now();
        decode_textures();
        gltf_import_times().images_ns += nanoseconds_since(start);
        const auto finish = [&](GltfCamera& camera) {
            if (camera.camera.far_plane == std::numeric_limits<float>::infinity())
                camera.camera.far_plane = far_plane_covering(camera.camera, content_.bounds);
        };
        if (content_.camera) finish(*content_.camera);
        for (PlacedGltfCamera& placed : content_.cameras)
            if (placed.view) finish(*placed.view);
        return std::move(content_);
    }

private:
    [[noreturn]] void fail(const std::string& message) const { gltf::fail(source_, message); }

    // ---- Nodes

    std::vector<int> root_nodes() const {
        if (model_.defaultScene >= 0 || !model_.scenes.empty()) {
            const int scene = std::max(model_.defaultScene, 0);
            if (std::size_t(scene) >= model_.scenes.size())
                fail("the default scene is scene " + std::to_string(scene) + " but the file has " +
                     std::to_string(model_.scenes.size()) + " scenes");
            return model_.scenes[std::size_t(scene)].nodes;
        }
        // No scenes: every node that is nobody's child.
        std::vector<bool> is_child(model_.nodes.size(), false);
        for (const tinygltf::Node& node : model_.nodes)
            for (const int child : node.children)
                if (child >= 0 && std::size_t(child) < is_child.size()) is_child[std::size_t(child)] = true;
        std::vector<int> roots;
        for (std::size_t n = 0; n < model_.nodes.size(); ++n)
            if (!is_child[n]) roots.push_back(int(n));
        return roots;
    }

    glm::mat4 local_transform(const tinygltf::Node& node, const std::string& label) const {
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(label + " has a matrix of " + std::to_string(node.matrix.size()) + " numbers, expected 16");
            glm::dmat4 matrix;
            std::copy(node.matrix.begin(), node.matrix.end(), glm::value_ptr(matrix));  // both column-major
            return glm::mat4(matrix);
        }
        glm::mat4 transform(1.0f);
        if (!node.translation.empty()) {
            if (node.translation.size() != 3) fail(label + " has a translation of " + std::to_string(node.translation.size()) + " numbers, expected 3");
            transform = glm::translate(transform, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
        }
        if (!node.rotation.empty()) {
            if (node.rotation.size() != 4) fail(label + " has a rotation of " + std::to_string(node.rotation.size()) + " numbers, expected 4 (a quaternion)");
            // glTF stores x, y, z, w; glm's constructor takes w first.
            const glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));
            const float length = glm::length(q);
            if (!(length > 0.0f) || !std::isfinite(length)) fail(label + " has a rotation quaternion of length 0 or not finite");
            transform = transform * glm::mat4_cast(q / length);
        }
        if (!node.scale.empty()) {
            if (node.scale.size() != 3) fail(label + " has a scale of " + std::to_string(node.scale.size()) + " numbers, expected 3");
            transform = glm::scale(transform, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
        }
        return transform;
    }

    // Depth first, in node order; a node reached twice means the graph is not a
    // forest (a cycle, or a shared child), which glTF forbids.
    // glTF's nodes form a forest: each node the child of at most one node, no
    // cycles. Checked over every node, not only those a scene reaches: a file
    // whose nodes all sit in cycles has no roots, and drew nothing.
    void check_node_forest() const {
        const std::size_t count = model_.nodes.size();
        std::vector<int> parent(count, -1);
        for (std::size_t n = 0; n < count; ++n)
            for (const int child : model_.nodes[n].children) {
                if (child < 0 || std::size_t(child) >= count)
                    fail(indexed("nodes", n, model_.nodes[n].name) + " has child " + std::to_string(child) +
                         " but the file has " + std::to_string(count) + " nodes");
                if (parent[std::size_t(child)] >= 0)
                    fail(indexed("nodes", std::size_t(child), model_.nodes[std::size_t(child)].name) +
                         " is a child of both nodes " + std::to_string(parent[std::size_t(child)]) + " and " +
                         std::to_string(n) + "; glTF nodes form a forest (one parent at most)");
                parent[std::size_t(child)] = int(n);
            }
        // With one parent each, a node is in a cycle exactly when following parents never ends at a root.
        std::vector<char> state(count, 0);  // 0 unknown, 1 on the current path, 2 reaches a root
        for (std::size_t n = 0; n < count; ++n) {
            std::vector<std::size_t> path;
            std::size_t at = n;
            while (state[at] == 0) {
                state[at] = 1;
                path.push_back(at);
                if (parent[at] < 0) break;
                at = std::size_t(parent[at]);
            }
            if (state[at] == 1 && parent[at] >= 0)
                fail(indexed("nodes", at, model_.nodes[at].name) +
                     " is its own ancestor (a cycle of children); glTF nodes form a forest");
            for (const std::size_t p : path) state[p] = 2;
        }
    }

    void walk_nodes() {
        check_node_forest();
        std::vector<bool> visited(model_.nodes.size(), false);
        struct Pending {
            int node;
            glm::mat4 parent_world;
        };
        std::vector<Pending> stack;
        const std::vector<int> roots = root_nodes();
        for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.push_back({*root, glm::mat4(1.0f)});
        while (!stack.empty()) {
            const Pending pending = stack.back();
            stack.pop_back();
            if (pending.node < 0 || std::size_t(pending.node) >= model_.nodes.size())
                fail("a scene or node refers to node " + std::to_string(pending.node) + " but the file has " +
                     std::to_string(model_.nodes.size()) + " nodes");
            const auto index = std::size_t(pending.node);
            const tinygltf::Node& node = model_.nodes[index];
            const std::string label = indexed("nodes", index, node.name);
            if (visited[index]) fail(label + " is reached twice from the scene; glTF nodes form a tree (no cycles or shared children)");
            visited[index] = true;
            const glm::mat4 world = pending.parent_world * local_transform(node, label);
            if (!finite(world)) fail(label + " has a world transform that is not finite");
            if (node.mesh >= 0) {
                const std::vector<glm::mat4> instances = gpu_instances(node, label);
                if (instances.empty()) place_mesh(node.mesh, world, label, pending.node, glm::mat4(1.0f));
                for (const glm::mat4& instance : instances) place_mesh(node.mesh, world, label, pending.node, instance);
            }
            node_name_ = node.name;
            if (node.camera >= 0) read_camera(node.camera, world, label);
            read_node_light(node, world, label);
            for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
                stack.push_back({*child, world});
        }
    }

    // ---- Meshes

    struct PlacedPrimitive {
        std::uint32_t mesh;
        std::uint32_t material;
    };

    // EXT_mesh_gpu_instancing: one transform T·R·S per instance, applied before the
    // node's own (world × instance); empty when the node has none. The mesh is
    // converted once and each instance is one more Object drawing it.
    std::vector<glm::mat4> gpu_instances(const tinygltf::Node& node, const std::string& node_label) const {
        const auto extension = node.extensions.find("EXT_mesh_gpu_instancing");
        if (extension == node.extensions.end()) return {};
        const std::string what = node_label + " EXT_mesh_gpu_instancing";
        const tinygltf::Value& attributes = extension->second.Get("attributes");
        if (!attributes.IsObject()) fail(what + " has no 'attributes' object");
        constexpr int f32 = TINYGLTF_COMPONENT_TYPE_FLOAT, i8 = TINYGLTF_COMPONENT_TYPE_BYTE,
                      i16 = TINYGLTF_COMPONENT_TYPE_SHORT;
        struct Column {
            const char* name;
            int type;
            std::vector<float> values;
        };
        Column columns[] = {{"TRANSLATION", TINYGLTF_TYPE_VEC3, {}}, {"ROTATION", TINYGLTF_TYPE_VEC4, {}},
                            {"SCALE", TINYGLTF_TYPE_VEC3, {}}};
        std::size_t count = 0;
        const char* counted = nullptr;
        for (Column& column : columns) {
            const tinygltf::Value& accessor = attributes.Get(column.name);
            if (!accessor.IsInt()) {
                if (accessor.Type() != tinygltf::NULL_TYPE) fail(what + " " + column.name + " is not an accessor index");
                continue;
            }
            const std::string label = what + " " + column.name;
            // The extension's types: floats, and for ROTATION normalized bytes and shorts.
            column.values = column.type == TINYGLTF_TYPE_VEC4
                                ? gltf::read_accessor_floats(model_, accessor.GetNumberAsInt(), source_, label,
                                                             column.type, {f32, i8, i16}, true)
                                : gltf::read_accessor_floats(model_, accessor.GetNumberAsInt(), source_, label,
                                                             column.type, {f32}, false);
            const std::size_t n = column.values.size() / (column.type == TINYGLTF_TYPE_VEC4 ? 4 : 3);
            if (counted && n != count)
                fail(label + " (accessor " + std::to_string(accessor.GetNumberAsInt()) + ") has " + std::to_string(n) +
                     " elements but " + counted + " has " + std::to_string(count) +
                     "; every instancing attribute has one element per instance");
            count = n, counted = column.name;
        }
        if (!counted) fail(what + " has none of TRANSLATION, ROTATION, SCALE");
        if (count == 0) fail(what + " has 0 instances");
        std::vector<glm::mat4> instances(count);
        for (std::size_t i = 0; i < count; ++i) {
            glm::mat4 m(1.0f);
            if (const auto& t = columns[0].values; !t.empty())
                m = glm::translate(m, glm::vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]));
            if (const auto& r = columns[1].values; !r.empty()) {
                const glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);  // glTF: x, y, z, w
                const float length = glm::length(q);
                if (!(length > 0.0f) || !std::isfinite(length))
                    fail(what + " ROTATION element " + std::to_string(i) + " is a quaternion of length 0 or not finite");
                m = m * glm::mat4_cast(q / length);
            }
            if (const auto& s = columns[2].values; !s.empty())
                m = glm::scale(m, glm::vec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
            if (!finite(m)) fail(what + " element " + std::to_string(i) + " has a transform that is not finite");
            instances[i] = m;
        }
        return instances;
    }

    void place_mesh(int mesh_index, const glm::mat4& world, const std::string& node_label, int node,
                    const glm::mat4& instance) {
        if (std::size_t(mesh_index) >= model_.meshes.size())
            fail(node_label + " uses mesh " + std::to_string(mesh_index) + " but the file has " +
                 std::to_string(model_.meshes.size()) + " meshes");
        // A skinned or morphed mesh is posed per node: each node gets its own copy.
        std::vector<PlacedPrimitive> own;
        auto converted = converted_meshes_.find(mesh_index);
        if (gltf::node_deforms_mesh(model_, node)) own = convert_mesh(mesh_index);
        else if (converted == converted_meshes_.end()) converted = converted_meshes_.emplace(mesh_index, convert_mesh(mesh_index)).first;
        // One object id per node (and per EXT_mesh_gpu_instancing instance) placing a mesh: its
        // primitives are one object to a person.
        const auto id = std::uint32_t(++placed_nodes_);
        for (const PlacedPrimitive& primitive : gltf::node_deforms_mesh(model_, node) ? own : converted->second) {
            try {  // an object and its node: ~100 bytes, but 10^5 nodes x 10^5 primitives add up
                tally_.add(sizeof(Object) + sizeof(int), node_label + "'s objects");
            } catch (const io::MemoryBudgetError& e) {
                fail(e.what());
            }
            object_nodes_.push_back(node);
            object_instances_.push_back(instance);
            content_.objects.push_back(Object{primitive.mesh, primitive.material, world * instance, id});
            content_.bounds.add(mesh_bounds_[primitive.mesh].transformed(world * instance));
        }
    }

    // What a primitive expands to, from its accessors' counts, before it is read:
    // one accessor shared by 10^5 primitives, morph targets or skinned copies
    // otherwise grows to gigabytes (io/memory_budget.hpp).
    void tally_primitive(const tinygltf::Primitive& primitive, const std::string& label) {
        const auto count_of = [&](int accessor) -> std::uint64_t {
            if (accessor < 0 || std::size_t(accessor) >= model_.accessors.size()) return 0;
            return std::uint64_t(model_.accessors[std::size_t(accessor)].count);
        };
        std::uint64_t vertices = 0;
        if (const auto it = primitive.attributes.find("POSITION"); it != primitive.attributes.end())
            vertices = count_of(it->second);
        const std::uint64_t indices = primitive.indices >= 0 ? count_of(primitive.indices) : vertices;
        // A vertex: position, normal, uv, tangent, colour and its source (~80 bytes); a morph
        // target keeps position, normal and tangent offsets per vertex (36 bytes).
        std::uint64_t bytes = io::saturating_add(io::saturating_mul(vertices, 80), io::saturating_mul(indices, 4));
        bytes = io::saturating_add(bytes, io::saturating_mul(io::saturating_mul(vertices, 36),
                                                             std::uint64_t(primitive.targets.size())));
        try {
            tally_.add(bytes, label + " (" + std::to_string(vertices) + " vertices, " +
                                  std::to_string(primitive.targets.size()) + " morph targets)");
        } catch (const io::MemoryBudgetError& e) {
            fail(e.what());
        }
    }

    std::vector<PlacedPrimitive> convert_mesh(int mesh_index) {
        const tinygltf::Mesh& mesh = model_.meshes[std::size_t(mesh_index)];
        std::vector<PlacedPrimitive> placed;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const std::string label = indexed("meshes", std::size_t(mesh_index), mesh.name) + " primitives[" + std::to_string(p) + "]";
            tally_primitive(mesh.primitives[p], label);
            const gltf::MaterialUvs uvs = uv_mapping_of(mesh.primitives[p].material);
            const gltf::UvMapping& uv_mapping = uvs.baked;
            gltf::PrimitiveMesh converted =
                gltf::read_primitive(model_, mesh.primitives[p], source_, label, uv_mapping.set, uvs.second_set);
            if (!converted.is_surface) {
                ++content_.skipped_primitives;
                continue;
            }
            // A map reading a set that a primitive with texture coordinates lacks is
            // refused, as the glTF validator refuses it (MESH_PRIMITIVE_TOO_FEW_TEXCOORDS).
            // A primitive with none reads (0, 0), as it always did: one texel everywhere.
            const bool has_maps = mesh.primitives[p].material >= 0 && uv_mapping_has_maps(mesh.primitives[p].material);
            const auto& attributes = mesh.primitives[p].attributes;
            const bool any_texcoords = std::any_of(attributes.begin(), attributes.end(), [](const auto& a) {
                return a.first.rfind("TEXCOORD_", 0) == 0;
            });
            const auto require_set = [&](int set, bool present) {
                if (!present && any_texcoords)
                    fail(label + ": material " + std::to_string(mesh.primitives[p].material) + " has a map with texCoord " +
                         std::to_string(set) + " but the primitive has no TEXCOORD_" + std::to_string(set));
            };
            if (has_maps) require_set(uv_mapping.set, !converted.mesh.uvs.empty());
            if (uvs.second_set >= 0) {
                require_set(uvs.second_set, !converted.mesh.uvs1.empty());
                if (converted.mesh.uvs1.empty()) converted.mesh.uvs1.assign(converted.mesh.positions.size(), glm::vec2(0.0f));
            }
            if (uv_mapping.transformed)
                for (glm::vec2& uv : converted.mesh.uvs) uv = glm::vec2(uv_mapping.transform * glm::vec3(uv, 1.0f));
            Bounds bounds;
            for (const glm::vec3& position : converted.mesh.positions) bounds.add(position);
            mesh_bounds_.push_back(bounds);
            content_.meshes.push_back(std::move(converted.mesh));
            mesh_sources_.push_back({mesh_index, int(p), std::move(converted.vertex_sources)});
            placed.push_back({std::uint32_t(content_.meshes.size() - 1), material_index(mesh.primitives[p].material, label)});
        }
        return placed;
    }

    // ---- Materials and textures

    // The texture coordinates a glTF material's maps read (-1: the default material, no maps).
    gltf::MaterialUvs uv_mapping_of(int gltf_material) {
        if (gltf_material < 0 || std::size_t(gltf_material) >= model_.materials.size()) return {};
        const auto known = uv_mappings_.find(gltf_material);
        if (known != uv_mappings_.end()) return known->second;
        const gltf::MaterialUvs mapping =
            gltf::read_material_uvs(model_, std::size_t(gltf_material), source_, content_.warnings);
        uv_mappings_.emplace(gltf_material, mapping);
        return mapping;
    }

    bool uv_mapping_has_maps(int gltf_material) const {
        // An index past the file's materials is refused by material_index, with its message.
        if (gltf_material < 0 || std::size_t(gltf_material) >= model_.materials.size()) return false;
        const tinygltf::Material& m = model_.materials[std::size_t(gltf_material)];
        return m.pbrMetallicRoughness.baseColorTexture.index >= 0 ||
               m.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 || m.normalTexture.index >= 0 ||
               m.occlusionTexture.index >= 0 || m.emissiveTexture.index >= 0;
    }

    std::uint32_t material_index(int gltf_material, const std::string& primitive_label) {
        if (gltf_material >= 0 && std::size_t(gltf_material) >= model_.materials.size())
            fail(primitive_label + " uses material " + std::to_string(gltf_material) + " but the file has " +
                 std::to_string(model_.materials.size()) + " materials");
        const auto known = converted_materials_.find(gltf_material);
        if (known != converted_materials_.end()) return known->second;
        content_.materials.push_back(
            gltf_material < 0 ? gltf::default_material()
                              : gltf::read_material(model_, std::size_t(gltf_material), source_,
                                                    [this](int texture, texture::ColorSpace space, const std::string& what) {
                                                        return texture_slot(texture, space, what);
                                                    },
                                                    uv_mapping_of(gltf_material), content_.warnings));
        const auto index = std::uint32_t(content_.materials.size() - 1);
        converted_materials_.emplace(gltf_material, index);
        return index;
    }

    TextureSlot texture_slot(int texture_index, texture::ColorSpace color_space, const std::string& what) {
        TextureSlot slot;
        if (texture_index < 0) return slot;
        if (std::size_t(texture_index) >= model_.textures.size())
            fail(what + " uses texture " + std::to_string(texture_index) + " but the file has " +
                 std::to_string(model_.textures.size()) + " textures");
        const tinygltf::Texture& gltf_texture = model_.textures[std::size_t(texture_index)];
        const std::string texture_label = "textures[" + std::to_string(texture_index) + "]";
        const int source = image_source(gltf_texture, texture_label + " (" + what + ")");
        if (gltf_texture.sampler >= 0) {
            if (std::size_t(gltf_texture.sampler) >= model_.samplers.size())
                fail(texture_label + " uses sampler " + std::to_string(gltf_texture.sampler) + " but the file has " +
                     std::to_string(model_.samplers.size()) + " samplers");
            read_sampler(std::size_t(gltf_texture.sampler), slot);
        }
        const std::pair key{source, color_space};
        const auto known = texture_indices_.find(key);
        if (known != texture_indices_.end()) {
            slot.texture = known->second;
        } else {
            slot.texture = std::int32_t(pending_images_.size());
            texture_indices_.emplace(key, slot.texture);
            pending_images_.push_back(key);
        }
        return slot;
    }

    // How to make a KTX2 (Basis Universal) image readable: Khronos' KTX-Software.
    static constexpr const char* kKtx2Advice =
        "convert the image to PNG, e.g. with KTX-Software's `ktx transcode --target rgba8 in.ktx2 rgba.ktx2` and "
        "`ktx extract rgba.ktx2 out.png`, and make the texture's source that PNG";

    // The image a texture shows: EXT_texture_webp's or EXT_texture_avif's source
    // where the texture has one (a file written for them may have no other),
    // else its own. KHR_texture_basisu (KTX2) alone is refused, saying how to
    // convert it: no Debian package transcodes Basis Universal.
    int image_source(const tinygltf::Texture& texture, const std::string& label) const {
        for (const char* name : {"EXT_texture_webp", "EXT_texture_avif"}) {
            const auto extension = texture.extensions.find(name);
            if (extension == texture.extensions.end()) continue;
            const tinygltf::Value& source = extension->second.Get("source");
            if (!source.IsInt() || source.GetNumberAsInt() < 0 ||
                std::size_t(source.GetNumberAsInt()) >= model_.images.size())
                fail(label + " " + name + " source is not an image index below " + std::to_string(model_.images.size()));
            return source.GetNumberAsInt();
        }
        if (texture.source >= 0 && std::size_t(texture.source) < model_.images.size()) return texture.source;
        if (texture.extensions.count("KHR_texture_basisu"))
            fail(label + " has only a KHR_texture_basisu (KTX2) image, which is not supported: " + kKtx2Advice);
        fail(label + " has image source " + std::to_string(texture.source) + " but the file has " +
             std::to_string(model_.images.size()) + " images");
    }

    // GL's enums as glTF stores them; any other value is refused.
    void read_sampler(std::size_t index, TextureSlot& slot) const {
        const tinygltf::Sampler& sampler = model_.samplers[index];
        const std::string label = indexed("samplers", index, sampler.name);
        const auto wrap = [&](int value, const char* what) {
            switch (value) {
                case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::repeat;
                case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::clamp_to_edge;
                case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::mirrored_repeat;
                default: break;
            }
            fail(label + " " + what + " is " + std::to_string(value) +
                 ", expected 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) or 33648 (MIRRORED_REPEAT)");
        };
        slot.wrap_s = wrap(sampler.wrapS, "wrapS");
        slot.wrap_t = wrap(sampler.wrapT, "wrapT");
        switch (sampler.magFilter) {
            case -1: break;  // absent: the default, LINEAR
            case TINYGLTF_TEXTURE_FILTER_NEAREST: slot.mag_filter = TextureFilter::nearest; break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR: slot.mag_filter = TextureFilter::linear; break;
            default:
                fail(label + " magFilter is " + std::to_string(sampler.magFilter) +
                     ", expected 9728 (NEAREST) or 9729 (LINEAR)");
        }
        switch (sampler.minFilter) {
            case -1: break;  // absent: the default, LINEAR_MIPMAP_LINEAR
            case TINYGLTF_TEXTURE_FILTER_NEAREST: slot.min_filter = TextureFilter::nearest; break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR: slot.min_filter = TextureFilter::linear; break;
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: slot.min_filter = TextureFilter::nearest_mipmap_nearest; break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: slot.min_filter = TextureFilter::linear_mipmap_nearest; break;
            case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: slot.min_filter = TextureFilter::nearest_mipmap_linear; break;
            case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: slot.min_filter = TextureFilter::linear_mipmap_linear; break;
            default:
                fail(label + " minFilter is " + std::to_string(sampler.minFilter) +
                     ", expected 9728, 9729, 9984, 9985, 9986 or 9987 (NEAREST ... LINEAR_MIPMAP_LINEAR)");
        }
    }

    // Decoded in parallel: a textured model's images are most of its load time.
    void decode_textures() {
        content_.textures.resize(pending_images_.size());
        tbb::parallel_for(std::size_t(0), pending_images_.size(), [this](std::size_t i) {
            const auto [image, color_space] = pending_images_[i];
            content_.textures[i] = std::make_shared<const texture::Texture>(decode_image(std::size_t(image), color_space));
        });
    }

    texture::Texture decode_image(std::size_t index, texture::ColorSpace color_space) const {
        const tinygltf::Image& image = model_.images[index];
        std::string label = indexed("images", index, image.name);
        if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) label += " (" + quoted(image.uri) + ")";
        if (image.image.empty()) {
            if (!image.uri.empty()) {
                if (!options_.read_external_files) fail(label + ": external image " + quoted(image.uri) + " is not read here");
                fail(label + ": cannot read image file " + quoted((base_dir_ / image.uri).string()));
            }
            fail(label + " has no data");
        }
        const std::vector<unsigned char>& bytes = image.image;
        if (!texture::Texture::can_decode(bytes)) {
            if (bytes.size() >= 12 && std::memcmp(bytes.data(), "\xABKTX 20\xBB", 8) == 0)
                fail(label + " is a KTX2 image (KHR_texture_basisu), which is not supported: " + kKtx2Advice);
            fail(label + " is neither PNG, JPEG, WebP nor AVIF (mimeType " + quoted(image.mimeType) +
                 "); glTF images are PNG or JPEG, or WebP and AVIF with EXT_texture_webp and EXT_texture_avif");
        }
        try {
            return texture::Texture::decode(bytes, label, color_space);
        } catch (const texture::TextureError& e) {
            fail(e.what());  // "images[i] 'name': what"
        }
    }

    // ---- Cameras and lights

    void read_camera(int camera_index, const glm::mat4& world, const std::string& node_label) {
        if (std::size_t(camera_index) >= model_.cameras.size())
            fail(node_label + " uses camera " + std::to_string(camera_index) + " but the file has " +
                 std::to_string(model_.cameras.size()) + " cameras");
        const tinygltf::Camera& gltf_camera = model_.cameras[std::size_t(camera_index)];
        PlacedGltfCamera& placed = content_.cameras[std::size_t(camera_index)];
        if (placed.name.empty()) placed.name = node_name_;  // an unnamed camera goes by its node's name
        if (placed.view) return;  // where a node first places it
        const bool orthographic = gltf_camera.type == "orthographic";
        if (!orthographic && gltf_camera.type != "perspective") return;  // tinygltf refuses other types
        const std::string label = indexed("cameras", std::size_t(camera_index), gltf_camera.name);
        GltfCamera camera;
        if (orthographic) {
            // glTF's orthographic matrix (projection_matrix): xmag, ymag != 0, zfar > znear >= 0.
            const tinygltf::OrthographicCamera& o = gltf_camera.orthographic;
            if (!(std::abs(o.xmag) > 0.0 && std::isfinite(float(o.xmag)) && std::abs(o.ymag) > 0.0 &&
                  std::isfinite(float(o.ymag))))
                fail(label + " xmag, ymag are " + std::to_string(o.xmag) + ", " + std::to_string(o.ymag) +
                     "; expected finite numbers other than 0");
            if (o.xmag < 0.0 || o.ymag < 0.0)
                fail(label + " has a negative xmag or ymag (" + std::to_string(o.xmag) + ", " + std::to_string(o.ymag) +
                     "), a mirrored view; expected > 0");
            if (!(o.znear >= 0.0 && std::isfinite(float(o.znear))))
                fail(label + " znear is " + std::to_string(o.znear) + ", expected >= 0");
            if (!(o.zfar > o.znear && std::isfinite(float(o.zfar))))
                fail(label + " zfar is " + std::to_string(o.zfar) + ", expected > znear (" + std::to_string(o.znear) + ")");
            camera.camera.projection = Projection::orthographic;
            camera.camera.x_magnification = float(o.xmag);
            camera.camera.y_magnification = float(o.ymag);
            camera.camera.near_plane = float(o.znear);
            camera.camera.far_plane = float(o.zfar);
            camera.aspect_ratio = float(o.xmag / o.ymag);  // the box maps to the whole image
        } else {
            const tinygltf::PerspectiveCamera& p = gltf_camera.perspective;
            if (!(p.yfov > 0.0 && p.yfov < M_PI)) fail(label + " yfov is " + std::to_string(p.yfov) + ", expected radians in (0, π)");
            if (!(p.znear > 0.0 && std::isfinite(float(p.znear)))) fail(label + " znear is " + std::to_string(p.znear) + ", expected > 0");
            if (p.zfar != 0.0 && !(p.zfar > p.znear && std::isfinite(float(p.zfar))))
                fail(label + " zfar is " + std::to_string(p.zfar) + ", expected > znear (" + std::to_string(p.znear) + ")");
            if (!(p.aspectRatio >= 0.0 && std::isfinite(float(p.aspectRatio))))
                fail(label + " aspectRatio is " + std::to_string(p.aspectRatio) + ", expected > 0");
            camera.camera.fov_y_degrees = float(p.yfov) * kRadiansToDegrees;
            camera.camera.near_plane = float(p.znear);
            camera.camera.far_plane = p.zfar == 0.0 ? std::numeric_limits<float>::infinity() : float(p.zfar);
            camera.aspect_ratio = float(p.aspectRatio);
        }
        camera.camera.position = glm::vec3(world[3]);
        const glm::vec3 forward = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);
        const glm::vec3 up = glm::mat3(world) * glm::vec3(0.0f, 1.0f, 0.0f);
        if (!(glm::length(forward) > 0.0f) || !(glm::length(glm::cross(forward, up)) > 0.0f))
            fail(node_label + " places " + label + " with a degenerate transform (no view direction or up)");
        camera.camera.target = camera.camera.position + glm::normalize(forward);
        camera.camera.up = glm::normalize(up);
        placed.view = camera;
        if (!content_.camera) content_.camera = camera;
    }

    void read_node_light(const tinygltf::Node& node, const glm::mat4& world, const std::string& node_label) {
        const auto extension = node.extensions.find("KHR_lights_punctual");
        if (extension == node.extensions.end()) return;
        const tinygltf::Value& light_value = extension->second.Get("light");
        if (!light_value.IsInt()) fail(node_label + " KHR_lights_punctual has no integer 'light'");
        const int index = light_value.GetNumberAsInt();
        if (index < 0 || std::size_t(index) >= model_.lights.size())
            fail(node_label + " uses light " + std::to_string(index) + " but the file has " +
                 std::to_string(model_.lights.size()) + " KHR_lights_punctual lights");
        const tinygltf::Light& gltf_light = model_.lights[std::size_t(index)];
        const std::string label = "KHR_lights_punctual " + indexed("lights", std::size_t(index), gltf_light.name);
        Light light;
        if (gltf_light.type == "point") light.type = LightType::point;
        else if (gltf_light.type == "spot") light.type = LightType::spot;
        else if (gltf_light.type == "directional") light.type = LightType::directional;
        else fail(label + " has type " + quoted(gltf_light.type) + ", expected point, spot or directional");
        const glm::vec3 color = gltf_light.color.empty() ? glm::vec3(1.0f) : gltf::color_factor(gltf_light.color, 3, label + " color", false, source_);
        if (!(gltf_light.intensity >= 0.0 && std::isfinite(float(gltf_light.intensity))))
            fail(label + " intensity is " + std::to_string(gltf_light.intensity) + ", expected a finite number >= 0");
        light.color = color * float(gltf_light.intensity);
        if (!std::isfinite(light.color.x + light.color.y + light.color.z)) fail(label + " color × intensity is not finite");
        light.position = glm::vec3(world[3]);
        if (light.type != LightType::point) {
            const glm::vec3 direction = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);
            if (!(glm::length(direction) > 0.0f)) fail(node_label + " places " + label + " with a degenerate transform (no direction)");
            light.direction = glm::normalize(direction);
        }
        if (light.type == LightType::spot) {
            const double inner = gltf_light.spot.innerConeAngle, outer = gltf_light.spot.outerConeAngle;
            if (!(inner >= 0.0 && inner < outer && outer <= M_PI / 2 + 1e-6))
                fail(label + " cone angles are inner " + std::to_string(inner) + ", outer " + std::to_string(outer) +
                     "; expected 0 <= inner < outer <= π/2 radians");
            light.inner_cone_degrees = float(inner) * kRadiansToDegrees;
            light.outer_cone_degrees = std::min(float(outer) * kRadiansToDegrees, 90.0f);
        }
        if (!(gltf_light.range >= 0.0 && std::isfinite(float(gltf_light.range))))
            fail(label + " range is " + std::to_string(gltf_light.range) + ", expected a finite number > 0");
        light.range = light.type == LightType::directional ? 0.0f : float(gltf_light.range);
        content_.lights.push_back(light);
    }

    const tinygltf::Model& model_;
    std::string source_;
    fs::path base_dir_;
    io::MemoryTally tally_;  // what the model's meshes and objects expand to, against --max-memory
    GltfReadOptions options_;
    GltfContent content_;
    std::string node_name_;  // of the node being walked
    std::map<int, std::vector<PlacedPrimitive>> converted_meshes_;   // glTF mesh -> its primitives' meshes
    std::vector<Bounds> mesh_bounds_;                                // per content_.meshes entry, object space
    std::vector<gltf::MeshSource> mesh_sources_;                     // per content_.meshes entry: its glTF primitive
    std::vector<int> object_nodes_;                                  // per content_.objects entry: its node
    std::size_t placed_nodes_ = 0;                                   // nodes that placed a mesh so far: the object ids (one per instance)
    std::vector<glm::mat4> object_instances_;                        // and its EXT_mesh_gpu_instancing transform
    std::map<int, std::uint32_t> converted_materials_;               // glTF material (-1: default) -> index
    std::map<int, gltf::MaterialUvs> uv_mappings_;                     // glTF material -> its maps' uvs
    std::map<std::pair<int, texture::ColorSpace>, std::int32_t> texture_indices_;
    std::vector<std::pair<int, texture::ColorSpace>> pending_images_;  // what content_.textures[i] decodes
};

}  // namespace

namespace {
std::atomic<bool> g_external_uris_allowed{false};
}  // namespace

bool external_uris_allowed() { return g_external_uris_allowed.load(std::memory_order_relaxed); }
void set_external_uris_allowed(bool allowed) { g_external_uris_allowed.store(allowed, std::memory_order_relaxed); }

GltfImportTimes& gltf_import_times() {
    static GltfImportTimes times;
    return times;
}

bool is_gltf_path(const fs::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".gltf" || extension == ".glb";
}

GltfContent import_gltf(std::span<const std::uint8_t> bytes, const std::string& source, const fs::path& base_dir,
                        const GltfReadOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const tinygltf::Model model = parse_model(bytes, source, base_dir, options);
    gltf_import_times().parse_ns += nanoseconds_since(start);
    return GltfReader(model, source, base_dir, options).read();
}

GltfContent import_gltf_file(const fs::path& path, const GltfReadOptions& options) {
    const std::string source = path.string();
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::uint8_t> bytes;
    try {
        read_file_bytes(path, bytes, "glTF file");
    } catch (const io::InputFileError& e) {
        fail(source, e.reason());
    }
    gltf_import_times().file_read_ns += nanoseconds_since(start);
    GltfContent content = import_gltf(bytes, source, path.parent_path(), options);
    for (const std::string& warning : content.warnings)
        std::fprintf(stderr, "tessera: warning: %s: %s\n", source.c_str(), warning.c_str());
    return content;
}

void append_gltf_content(Scene& scene, const GltfContent& content, const glm::mat4& placement, bool with_lights) {
    const auto first_mesh = std::uint32_t(scene.meshes.size());
    const auto first_material = std::uint32_t(scene.materials.size());
    const auto first_texture = std::int32_t(scene.textures.size());
    scene.meshes.insert(scene.meshes.end(), content.meshes.begin(), content.meshes.end());
    scene.textures.insert(scene.textures.end(), content.textures.begin(), content.textures.end());
    for (Material material : content.materials) {
        for (TextureSlot* slot : {&material.albedo_map, &material.metallic_map, &material.roughness_map, &material.ao_map,
                                  &material.normal_map, &material.emissive_map})
            if (slot->present()) slot->texture += first_texture;
        scene.materials.push_back(material);
    }
    const auto first_object = std::uint32_t(scene.objects.size());
    // The file's object ids follow the scene's own (a TOML [[models]] entry then gives its objects one id).
    std::uint32_t first_id = 0;
    for (const Object& object : scene.objects) first_id = std::max(first_id, object.id);
    for (const Object& object : content.objects)
        scene.objects.push_back(Object{object.mesh + first_mesh, object.material + first_material,
                                       placement * object.model, first_id + object.id});
    if (content.rig) {
        PosedGltfModel posed;
        posed.rig = content.rig;
        posed.first_mesh = first_mesh;
        posed.first_object = first_object;
        posed.placement = placement;
        scene.posed_models.push_back(posed);
    }
    if (!with_lights) return;
    for (Light light : content.lights) {
        light.position = glm::vec3(placement * glm::vec4(light.position, 1.0f));
        const glm::vec3 direction = glm::mat3(placement) * light.direction;
        if (glm::length(direction) > 0.0f) light.direction = glm::normalize(direction);
        scene.lights.push_back(light);
    }
}

namespace {

// The camera --camera selects: an index into the file's cameras, or a name.
const GltfCamera& selected_camera(const GltfContent& content, const std::string& source, const std::string& selector) {
    std::optional<std::size_t> index;
    if (!selector.empty() && selector.size() < 10 &&
        std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); }))
        index = std::size_t(std::stoul(selector));
    for (std::size_t c = 0; c < content.cameras.size() && !index; ++c)
        if (content.cameras[c].name == selector) index = c;
    std::string known;
    for (std::size_t c = 0; c < content.cameras.size(); ++c)
        known += (c ? ", " : "") + std::to_string(c) + (content.cameras[c].name.empty() ? "" : " " + quoted(content.cameras[c].name)) +
                 " (" + content.cameras[c].type + (content.cameras[c].view ? "" : ", not placed") + ")";
    if (known.empty()) known = "none";
    if (!index || *index >= content.cameras.size())
        fail(source, "--camera " + quoted(selector) + " names no camera of the file; its cameras: " + known);
    const PlacedGltfCamera& placed = content.cameras[*index];
    if (!placed.view) fail(source, "--camera " + quoted(selector) + " is not placed by any node of the scene");
    return *placed.view;
}

}  // namespace

Scene make_gltf_scene(const GltfContent& content, const std::string& source, const std::string& camera_selector) {
    Scene scene;
    scene.source = source;
    append_gltf_content(scene, content, glm::mat4(1.0f), true);
    const GltfCamera* camera = content.camera ? &*content.camera : nullptr;
    if (!camera_selector.empty()) camera = &selected_camera(content, source, camera_selector);
    if (camera) {
        scene.camera = camera->camera;
        if (camera->aspect_ratio > 0.0f)
            scene.height = int(std::clamp(std::round(float(scene.width) / camera->aspect_ratio), 1.0f,
                                          float(kMaxImageDimension)));
    } else {
        scene.camera = framing_camera(content.bounds, float(scene.width) / float(scene.height));
    }
    if (scene.lights.empty()) {
        scene.lights = default_light_rig(scene.camera, content.bounds);
        scene.default_lights = true;
    }
    validate_scene(scene);
    return scene;
}

}  // namespace tessera
