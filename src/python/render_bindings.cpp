// tessera.Renderer and tessera.Frame: a render with the GIL released, its
// images handed to NumPy without a copy.
//
// The memory: a frame's images are moved out of the renderer into a Frame
// (Renderer::swap_image), and the arrays view them, each keeping the Frame's
// images alive through its base. So an array stays valid for as long as it
// lives, whatever is rendered after it. When the last array and the Frame are
// gone, the images go back to their renderer, whose next frame writes into
// them: a loop that drops each frame before the next allocates nothing.
#include <algorithm>
#include <mutex>
#include <string>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python/bindings.hpp"
#include "tessera/image_io.hpp"

namespace tessera::python {

namespace {

// Images given back by dropped frames, for the renderer's next frames.
struct ImagePool {
    std::mutex mutex;
    std::vector<RenderedImage> spare;
    static constexpr std::size_t kMaxSpare = 2;  // the frame being used and the next one
};

// One rendered frame's images, owned by the Python Frame and its arrays.
struct FrameImages {
    RenderedImage image;
    FrameStats stats;
    std::weak_ptr<ImagePool> pool;
    ~FrameImages() {
        if (const auto p = pool.lock()) {
            std::lock_guard lock(p->mutex);
            if (p->spare.size() < ImagePool::kMaxSpare) p->spare.push_back(std::move(image));
        }
    }
};

struct Frame {
    std::shared_ptr<const FrameImages> images;
};

struct PythonRenderer {
    std::unique_ptr<Renderer> renderer;
    std::mutex mutex;  // one frame at a time per renderer
    std::shared_ptr<ImagePool> pool = std::make_shared<ImagePool>();
    int width = 0, height = 0, msaa = 0;  // 0: the scene's
    AovSet aovs;
    bool radiance = false;
};

// `plane` as an array of `shape`, viewing it in place; None for a plane not rendered.
template <class T>
py::object view(const std::shared_ptr<const FrameImages>& images, const std::vector<T>& plane,
                std::vector<py::ssize_t> shape) {
    if (plane.empty()) return py::none();
    auto* owner = new std::shared_ptr<const FrameImages>(images);
    const py::capsule base(owner, [](void* p) { delete static_cast<std::shared_ptr<const FrameImages>*>(p); });
    return py::array_t<T>(std::move(shape), plane.data(), base);
}

AovSet aov_set(const py::object& aovs) {
    AovSet set;
    if (aovs.is_none()) return set;
    if (py::isinstance<py::str>(aovs)) {
        const std::string list = aovs.cast<std::string>();
        if (list == "all") {
            for (Aov aov : kAllAovs) set.insert(aov);
        } else if (!list.empty()) {
            parse_aov_list(list, set);
        }
        return set;
    }
    for (const py::handle name : aovs) parse_aov_list(py::str(name).cast<std::string>(), set);
    return set;
}

std::shared_ptr<const FrameImages> render_frame(PythonRenderer& r, const SharedScene& shared) {
    auto images = std::make_shared<FrameImages>();
    py::gil_scoped_release release;
    std::lock_guard lock(r.mutex);
    RenderedImage recycled;
    {
        std::lock_guard pool_lock(r.pool->mutex);
        if (!r.pool->spare.empty()) recycled = std::move(r.pool->spare.back()), r.pool->spare.pop_back();
    }
    r.renderer->swap_image(recycled);
    const int width = r.width ? r.width : shared.scene.width, height = r.height ? r.height : shared.scene.height;
    const int msaa = r.msaa ? r.msaa : shared.scene.msaa;
    {
        std::shared_lock read(shared.mutex);
        const Scene& scene = shared.scene;
        if (scene.width == width && scene.height == height && scene.msaa == msaa) {
            r.renderer->render(scene);
        } else {
            // Another size than the scene's own: drawn alone, the scene's size put back after.
            read.unlock();
            std::unique_lock write(shared.mutex);
            Scene& resized = const_cast<Scene&>(shared.scene);
            const int old_width = resized.width, old_height = resized.height, old_msaa = resized.msaa;
            resized.width = width, resized.height = height, resized.msaa = msaa;
            try {
                r.renderer->render(resized);
            } catch (...) {
                resized.width = old_width, resized.height = old_height, resized.msaa = old_msaa;
                throw;
            }
            resized.width = old_width, resized.height = old_height, resized.msaa = old_msaa;
        }
    }
    images->stats = r.renderer->last_frame_stats();
    r.renderer->swap_image(images->image);
    images->pool = r.pool;
    return images;
}

py::dict stats_dict(const FrameStats& s) {
    py::dict d;
    d["triangles_in"] = s.triangles_in, d["triangles_binned"] = s.triangles_binned;
    d["fragments_rasterized"] = s.fragments_rasterized, d["fragments_shaded"] = s.fragments_shaded;
    d["vertex_ms"] = s.vertex_ms, d["triangles_ms"] = s.triangles_ms, d["tiles_ms"] = s.tiles_ms;
    d["total_ms"] = s.total_ms;
    return d;
}

}  // namespace

void bind_render(py::module_& m) {
    py::class_<Frame>(m, "Frame",
                      "A rendered frame. Its arrays view the frame's own memory (no copy) and stay valid as long as "
                      "they live; arrays of AOVs not asked for are None.")
        .def_property_readonly("width", [](const Frame& f) { return f.images->image.width; })
        .def_property_readonly("height", [](const Frame& f) { return f.images->image.height; })
        .def_property_readonly("color", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.display, {i.height, i.width, 3});
        }, "(H, W, 3) uint8: display-referred RGB after Reinhard and gamma 1/2.2, what PNG stores")
        .def_property_readonly("radiance", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.radiance, {i.height, i.width, 3});
        }, "(H, W, 3) float32: scene-linear radiance before tonemapping (Renderer(radiance=True))")
        .def_property_readonly("depth", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.depth, {i.height, i.width});
        }, "(H, W) float32: view-axis distance, +inf for the background")
        .def_property_readonly("normal", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.normal, {i.height, i.width, 3});
        }, "(H, W, 3) float32: world-space unit shading normal, 0 for the background")
        .def_property_readonly("albedo", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.albedo, {i.height, i.width, 3});
        }, "(H, W, 3) float32: linear albedo after texturing, 0 for the background")
        .def_property_readonly("roughness", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.roughness, {i.height, i.width});
        })
        .def_property_readonly("metallic", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.metallic, {i.height, i.width});
        })
        .def_property_readonly("position", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.position, {i.height, i.width, 3});
        }, "(H, W, 3) float32: world-space point, 0 for the background")
        .def_property_readonly("object_id", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.object_id, {i.height, i.width});
        }, "(H, W) uint32: the object's id (Scene.object_ids), 0 for the background")
        .def_property_readonly("material_id", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.material_id, {i.height, i.width});
        }, "(H, W) uint32: the material's index + 1, 0 for the background")
        .def_property_readonly("shadow", [](const Frame& f) {
            const RenderedImage& i = f.images->image;
            return view(f.images, i.aov.shadow, {i.height, i.width});
        }, "(H, W) float32: the mean visibility of the lights that cast shadows (1 lit), 1 for the background")
        .def_property_readonly("stats", [](const Frame& f) { return stats_dict(f.images->stats); })
        .def("save",
             [](const Frame& f, const std::filesystem::path& path) {
                 py::gil_scoped_release release;
                 write_image(f.images->image, path);
             },
             py::arg("path"),
             "Writes .png (the colour image) or .exr (radiance and every AOV rendered, as `tessera render --aov` "
             "does; needs radiance=True), through a temporary file renamed into place")
        .def("__repr__", [](const Frame& f) {
            return "<tessera.Frame " + std::to_string(f.images->image.width) + "x" +
                   std::to_string(f.images->image.height) + ">";
        });

    py::class_<PythonRenderer>(m, "Renderer", "Renders scenes; keeps its memory from frame to frame")
        .def(py::init([](const py::object& width, const py::object& height, int threads, const py::object& msaa,
                         const py::object& aovs, bool radiance, const std::string& isa, int tile_size,
                         bool light_culling) {
                 auto r = std::make_unique<PythonRenderer>();
                 if (!width.is_none()) r->width = width.cast<int>();
                 if (!height.is_none()) r->height = height.cast<int>();
                 if (width.is_none() != height.is_none()) throw py::value_error("give both width and height, or neither");
                 if (!width.is_none() &&
                     (r->width < 1 || r->height < 1 || r->width > kMaxImageDimension || r->height > kMaxImageDimension ||
                      std::int64_t(r->width) * r->height > kMaxImagePixels))
                     throw py::value_error("image size " + std::to_string(r->width) + "x" + std::to_string(r->height) +
                                           " is outside 1.." + std::to_string(kMaxImageDimension) + " per side");
                 if (!msaa.is_none()) {
                     r->msaa = msaa.cast<int>();
                     if (r->msaa != 1 && r->msaa != 4) throw py::value_error("msaa: expected 1 or 4");
                 }
                 r->aovs = aov_set(aovs);
                 r->radiance = radiance;
                 RenderSettings settings;
                 settings.threads = threads;
                 settings.tile_size = tile_size;
                 settings.isa = isa;
                 settings.keep_radiance = radiance;
                 settings.light_culling = light_culling;
                 settings.aovs = r->aovs;
                 r->renderer = std::make_unique<Renderer>(settings);
                 return r;
             }),
             py::arg("width") = py::none(), py::arg("height") = py::none(), py::arg("threads") = 0,
             py::arg("msaa") = py::none(), py::arg("aovs") = py::tuple(), py::arg("radiance") = false,
             py::arg("isa") = "auto", py::arg("tile_size") = 64, py::arg("light_culling") = true,
             "width, height, msaa: None = the scene's. threads: 0 = one per hardware thread. aovs: names from "
             "depth, normal, albedo, roughness, metallic, position, object_id, material_id, shadow, or 'all'. radiance: "
             "also keep the HDR image.")
        .def("render", [](PythonRenderer& r, const SharedScene& scene) { return Frame{render_frame(r, scene)}; },
             py::arg("scene"),
             "Renders the scene (the GIL released: other Python threads run, and other renderers can draw at "
             "once) and returns a Frame")
        .def_property_readonly("threads", [](const PythonRenderer& r) { return r.renderer->threads(); })
        .def_property_readonly("isa", [](const PythonRenderer& r) { return r.renderer->isa_name(); })
        .def_property_readonly("aovs", [](const PythonRenderer& r) {
            std::vector<std::string> names;
            for (Aov aov : kAllAovs)
                if (r.aovs.contains(aov)) names.emplace_back(aov_name(aov));
            return names;
        });
}

}  // namespace tessera::python
