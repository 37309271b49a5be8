// tessera.Scene, tessera.Camera and tessera.load: scenes from files or built
// from NumPy arrays, into the same tessera::Scene the command line renders.
#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python/bindings.hpp"
#include "scene/scene_validation.hpp"
#include "texture/texture.hpp"

namespace tessera::python {

namespace {

// Area-weighted vertex normals, for meshes given without normals (a face's
// cross product is twice its area); a vertex on no triangle gets +Y.
std::vector<glm::vec3> smooth_normals(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
    std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::vec3 &a = positions[indices[t]], &b = positions[indices[t + 1]], &c = positions[indices[t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        for (int k = 0; k < 3; ++k) normals[indices[t + k]] += n;
    }
    for (glm::vec3& n : normals) {
        const float length = glm::length(n);
        n = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return normals;
}

template <class Vec>
std::vector<Vec> rows_of(const py::handle& array, const char* what, std::size_t expected_rows) {
    constexpr int kColumns = Vec::length();
    const auto rows = float_rows(array, kColumns, what);
    if (expected_rows != std::size_t(-1) && std::size_t(rows.shape(0)) != expected_rows)
        throw py::value_error(std::string(what) + ": expected " + std::to_string(expected_rows) +
                              " rows (one per position), got " + std::to_string(rows.shape(0)));
    std::vector<Vec> out(std::size_t(rows.shape(0)));
    const float* v = rows.data();
    for (std::size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < kColumns; ++c) out[i][c] = v[i * kColumns + std::size_t(c)];
    return out;
}

constexpr std::size_t kAnyRows = std::size_t(-1);

// A trimesh-like object: .vertices and .faces, and where it has them
// .vertex_normals and .visual.uv.
bool is_trimesh_like(const py::handle& value) {
    return py::hasattr(value, "vertices") && py::hasattr(value, "faces");
}

std::shared_ptr<SharedScene> make_scene(int width, int height) {
    auto shared = std::make_shared<SharedScene>();
    shared->scene.source = "python scene";
    shared->scene.width = width;
    shared->scene.height = height;
    return shared;
}

std::uint32_t next_object_id(const Scene& scene) {
    std::uint32_t id = 0;
    for (std::size_t o = 0; o < scene.objects.size(); ++o)
        id = std::max(id, scene.objects[o].id != 0 ? scene.objects[o].id : std::uint32_t(o + 1));
    return id + 1;
}

void check_size(int width, int height) {
    if (width < 1 || height < 1 || width > kMaxImageDimension || height > kMaxImageDimension ||
        std::int64_t(width) * height > kMaxImagePixels)
        throw py::value_error("image size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
                              std::to_string(kMaxImageDimension) + " per side or above " +
                              std::to_string(kMaxImagePixels) + " pixels");
}

// The OpenGL projection of a pinhole camera with intrinsics K, in OpenCV's
// pixel convention: u = fx·X/Z + s·Y/Z + cx, v = fy·Y/Z + cy in the camera
// frame of OpenCV (x right, y down, z forward), integer (u, v) at pixel centres,
// (0, 0) the centre of the top-left pixel. Pixel (i, j) covers NDC
// x in 2(i, i+1)/w - 1 and y in 1 - 2(j, j+1)/h, so u + 1/2 and v + 1/2 map
// linearly onto NDC; with GL's view space (x, y, z) = (X, -Y, -Z):
//   x_clip = 2fx/w·x - 2s/w·y + (1 - 2(cx + 1/2)/w)·z,   w_clip = -z,
//   y_clip = 2fy/h·y + (2(cy + 1/2)/h - 1)·z.
glm::mat4 intrinsic_projection(const glm::mat3& k, int width, int height, float near_plane, float far_plane) {
    const float fx = k[0][0], fy = k[1][1], s = k[1][0], cx = k[2][0], cy = k[2][1];
    const float w = float(width), h = float(height);
    glm::mat4 p(0.0f);  // p[column][row]
    p[0][0] = 2.0f * fx / w;
    p[1][0] = -2.0f * s / w;
    p[2][0] = 1.0f - 2.0f * (cx + 0.5f) / w;
    p[1][1] = 2.0f * fy / h;
    p[2][1] = 2.0f * (cy + 0.5f) / h - 1.0f;
    p[2][2] = -(far_plane + near_plane) / (far_plane - near_plane);
    p[3][2] = -2.0f * far_plane * near_plane / (far_plane - near_plane);
    p[2][3] = -1.0f;
    return p;
}

Camera camera_from_intrinsics(const py::object& k_value, const py::object& extrinsic_value, int width, int height,
                              const std::string& convention, float near_plane, float far_plane) {
    check_size(width, height);
    if (!(near_plane > 0.0f && near_plane < far_plane && std::isfinite(far_plane)))
        throw py::value_error("expected 0 < near < far, finite");
    const glm::mat3 k = matrix3(k_value, "K");
    if (!(k[0][0] > 0.0f && k[1][1] > 0.0f) || k[0][1] != 0.0f || k[0][2] != 0.0f || k[1][2] != 0.0f ||
        k[2][2] != 1.0f)
        throw py::value_error("K: expected [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with fx, fy > 0");
    glm::mat4 extrinsic = matrix4(extrinsic_value, "extrinsic");
    if (extrinsic[0][3] != 0.0f || extrinsic[1][3] != 0.0f || extrinsic[2][3] != 0.0f || extrinsic[3][3] != 1.0f)
        throw py::value_error("extrinsic: expected a rigid world-to-camera transform, last row [0, 0, 0, 1]");
    const glm::mat3 rotation(extrinsic);
    if (std::abs(glm::determinant(rotation) - 1.0f) > 1e-3f ||
        glm::length(glm::mat3(glm::transpose(rotation) * rotation)[0] - glm::vec3(1, 0, 0)) > 1e-3f)
        throw py::value_error("extrinsic: expected a rotation (orthonormal, determinant 1) and a translation");
    glm::mat4 view = extrinsic;
    if (convention == "opencv") {
        // OpenCV's camera frame (x right, y down, z forward) to GL's (x right, y up, z backward).
        view = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, -1.0f, -1.0f)) * extrinsic;
    } else if (convention != "opengl") {
        throw py::value_error("convention: expected 'opencv' or 'opengl', got '" + convention + "'");
    }
    Camera camera;
    camera.explicit_matrices = true;
    camera.explicit_view = view;
    camera.explicit_projection = intrinsic_projection(k, width, height, near_plane, far_plane);
    // The same camera as position/target/up, for the shader's camPos and what reads those.
    const glm::mat4 camera_to_world = glm::inverse(view);
    camera.position = glm::vec3(camera_to_world[3]);
    camera.target = camera.position - glm::vec3(camera_to_world[2]);
    camera.up = glm::vec3(camera_to_world[1]);
    camera.fov_y_degrees = glm::degrees(2.0f * std::atan(0.5f * float(height) / k[1][1]));
    camera.near_plane = near_plane;
    camera.far_plane = far_plane;
    return camera;
}

TextureSlot texture_slot(const Scene& scene, int texture, const char* what) {
    if (texture < -1 || texture >= int(scene.textures.size()))
        throw py::value_error(std::string(what) + ": no texture " + std::to_string(texture) + " (the scene has " +
                              std::to_string(scene.textures.size()) + "; -1 = none)");
    return TextureSlot{texture, TextureWrap::repeat};
}

}  // namespace

void bind_scene(py::module_& m) {
    py::class_<Camera>(m, "Camera", "A perspective camera: position/target/up/fov_y, or intrinsics and an extrinsic")
        .def(py::init([](const py::object& position, const py::object& target, const py::object& up, float fov_y,
                         float near_plane, float far_plane) {
                 Camera c;
                 c.position = vec3(position, "position"), c.target = vec3(target, "target"), c.up = vec3(up, "up");
                 if (!(fov_y > 0.0f && fov_y < 180.0f)) throw py::value_error("fov_y: expected (0, 180) degrees");
                 if (!(near_plane > 0.0f && near_plane < far_plane)) throw py::value_error("expected 0 < near < far");
                 c.fov_y_degrees = fov_y, c.near_plane = near_plane, c.far_plane = far_plane;
                 return c;
             }),
             py::arg("position") = py::make_tuple(0.0, 0.0, 3.0), py::arg("target") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("up") = py::make_tuple(0.0, 1.0, 0.0), py::arg("fov_y") = 45.0f, py::arg("near") = 0.1f,
             py::arg("far") = 100.0f)
        .def_static("from_intrinsics", &camera_from_intrinsics, py::arg("K"), py::arg("extrinsic"), py::arg("width"),
                    py::arg("height"), py::arg("convention") = "opencv", py::arg("near") = 0.1f,
                    py::arg("far") = 100.0f,
                    "A pinhole camera: K = [[fx, s, cx], [0, fy, cy], [0, 0, 1]] in pixels (OpenCV's convention: "
                    "integer coordinates at pixel centres), extrinsic the 4x4 world-to-camera transform, its camera "
                    "frame OpenCV's (x right, y down, z forward) or OpenGL's (x right, y up, looking along -z)")
        .def_property_readonly("position", [](const Camera& c) { return std::vector<float>{c.position.x, c.position.y, c.position.z}; })
        .def_property_readonly("target", [](const Camera& c) { return std::vector<float>{c.target.x, c.target.y, c.target.z}; })
        .def_property_readonly("up", [](const Camera& c) { return std::vector<float>{c.up.x, c.up.y, c.up.z}; })
        .def_property_readonly("fov_y", [](const Camera& c) { return c.fov_y_degrees; })
        .def_property_readonly("near", [](const Camera& c) { return c.near_plane; })
        .def_property_readonly("far", [](const Camera& c) { return c.far_plane; })
        .def_property_readonly("from_matrices", [](const Camera& c) { return c.explicit_matrices; })
        .def("view_matrix", [](const Camera& c) { return to_numpy(view_matrix(c)); },
             "World to OpenGL view space (4x4, row-major)")
        .def("projection_matrix", [](const Camera& c, int width, int height) {
                 return to_numpy(projection_matrix(c, width, height));
             }, py::arg("width"), py::arg("height"), "OpenGL view to clip space (4x4) for an image of this size")
        .def("__repr__", [](const Camera& c) {
            return "tessera.Camera(position=(" + std::to_string(c.position.x) + ", " + std::to_string(c.position.y) +
                   ", " + std::to_string(c.position.z) + "), fov_y=" + std::to_string(c.fov_y_degrees) +
                   (c.explicit_matrices ? ", from intrinsics)" : ")");
        });

    py::class_<SharedScene, std::shared_ptr<SharedScene>>(m, "Scene",
                                                          "A scene: meshes, materials, textures, objects, lights, camera")
        .def(py::init(&make_scene), py::arg("width") = 640, py::arg("height") = 480)
        .def_property("width", [](const SharedScene& s) { return s.scene.width; },
                      [](SharedScene& s, int width) {
                          check_size(width, s.scene.height);
                          std::unique_lock lock(s.mutex);
                          s.scene.width = width;
                      })
        .def_property("height", [](const SharedScene& s) { return s.scene.height; },
                      [](SharedScene& s, int height) {
                          check_size(s.scene.width, height);
                          std::unique_lock lock(s.mutex);
                          s.scene.height = height;
                      })
        .def_property("msaa", [](const SharedScene& s) { return s.scene.msaa; },
                      [](SharedScene& s, int msaa) {
                          if (msaa != 1 && msaa != 4) throw py::value_error("msaa: expected 1 or 4");
                          std::unique_lock lock(s.mutex);
                          s.scene.msaa = msaa;
                      })
        .def_property("clear_color", [](const SharedScene& s) {
                          const glm::vec3 c = s.scene.clear_color;
                          return std::vector<float>{c.r, c.g, c.b};
                      },
                      [](SharedScene& s, const py::object& color) {
                          const glm::vec3 c = vec3(color, "clear_color");
                          std::unique_lock lock(s.mutex);
                          s.scene.clear_color = c;
                      })
        .def_property("camera", [](const SharedScene& s) { return s.scene.camera; },
                      [](SharedScene& s, const Camera& camera) {
                          std::unique_lock lock(s.mutex);
                          s.scene.camera = camera;
                      })
        .def_property_readonly("source", [](const SharedScene& s) { return s.scene.source; })
        .def_property_readonly("mesh_count", [](const SharedScene& s) { return s.scene.meshes.size(); })
        .def_property_readonly("material_count", [](const SharedScene& s) { return s.scene.materials.size(); })
        .def_property_readonly("texture_count", [](const SharedScene& s) { return s.scene.textures.size(); })
        .def_property_readonly("object_count", [](const SharedScene& s) { return s.scene.objects.size(); })
        .def_property_readonly("light_count", [](const SharedScene& s) { return s.scene.lights.size(); })
        .def("object_ids", [](const SharedScene& s) {
                 py::array_t<std::uint32_t> ids(py::ssize_t(s.scene.objects.size()));
                 auto w = ids.mutable_unchecked<1>();
                 for (std::size_t o = 0; o < s.scene.objects.size(); ++o)
                     w(py::ssize_t(o)) = s.scene.objects[o].id != 0 ? s.scene.objects[o].id : std::uint32_t(o + 1);
                 return ids;
             },
             "Each object's value in the object_id AOV, in object order")
        .def("add_mesh",
             [](SharedScene& s, const py::object& positions, const py::object& indices, const py::object& normals,
                const py::object& uvs, const py::object& colors, const std::string& name) {
                 py::object p = positions, i = indices, n = normals, uv = uvs;
                 if (is_trimesh_like(positions)) {
                     p = positions.attr("vertices"), i = positions.attr("faces");
                     if (n.is_none() && py::hasattr(positions, "vertex_normals")) n = positions.attr("vertex_normals");
                     if (uv.is_none() && py::hasattr(positions, "visual") &&
                         py::hasattr(positions.attr("visual"), "uv") && !positions.attr("visual").attr("uv").is_none())
                         uv = positions.attr("visual").attr("uv");
                 } else if (indices.is_none()) {
                     throw py::value_error("indices: expected an (M, 3) integer array (or a trimesh-like mesh)");
                 }
                 Mesh mesh;
                 mesh.name = name.empty() ? "python mesh " + std::to_string(s.scene.meshes.size()) : name;
                 mesh.positions = rows_of<glm::vec3>(p, "positions", kAnyRows);
                 mesh.indices = triangle_indices(i, mesh.positions.size(), "indices");
                 if (!n.is_none()) mesh.normals = rows_of<glm::vec3>(n, "normals", mesh.positions.size());
                 else mesh.normals = smooth_normals(mesh.positions, mesh.indices);
                 if (!uv.is_none()) mesh.uvs = rows_of<glm::vec2>(uv, "uvs", mesh.positions.size());
                 if (!colors.is_none()) {
                     const py::array c = py::array::ensure(colors);
                     const bool rgb = c && c.ndim() == 2 && c.shape(1) == 3;
                     if (rgb)
                         for (const glm::vec3& v : rows_of<glm::vec3>(colors, "colors", mesh.positions.size()))
                             mesh.colors.emplace_back(v, 1.0f);
                     else mesh.colors = rows_of<glm::vec4>(colors, "colors", mesh.positions.size());
                 }
                 std::unique_lock lock(s.mutex);
                 s.scene.meshes.push_back(std::move(mesh));
                 return s.scene.meshes.size() - 1;
             },
             py::arg("positions"), py::arg("indices") = py::none(), py::arg("normals") = py::none(),
             py::arg("uvs") = py::none(), py::arg("colors") = py::none(), py::arg("name") = "",
             "Adds a triangle mesh (object space) and returns its index. positions (N, 3) float; indices (M, 3) "
             "integers < N; normals (N, 3) (default: area-weighted smooth normals); uvs (N, 2), (0, 0) the "
             "texture's top-left; colors (N, 3) or (N, 4) linear. Or a trimesh-like object (vertices, faces, "
             "vertex_normals, visual.uv).")
        .def("add_texture",
             [](SharedScene& s, const py::array& pixels, bool srgb) {
                 const char kind = pixels.dtype().kind();
                 const bool bytes = pixels.dtype().is(py::dtype::of<std::uint8_t>());
                 if (!bytes && kind != 'f')
                     throw py::value_error("pixels: expected a uint8 or float array, got dtype " +
                                           std::string(py::str(pixels.dtype())));
                 if (!(pixels.ndim() == 2 || (pixels.ndim() == 3 && pixels.shape(2) >= 1 && pixels.shape(2) <= 4)))
                     throw py::value_error("pixels: expected shape (H, W) or (H, W, 1..4)");
                 const int h = int(pixels.shape(0)), w = int(pixels.shape(1));
                 const int channels = pixels.ndim() == 3 ? int(pixels.shape(2)) : 1;
                 const texture::ColorSpace space = srgb ? texture::ColorSpace::srgb : texture::ColorSpace::linear;
                 std::shared_ptr<const texture::Texture> made;
                 try {
                     if (bytes) {
                         const auto a = py::array_t<std::uint8_t, py::array::c_style>::ensure(pixels);
                         made = std::make_shared<const texture::Texture>(
                             texture::Texture::from_pixels(w, h, channels, a.data(), space));
                     } else {
                         const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(pixels);
                         for (py::ssize_t k = 0; k < a.size(); ++k)
                             if (!std::isfinite(a.data()[k])) throw py::value_error("pixels: every value must be finite");
                         made = std::make_shared<const texture::Texture>(
                             texture::Texture::from_pixels(w, h, channels, a.data(), space));
                     }
                 } catch (const texture::TextureError& e) {
                     throw py::value_error(std::string("pixels: ") + e.what());
                 }
                 std::unique_lock lock(s.mutex);
                 s.scene.textures.push_back(std::move(made));
                 return s.scene.textures.size() - 1;
             },
             py::arg("pixels"), py::arg("srgb") = true,
             "Adds a texture from (H, W[, C]) pixels, top row first: uint8 as they are, floats in [0, 1] rounded "
             "to 8 bits; srgb=True for colour (albedo, emissive), False for data (normal maps). Returns its index.")
        .def("add_material",
             [](SharedScene& s, const py::object& albedo, float metallic, float roughness, float ao,
                const py::object& emissive, int albedo_texture, int normal_texture, int emissive_texture,
                bool double_sided) {
                 Material material;
                 material.albedo = vec3(albedo, "albedo");
                 material.emissive = vec3(emissive, "emissive");
                 const auto unit = [](float v, const char* what) {
                     if (!(v >= 0.0f && v <= 1.0f)) throw py::value_error(std::string(what) + ": expected [0, 1]");
                 };
                 for (int c = 0; c < 3; ++c) unit(material.albedo[c], "albedo");
                 if (!(material.emissive.r >= 0 && material.emissive.g >= 0 && material.emissive.b >= 0))
                     throw py::value_error("emissive: expected >= 0");
                 unit(metallic, "metallic"), unit(roughness, "roughness"), unit(ao, "ao");
                 material.metallic = metallic, material.roughness = roughness, material.ao = ao;
                 std::unique_lock lock(s.mutex);
                 material.albedo_map = texture_slot(s.scene, albedo_texture, "albedo_texture");
                 material.normal_map = texture_slot(s.scene, normal_texture, "normal_texture");
                 material.emissive_map = texture_slot(s.scene, emissive_texture, "emissive_texture");
                 if (material.emissive_map.present() && material.emissive == glm::vec3(0.0f)) material.emissive = glm::vec3(1.0f);
                 material.derived_tangent_frame = DerivedTangentFrame::gltf;
                 material.double_sided = double_sided;
                 s.scene.materials.push_back(material);
                 return s.scene.materials.size() - 1;
             },
             py::arg("albedo") = py::make_tuple(0.5, 0.0, 0.0), py::arg("metallic") = 0.0f,
             py::arg("roughness") = 0.5f, py::arg("ao") = 1.0f, py::arg("emissive") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("albedo_texture") = -1, py::arg("normal_texture") = -1, py::arg("emissive_texture") = -1,
             py::arg("double_sided") = true,
             "Adds a PBR material (linear albedo in [0, 1]; textures by index from add_texture, -1 = none, "
             "each multiplying its factor) and returns its index.")
        .def("add_object",
             [](SharedScene& s, std::size_t mesh, std::size_t material, const py::object& transform,
                const py::object& id) {
                 Object object;
                 if (!transform.is_none()) object.model = matrix4(transform, "transform");
                 std::unique_lock lock(s.mutex);
                 if (mesh >= s.scene.meshes.size()) throw py::value_error("mesh: no mesh " + std::to_string(mesh));
                 if (material >= s.scene.materials.size())
                     throw py::value_error("material: no material " + std::to_string(material) +
                                           (s.scene.materials.empty() ? " (add one with add_material)" : ""));
                 object.mesh = std::uint32_t(mesh), object.material = std::uint32_t(material);
                 object.id = id.is_none() ? next_object_id(s.scene) : id.cast<std::uint32_t>();
                 if (object.id == 0) throw py::value_error("id: 0 is the background's; expected >= 1");
                 s.scene.objects.push_back(object);
                 return object.id;
             },
             py::arg("mesh"), py::arg("material") = 0, py::arg("transform") = py::none(), py::arg("id") = py::none(),
             "Places a mesh with a material; transform is the 4x4 object-to-world matrix. Returns the object's "
             "id, its value in the object_id AOV (by default one more than the largest so far).")
        .def("set_transform",
             [](SharedScene& s, std::size_t object, const py::object& transform) {
                 const glm::mat4 model = matrix4(transform, "transform");
                 std::unique_lock lock(s.mutex);
                 if (object >= s.scene.objects.size()) throw py::value_error("object: no object " + std::to_string(object));
                 s.scene.objects[object].model = model;
             },
             py::arg("object"), py::arg("transform"), "Moves object number `object` (its index, not its id)")
        .def("add_light",
             [](SharedScene& s, const std::string& type, const py::object& position, const py::object& color,
                const py::object& direction, float inner_cone, float outer_cone, float range, bool shadows,
                int shadow_map_size, int shadow_filter_radius) {
                 Light light;
                 if (type == "point") light.type = LightType::point;
                 else if (type == "directional") light.type = LightType::directional;
                 else if (type == "spot") light.type = LightType::spot;
                 else throw py::value_error("type: expected 'point', 'directional' or 'spot', got '" + type + "'");
                 light.position = vec3(position, "position");
                 light.color = vec3(color, "color");
                 if (!(light.color.r >= 0 && light.color.g >= 0 && light.color.b >= 0))
                     throw py::value_error("color: expected >= 0");
                 const glm::vec3 d = vec3(direction, "direction");
                 if (!(glm::length(d) > 0.0f)) throw py::value_error("direction: expected a non-zero vector");
                 light.direction = glm::normalize(d);
                 if (!(inner_cone >= 0.0f && inner_cone < outer_cone && outer_cone <= 90.0f))
                     throw py::value_error("expected 0 <= inner_cone < outer_cone <= 90 degrees");
                 light.inner_cone_degrees = inner_cone, light.outer_cone_degrees = outer_cone;
                 if (!(range >= 0.0f && std::isfinite(range))) throw py::value_error("range: expected >= 0 (0 = unlimited)");
                 light.range = range;
                 if (shadow_map_size < kMinShadowMapSize || shadow_map_size > kMaxShadowMapSize)
                     throw py::value_error("shadow_map_size: expected " + std::to_string(kMinShadowMapSize) + ".." +
                                           std::to_string(kMaxShadowMapSize) + " texels");
                 if (shadow_filter_radius < 0 || shadow_filter_radius > kMaxShadowFilterRadius)
                     throw py::value_error("shadow_filter_radius: expected 0.." + std::to_string(kMaxShadowFilterRadius));
                 light.shadows = shadows;
                 light.shadow_map_size = shadow_map_size, light.shadow_filter_radius = shadow_filter_radius;
                 std::unique_lock lock(s.mutex);
                 s.scene.lights.push_back(light);
                 return s.scene.lights.size() - 1;
             },
             py::arg("type") = "point", py::arg("position") = py::make_tuple(0.0, 0.0, 0.0),
             py::arg("color") = py::make_tuple(1.0, 1.0, 1.0), py::arg("direction") = py::make_tuple(0.0, 0.0, -1.0),
             py::arg("inner_cone") = 0.0f, py::arg("outer_cone") = 45.0f, py::arg("range") = 0.0f,
             py::arg("shadows") = false, py::arg("shadow_map_size") = kDefaultShadowMapSize,
             py::arg("shadow_filter_radius") = kDefaultShadowFilterRadius,
             "Adds a light (point and spot colours are radiance times distance squared) and returns its index")
        .def("validate",
             [](const SharedScene& s) {
                 std::shared_lock lock(s.mutex);
                 validate_scene(s.scene);
             },
             "Raises SceneError for the first problem the renderer would refuse or mis-draw")
        .def("__repr__", [](const SharedScene& s) {
            return "<tessera.Scene '" + s.scene.source + "' " + std::to_string(s.scene.width) + "x" +
                   std::to_string(s.scene.height) + ", " + std::to_string(s.scene.objects.size()) + " objects, " +
                   std::to_string(s.scene.lights.size()) + " lights>";
        });

    m.def("load",
          [](const std::filesystem::path& path, const std::string& camera) {
              auto shared = std::make_shared<SharedScene>();
              shared->scene = load_scene_file(path, camera);
              return shared;
          },
          py::arg("path"), py::arg("camera") = "", py::call_guard<py::gil_scoped_release>(),
          "Reads a TOML scene or a .gltf/.glb file (camera: a glTF camera's name or index). Raises SceneError "
          "(file:line:column: message) for a file that cannot be used.");
}

}  // namespace tessera::python
