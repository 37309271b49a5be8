// Single-sided materials (Material::double_sided = false): a plane whose front
// (its normal, +Y) faces the camera is drawn, seen from behind it is not; a
// mirroring model matrix swaps the sides (glTF's rule); double-sided draws
// both. Every ISA, with and without MSAA, gives the same image.
#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/isa_agreement.hpp"
#include "tessera/renderer.hpp"
#include "texture/texture.hpp"

using namespace tessera;

namespace {

// A 20×20 plane (normal +Y) seen from above or below; the near plane cuts it
// when `grazing`, so clipped fans are culled too.
Scene plane_scene(bool double_sided, bool from_above, glm::vec3 scale, bool grazing = false) {
    Scene scene;
    scene.width = 32, scene.height = 24;
    scene.clear_color = glm::vec3(0.0f);
    const float side = from_above ? 1.0f : -1.0f;
    scene.camera.position = grazing ? glm::vec3(0, side * 0.5f, 0) : glm::vec3(0, side * 5.0f, 0);
    scene.camera.target = grazing ? glm::vec3(0, 0, -4) : glm::vec3(0);
    scene.camera.up = {0, 0, -1};
    scene.meshes.push_back(make_plane_mesh());
    Material material;
    material.double_sided = double_sided;
    scene.materials.push_back(material);
    scene.objects.push_back(Object{0, 0, glm::scale(glm::mat4(1.0f), 10.0f * scale)});
    scene.lights.push_back(Light{});
    scene.lights.back().type = LightType::directional;
    scene.lights.back().direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    scene.lights.back().color = {3, 3, 3};
    return scene;
}

// Whether the image's centre pixel shows the plane rather than the clear colour.
bool centre_drawn(const Scene& scene, const char* isa = "auto") {
    Renderer renderer({.isa = isa});
    const RenderedImage& image = renderer.render(scene);
    const std::size_t centre = 3 * (std::size_t(scene.height / 2) * scene.width + scene.width / 2);
    const glm::vec3 radiance{image.radiance[centre], image.radiance[centre + 1], image.radiance[centre + 2]};
    return glm::length(radiance) > 0.0f;  // black clear colour: 0; the plane has at least its ambient term
}

}  // namespace

TEST_CASE("single-sided materials cull back faces, a mirroring transform swaps front and back") {
    const glm::vec3 plain(1.0f), mirrored(1.0f, -1.0f, 1.0f);
    for (const bool grazing : {false, true}) {
        CAPTURE(grazing);
        CHECK(centre_drawn(plane_scene(true, true, plain, grazing)));
        CHECK(centre_drawn(plane_scene(true, false, plain, grazing)));
        CHECK(centre_drawn(plane_scene(false, true, plain, grazing)));
        CHECK_FALSE(centre_drawn(plane_scene(false, false, plain, grazing)));
        // Scaled by -1 in y the plane's normal points down: its front faces downwards.
        CHECK_FALSE(centre_drawn(plane_scene(false, true, mirrored, grazing)));
        CHECK(centre_drawn(plane_scene(false, false, mirrored, grazing)));
    }
}

TEST_CASE("culling gives the same image with every ISA and with MSAA as the scalar path") {
    // A cube with one single-sided material seen from inside-out angles: its
    // far faces' insides are the back faces a camera inside sees.
    Scene scene = plane_scene(false, true, glm::vec3(1.0f));
    scene.meshes[0] = make_cube_mesh();
    scene.objects[0].model = glm::rotate(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), 0.5f, glm::vec3(1, 1, 0));
    scene.camera.position = {0.3f, 0.2f, 0.1f};  // inside the cube: every face is seen from behind
    for (const int msaa : {1, 4}) {
        CAPTURE(msaa);
        scene.msaa = msaa;
        Renderer scalar({.isa = "scalar"});
        const RenderedImage reference = scalar.render(scene);
        // Inside a single-sided cube nothing is drawn.
        bool any_drawn = false;
        for (const float v : reference.radiance) any_drawn = any_drawn || v > 0.0f;
        CHECK_FALSE(any_drawn);
        scene.camera.position = {0.0f, 7.0f, 1.0f};  // outside: the front faces are drawn
        const RenderedImage outside = scalar.render(scene);
        for (const char* isa : {"sse4", "avx2", "avx512", "auto"}) {
            CAPTURE(isa);
            try {
                Renderer renderer({.isa = isa});
                CHECK(renderer.render(scene).display == outside.display);
            } catch (const std::invalid_argument&) {
                MESSAGE("skipped: this CPU cannot run " << isa);
            }
        }
        scene.camera.position = {0.3f, 0.2f, 0.1f};
    }
}

