// Checks of the arrays Python hands in: what the scene's consumers trust
// (tessera/scene.hpp) is established here, with a ValueError for anything else.
#include <cmath>
#include <string>

#include "python/bindings.hpp"

namespace tessera::python {

namespace {

[[noreturn]] void refuse(const char* what, const std::string& message) {
    throw py::value_error(std::string(what) + ": " + message);
}

std::string shape_text(const py::array& a) {
    std::string text = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
    return text + (a.ndim() == 1 ? ",)" : ")");
}

py::array as_array(const py::handle& value, const char* what) {
    if (value.is_none()) refuse(what, "expected an array, got None");
    py::array a = py::array::ensure(value);
    if (!a) refuse(what, "expected an array");
    return a;
}

}  // namespace

FloatRows float_rows(const py::handle& value, py::ssize_t columns, const char* what) {
    const py::array a = as_array(value, what);
    const char kind = a.dtype().kind();
    if (kind != 'f')
        refuse(what, "expected a float32 or float64 array, got dtype " + std::string(py::str(a.dtype())));
    if (a.ndim() != 2 || a.shape(1) != columns)
        refuse(what, "expected shape (N, " + std::to_string(columns) + "), got " + shape_text(a));
    auto rows = FloatRows::ensure(a);  // a copy only where not float32 in C order
    const float* v = rows.data();
    for (py::ssize_t i = 0; i < rows.size(); ++i)
        if (!std::isfinite(v[i]))
            refuse(what, "row " + std::to_string(i / columns) + " holds " + std::to_string(v[i]) +
                             "; every value must be finite");
    return rows;
}

std::vector<std::uint32_t> triangle_indices(const py::handle& value, std::size_t vertex_count, const char* what) {
    const py::array a = as_array(value, what);
    const char kind = a.dtype().kind();
    if (kind != 'i' && kind != 'u')
        refuse(what, "expected an integer array, got dtype " + std::string(py::str(a.dtype())));
    if (!((a.ndim() == 2 && a.shape(1) == 3) || (a.ndim() == 1 && a.shape(0) % 3 == 0)))
        refuse(what, "expected shape (M, 3) or (3M,), got " + shape_text(a));
    const auto wide = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    std::vector<std::uint32_t> indices(std::size_t(wide.size()));
    const std::int64_t* v = wide.data();
    for (std::size_t i = 0; i < indices.size(); ++i) {
        if (v[i] < 0 || std::uint64_t(v[i]) >= vertex_count)
            refuse(what, "triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(v[i]) +
                             "; expected 0.." + std::to_string(std::int64_t(vertex_count) - 1));
        indices[i] = std::uint32_t(v[i]);
    }
    return indices;
}

namespace {

template <int N>
glm::mat<N, N, float> square_matrix(const py::handle& value, const char* what) {
    const py::array a = as_array(value, what);
    const char kind = a.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        refuse(what, "expected a numeric array, got dtype " + std::string(py::str(a.dtype())));
    if (a.ndim() != 2 || a.shape(0) != N || a.shape(1) != N)
        refuse(what, "expected shape (" + std::to_string(N) + ", " + std::to_string(N) + "), got " + shape_text(a));
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    glm::mat<N, N, float> m(1.0f);
    for (int r = 0; r < N; ++r)
        for (int c = 0; c < N; ++c) {
            const double x = d.at(r, c);
            if (!std::isfinite(x)) refuse(what, "every value must be finite");
            m[c][r] = float(x);  // glm is column-major: m[column][row]
        }
    return m;
}

}  // namespace

glm::mat4 matrix4(const py::handle& value, const char* what) { return square_matrix<4>(value, what); }
glm::mat3 matrix3(const py::handle& value, const char* what) { return square_matrix<3>(value, what); }

glm::vec3 vec3(const py::handle& value, const char* what) {
    const auto a = py::array_t<double, py::array::forcecast>::ensure(value);
    if (!a || a.ndim() != 1 || a.shape(0) != 3) refuse(what, "expected three numbers");
    const glm::vec3 v(float(a.at(0)), float(a.at(1)), float(a.at(2)));
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) refuse(what, "every value must be finite");
    return v;
}

py::array_t<float> to_numpy(const glm::mat4& m) {
    py::array_t<float> a({4, 4});
    auto w = a.mutable_unchecked<2>();
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) w(r, c) = m[c][r];
    return a;
}

}  // namespace tessera::python
