// The Python module's parts: each binds one part of the C++ API onto the
// module; the arrays' checks are shared. No rendering or comparison is done
// here: the bindings call the same libraries as the command line.
#pragma once

#include <cstdint>
#include <memory>
#include <shared_mutex>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "tessera/renderer.hpp"
#include "tessera/scene.hpp"

namespace tessera::python {

namespace py = pybind11;

// A scene shared between Python and the renderers that draw it. Renderers draw
// it with the GIL released, several at once (shared lock); changes, and a
// render at another size than the scene's, take it alone (unique lock).
struct SharedScene {
    Scene scene;
    mutable std::shared_mutex mutex;
};

// The arrays' checks (arrays.cpp). Each throws py::value_error naming `what`
// and what was expected: a wrong dtype, shape, a value that is not finite, an
// index out of range.
// An (N, columns) array of finite floats (float32 or float64), as float32.
using FloatRows = py::array_t<float, py::array::c_style | py::array::forcecast>;
FloatRows float_rows(const py::handle& array, py::ssize_t columns, const char* what);
// Triangle indices: an (M, 3) or (3M,) array of integers in [0, vertex_count).
std::vector<std::uint32_t> triangle_indices(const py::handle& array, std::size_t vertex_count, const char* what);
// A 4×4 finite matrix (float or integer dtype), numpy's row-major layout: m[row][column].
glm::mat4 matrix4(const py::handle& array, const char* what);
glm::mat3 matrix3(const py::handle& array, const char* what);
// A finite 3-vector from any sequence of three numbers.
glm::vec3 vec3(const py::handle& value, const char* what);
// A 4×4 glm matrix as a numpy array (row-major).
py::array_t<float> to_numpy(const glm::mat4& m);

void bind_scene(py::module_& m);
void bind_render(py::module_& m);
void bind_check(py::module_& m);

}  // namespace tessera::python