namespace {

// The plane's centre radiance, seen from `side` (+1 above, −1 below) with the
// light shining from that side.
glm::vec3 centre_radiance(Scene scene, const char* isa) {
    Renderer renderer({.isa = isa});
    const RenderedImage& image = renderer.render(scene);
    const std::size_t centre = 3 * (std::size_t(scene.height / 2) * scene.width + scene.width / 2);
    return {image.radiance[centre], image.radiance[centre + 1], image.radiance[centre + 2]};
}

Scene lit_from(float side, bool double_sided = true) {
    Scene scene = plane_scene(double_sided, side > 0.0f, glm::vec3(1.0f));
    // No x component: the view mirrors x between the two sides (the pixel centre lands at ±x).
    scene.lights.back().direction = glm::normalize(glm::vec3(0.0f, -side, 0.2f));
    return scene;
}

}  // namespace

// glTF §3.9.5: a double-sided material's back face is shaded with its normal
// flipped, so a plane seen from below and lit from below looks as the same
// plane seen and lit from above (the set-ups mirror each other in y). Without
// the flip the back is lit from behind: ambient only.
TEST_CASE("a double-sided back face is lit from its own side, by every ISA") {
    for (const char* isa : {"scalar", "sse4", "avx2", "avx512", "auto"}) {
        CAPTURE(isa);
        try {
            const glm::vec3 front = centre_radiance(lit_from(1.0f), isa);
            const glm::vec3 back = centre_radiance(lit_from(-1.0f), isa);
            CHECK(front.r > 0.05f);
            for (int c = 0; c < 3; ++c) CHECK(back[c] == doctest::Approx(front[c]).epsilon(1e-4));
            // Lit from the other side, the back shows the ambient term only: far darker.
            Scene from_behind = lit_from(-1.0f);
            from_behind.lights.back().direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
            CHECK(centre_radiance(from_behind, isa).r < 0.2f * front.r);
        } catch (const std::invalid_argument&) {
            MESSAGE("skipped: this CPU cannot run " << isa);
        }
    }
}

// With a normal map the whole tangent frame flips (T, B and N, as the glTF
// sample viewer does): the back's shading normal is minus the front's. For the
// stored-tangent and both derived frames, every ISA agrees with the scalar path.
TEST_CASE("a double-sided back face flips its normal-mapped frame alike in the scalar and SIMD paths") {
    for (const DerivedTangentFrame frame : {DerivedTangentFrame::gltf, DerivedTangentFrame::learnopengl})
        for (const bool stored_tangents : {false, true}) {
            CAPTURE(int(frame));
            CAPTURE(stored_tangents);
            Scene scene = lit_from(-1.0f);
            scene.width = 48, scene.height = 40;
            // A tilted, varying normal map: x leans from −0.6 to 0.6 across u.
            std::vector<float> texels;
            for (int x = 0; x < 8; ++x) {
                const float nx = -0.6f + 1.2f * float(x) / 7.0f;
                for (float c : {nx * 0.5f + 0.5f, 0.5f, std::sqrt(1.0f - nx * nx) * 0.5f + 0.5f}) texels.push_back(c);
            }
            scene.textures.push_back(std::make_shared<const texture::Texture>(
                texture::Texture::from_pixels(8, 1, 3, texels.data(), texture::ColorSpace::linear)));
            scene.materials[0].normal_map.texture = 0;
            scene.materials[0].derived_tangent_frame = frame;
            if (stored_tangents) scene.meshes[0].tangents.assign(scene.meshes[0].positions.size(), {1, 0, 0, 1});
            Renderer scalar({.isa = "scalar"});
            const RenderedImage reference = scalar.render(scene);
            // The back (normal flipped to −Y, lit from below) is brighter than its ambient.
            const glm::vec3 centre = centre_radiance(scene, "scalar");
            Scene dark = scene;
            dark.lights.clear();
            CHECK(centre.r > 3.0f * centre_radiance(dark, "scalar").r);
            test::check_every_isa_within(scene, reference, 1);
        }
}
