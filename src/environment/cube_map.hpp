// Cube maps and the BRDF table of LearnOpenGL's image-based lighting
// (docs/reference/ibl_lighting.md): what the pre-computation makes and the
// fragment stage samples, with OpenGL's addressing and filtering rules.
//
// Faces are GL_TEXTURE_CUBE_MAP_POSITIVE_X + f (f = 0..5: +X, −X, +Y, −Y, +Z,
// −Z), addressed as the GL specification's cube map table does (face_coords).
// Each face of each level is stored with a one-texel border copied from the
// faces beside it (corners: the mean of the three texels that meet there), so
// that a bilinear tap near an edge reads the neighbouring face: OpenGL's
// GL_TEXTURE_CUBE_MAP_SEAMLESS, which the chapter enables, at the cost of
// (n+2)² instead of n² texels a face. Texels are linear RGB floats (GL stores
// RGB16F; we keep float, see the reference page).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace tessera::environment {

inline constexpr int kCubeFaces = 6;

// Face and (s, t) in [0, 1]² of direction `d` (any non-zero length): the GL
// rule, the major axis picked in the order x, y, z on ties.
struct FaceCoords {
    int face;
    float s, t;
};
FaceCoords face_coords(const glm::vec3& d);
// The direction (not unit) through face coordinates (s, t) of `face`, the
// inverse of face_coords; s, t may lie outside [0, 1] (border texels).
glm::vec3 face_direction(int face, float s, float t);

class CubeMap {
public:
    CubeMap() = default;
    // `levels` levels of side size, size/2, ..., each at least 1; texels zero.
    CubeMap(int size, int levels);

    int size(int level = 0) const { return level_size_[std::size_t(level)]; }
    int levels() const { return int(level_size_.size()); }
    // Texel (x, y) of a face, x, y in [-1, size] (−1 and size: the border).
    glm::vec3& texel(int level, int face, int x, int y) { return data_[index(level, face, x, y)]; }
    const glm::vec3& texel(int level, int face, int x, int y) const { return data_[index(level, face, x, y)]; }
    std::size_t index(int level, int face, int x, int y) const {
        const std::size_t n2 = std::size_t(level_size_[std::size_t(level)]) + 2;
        return level_offset_[std::size_t(level)] + std::size_t(face) * n2 * n2 + std::size_t(y + 1) * n2 + std::size_t(x + 1);
    }

    // Copies each face's border from its neighbours (after the interior is written).
    void fill_borders(int level);
    // Levels 1.. as 2×2 box means of the level above (glGenerateMipmap), borders filled.
    void generate_mipmaps();

    // GL_LINEAR at one level (seamless), and GL_LINEAR_MIPMAP_LINEAR at `lod`
    // (clamped to [0, levels − 1]): the reference samplers the SIMD kernels
    // (shade/ibl_kernels_simd.cpp) repeat operation for operation.
    glm::vec3 sample_bilinear(const glm::vec3& direction, int level) const;
    glm::vec3 sample_trilinear(const glm::vec3& direction, float lod) const;

    // Raw storage (the disk cache, the SIMD kernels): RGB floats, level by level.
    const std::vector<glm::vec3>& data() const { return data_; }
    std::vector<glm::vec3>& data() { return data_; }
    std::size_t level_offset(int level) const { return level_offset_[std::size_t(level)]; }

private:
    std::vector<int> level_size_;
    std::vector<std::size_t> level_offset_;  // in texels
    std::vector<glm::vec3> data_;
};

// The split-sum BRDF table (brdf.fs): (A, B) = the scale and bias of F0 at
// u = N·V, v = roughness, GL_LINEAR with GL_CLAMP_TO_EDGE.
class BrdfLut {
public:
    BrdfLut() = default;
    explicit BrdfLut(int size) : size_(size), data_(std::size_t(size) * std::size_t(size)) {}
    int size() const { return size_; }
    glm::vec2& texel(int x, int y) { return data_[std::size_t(y) * std::size_t(size_) + std::size_t(x)]; }
    const glm::vec2& texel(int x, int y) const { return data_[std::size_t(y) * std::size_t(size_) + std::size_t(x)]; }
    glm::vec2 sample(float u, float v) const;
    const std::vector<glm::vec2>& data() const { return data_; }
    std::vector<glm::vec2>& data() { return data_; }

private:
    int size_ = 0;
    std::vector<glm::vec2> data_;
};

}  // namespace tessera::environment
