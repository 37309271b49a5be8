#include <doctest/doctest.h>

#include <cstring>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "geometry/vertex_stage.hpp"

using namespace tessera;

TEST_CASE("the normal matrix keeps normals perpendicular under non-uniform scale") {
    const glm::mat4 model = glm::scale(glm::mat4(1.0f), glm::vec3(4.0f, 1.0f, 1.0f));
    // A surface through (1,0,0) and (0,1,0): tangent (-1,1,0), normal (1,1,0).
    const glm::vec3 tangent_world = glm::vec3(model * glm::vec4(-1, 1, 0, 0));
    const glm::vec3 normal_world = geometry::normal_matrix(model) * glm::vec3(1, 1, 0);
    CHECK(glm::dot(tangent_world, normal_world) == doctest::Approx(0.0f));
    // mat3(model) alone would not be perpendicular.
    CHECK(glm::dot(tangent_world, glm::mat3(model) * glm::vec3(1, 1, 0)) != doctest::Approx(0.0f));
}

TEST_CASE("shade_vertices computes WorldPos, clip position and normal as the reference vertex shader") {
    Mesh mesh;
    mesh.positions = {{1, 2, 3}};
    mesh.normals = {{0, 0, 1}};
    mesh.uvs = {{0.25f, 0.75f}};
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0));
    const glm::mat4 view_projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 100.0f);
    geometry::ShadedVertex out;
    geometry::shade_vertices(mesh, 0, model, view_projection, {&out, 1});
    CHECK(out.world_pos.x == doctest::Approx(11.0f));
    CHECK(out.world_pos.y == doctest::Approx(2.0f));
    const glm::vec4 expected = view_projection * glm::vec4(11, 2, 3, 1);
    for (int i = 0; i < 4; ++i) CHECK(out.clip_pos[i] == doctest::Approx(expected[i]));
    CHECK(out.normal.z == doctest::Approx(1.0f));
    CHECK(out.uv.x == 0.25f);
}

namespace {

bool same_bits(const void* a, const void* b, std::size_t bytes) { return std::memcmp(a, b, bytes) == 0; }

}  // namespace

