// Tessera as a library: loads a scene file (TOML, .gltf or .glb), renders it and writes a PNG.
//   embed SCENE OUT.png
#include <cstdio>
#include <exception>

#include <tessera/image_io.hpp>
#include <tessera/renderer.hpp>
#include <tessera/scene.hpp>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s SCENE OUT.png\n", argv[0]);
        return 2;
    }
    try {
        const tessera::Scene scene = tessera::load_scene_file(argv[1]);
        tessera::RenderSettings settings;
        settings.keep_radiance = false;  // a PNG stores only the display image
        tessera::Renderer renderer(settings);
        const tessera::RenderedImage& image = renderer.render(scene);
        tessera::write_image(image, argv[2]);  // to a temporary name, then renamed
        std::printf("%s: %d x %d, %.1f ms on %d threads (%s)\n", argv[2], image.width, image.height,
                    renderer.last_frame_stats().total_ms, renderer.threads(), renderer.isa_name().c_str());
        return 0;
    } catch (const std::exception& error) {  // SceneError, ImageError: "file: what is wrong"
        std::fprintf(stderr, "embed: error: %s\n", error.what());
        return 1;
    }
}
