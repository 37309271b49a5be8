// The `tessera._tessera` extension module: the C++ renderer's Python face.
// C++ errors become Python exceptions carrying the C++ message: a scene file's
// SceneError keeps its "file:line:column: message".
#include "python/bindings.hpp"
#include "tessera/image_io.hpp"

PYBIND11_MODULE(_tessera, m) {
    namespace py = pybind11;
    using namespace tessera::python;
    m.doc() = "Tessera, a multithreaded SIMD CPU rasterizer: scenes in, NumPy images out";
    // A scene that cannot be used: a ValueError, so that callers catching bad input catch it too.
    py::register_exception<tessera::SceneError>(m, "SceneError", PyExc_ValueError);
    py::register_exception<tessera::ImageError>(m, "ImageError", PyExc_OSError);
    bind_scene(m);
    bind_render(m);
    bind_check(m);
}