// The vertex kernels compute, a vector of vertices at a time, what shade_vertices,
// outcode and to_screen compute one by one: the same bits for every ISA,
// including vertices behind the camera, past the guard band, and non-finite ones.
TEST_CASE("the vertex stage gives the scalar result bit for bit with every ISA's kernel") {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<float> coord(-3.0f, 3.0f), unit(0.0f, 1.0f);
    Mesh mesh;
    constexpr std::size_t kVertices = 4099;  // not a multiple of any lane count
    for (std::size_t i = 0; i < kVertices; ++i) {
        glm::vec3 p(coord(rng), coord(rng), coord(rng) - 4.0f);
        if (i % 13 == 0) p *= 1000.0f;  // far outside: guard-band and far-plane outcodes
        if (i % 17 == 0) p.z = 6.0f;    // behind the camera
        glm::vec3 n(coord(rng), coord(rng), coord(rng));
        if (i % 101 == 0) n.x = std::numeric_limits<float>::quiet_NaN();
        if (i % 103 == 0) p.y = std::numeric_limits<float>::infinity();
        mesh.positions.push_back(p);
        mesh.normals.push_back(n);
        mesh.uvs.push_back({unit(rng), unit(rng)});
    }
    const glm::mat4 model = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -0.2f, 0.1f)), 0.7f,
                                                   glm::normalize(glm::vec3(1, 2, 3))),
                                       glm::vec3(1.5f, 0.5f, 2.0f));
    const glm::mat4 view_projection =
        glm::perspective(glm::radians(50.0f), 16.0f / 9.0f, 0.1f, 100.0f) *
        glm::lookAt(glm::vec3(0.5f, 0.2f, 3.0f), glm::vec3(0, 0, -4), glm::vec3(0, 1, 0));
    const geometry::Viewport viewport{1280, 720};
    const geometry::GuardBand guard(viewport.width, viewport.height);

    for (const bool with_uvs : {true, false}) {
        CAPTURE(with_uvs);
        if (!with_uvs) mesh.uvs.clear();
        // From vertex 5 on, so runs start off any alignment.
        const std::size_t first = 5, count = kVertices - first;
        std::vector<geometry::ShadedVertex> expected(count);
        std::vector<std::uint32_t> expected_codes(count);
        std::vector<geometry::ScreenVertex> expected_screen(count);
        geometry::run_vertex_stage(simd::Isa::scalar, mesh, first, model, view_projection, guard, viewport,
                                   {expected, expected_codes.data(), expected_screen.data()});
        std::size_t clipped = 0, not_finite = 0;
        for (std::uint32_t code : expected_codes)
            clipped += (code & geometry::kClipPlaneBits) != 0, not_finite += code == geometry::kNotFinite;
        REQUIRE(clipped > 100);  // the cases above really occur
        REQUIRE(not_finite > 50);
        REQUIRE(clipped < count / 2);

        for (simd::Isa isa : {simd::Isa::sse4, simd::Isa::avx2, simd::Isa::avx512}) {
            CAPTURE(simd::isa_name(isa));
            if (!simd::isa_supported(isa)) {
                MESSAGE("skipped: " << simd::isa_name(isa) << " is not supported by this CPU");
                continue;
            }
            // The output at four alignments against cache lines: the kernels
            // store whole vectors and prefetch ahead, yet write only the run.
            for (const std::size_t shift : {0, 1, 2, 3}) {
                CAPTURE(shift);
                const geometry::ShadedVertex untouched{{7, 7, 7, 7}, {7, 7, 7}, {7, 7, 7}, {7, 7}};
                std::vector<geometry::ShadedVertex> room(count + 4, untouched);
                const std::span<geometry::ShadedVertex> vertices(room.data() + shift, count);
                std::vector<std::uint32_t> codes(count);
                std::vector<geometry::ScreenVertex> screen(count);
                geometry::run_vertex_stage(isa, mesh, first, model, view_projection, guard, viewport,
                                           {vertices, codes.data(), screen.data()});
                for (std::size_t i = 0; i < room.size(); ++i)
                    if (i < shift || i >= shift + count) REQUIRE(same_bits(&room[i], &untouched, sizeof untouched));
                std::size_t mismatched = 0;
                for (std::size_t i = 0; i < count; ++i) {
                    bool ok = same_bits(&vertices[i], &expected[i], sizeof(geometry::ShadedVertex)) &&
                              codes[i] == expected_codes[i] && screen[i].outcode == codes[i] &&
                              expected_screen[i].outcode == expected_codes[i];
                    // The screen position means something only where no plane clips the vertex.
                    if (!(expected_codes[i] & (geometry::kClipPlaneBits | geometry::kNotFinite)))
                        ok = ok && same_bits(&screen[i], &expected_screen[i], sizeof(geometry::ScreenVertex));
                    mismatched += !ok;
                }
                CHECK(mismatched == 0);
            }
        }
    }
}

TEST_CASE("a mirroring model matrix flips the tangent's handedness so the bitangent follows the surface") {
    // A surface in z = 0 with normal +z, tangent +x and bitangent cross(N, T)·w = +y.
    Mesh mesh;
    mesh.positions = {{0, 0, 0}};
    mesh.normals = {{0, 0, 1}};
    mesh.tangents = {{1, 0, 0, 1}};
    const glm::vec3 bitangent_object = glm::cross(mesh.normals[0], glm::vec3(mesh.tangents[0])) * mesh.tangents[0].w;
    for (const glm::vec3 scale : {glm::vec3(1, 1, 1), glm::vec3(-1, 1, 1), glm::vec3(1, -1, 1), glm::vec3(-1, -1, -1),
                                  glm::vec3(2, -3, 1)}) {
        INFO("scale ", scale.x, " ", scale.y, " ", scale.z);
        const glm::mat4 model = glm::scale(glm::mat4(1.0f), scale);
        std::vector<glm::vec4> out(1);
        geometry::transform_tangents(mesh, 0, model, out);
        const glm::vec3 normal_world = glm::normalize(geometry::normal_matrix(model) * mesh.normals[0]);
        const glm::vec3 bitangent_world = glm::cross(normal_world, glm::vec3(out[0])) * out[0].w;
        // The bitangent the surface carries is the object's one taken through the model matrix.
        const glm::vec3 expected = glm::mat3(model) * bitangent_object;
        CHECK(glm::dot(glm::normalize(bitangent_world), glm::normalize(expected)) == doctest::Approx(1.0f));
        CHECK(glm::vec3(out[0]) == glm::mat3(model) * glm::vec3(mesh.tangents[0]));
    }
}
