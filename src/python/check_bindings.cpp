// The golden-image comparison of `tessera check` (check/compare.hpp), for
// tessera.check.assert_matches_golden, and image reading for tests.
#include <cstring>
#include <string>

#include <OpenImageIO/imageio.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "check/compare.hpp"
#include "python/bindings.hpp"
#include "tessera/image_io.hpp"

namespace tessera::python {

namespace {

// What the comparison reads of `image`: a Frame's images, or an (H, W, 3)
// array: uint8 display values, or float radiance (an EXR golden's units).
RenderedImage image_of(const py::handle& image) {
    RenderedImage out;
    py::object pixels = py::reinterpret_borrow<py::object>(image);
    if (py::hasattr(image, "color") && py::hasattr(image, "radiance")) {  // a Frame
        const py::object radiance = image.attr("radiance");
        pixels = image.attr("color");
        if (!radiance.is_none()) {
            const auto r = radiance.cast<py::array_t<float, py::array::c_style>>();
            out.radiance.assign(r.data(), r.data() + r.size());
        }
    }
    const py::array a = py::array::ensure(pixels);
    if (!a || a.ndim() != 3 || a.shape(2) != 3)
        throw py::value_error("image: expected a Frame or an (H, W, 3) array");
    out.height = int(a.shape(0)), out.width = int(a.shape(1));
    if (a.dtype().is(py::dtype::of<std::uint8_t>())) {
        const auto d = py::array_t<std::uint8_t, py::array::c_style>::ensure(a);
        out.display.assign(d.data(), d.data() + d.size());
    } else if (a.dtype().kind() == 'f') {
        const auto r = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
        out.radiance.assign(r.data(), r.data() + r.size());
    } else {
        throw py::value_error("image: expected uint8 (display) or float (radiance) values, got dtype " +
                              std::string(py::str(a.dtype())));
    }
    return out;
}

check::Thresholds thresholds_of(const py::dict& given) {
    check::Thresholds t;
    for (const auto& [key, value] : given) {
        const std::string name = py::str(key);
        if (name == "perceptual") { t.perceptual = value.cast<bool>(); continue; }
        const double v = value.cast<double>();
        if (name == "fail") t.fail = v;
        else if (name == "fail_relative") t.fail_relative = v;
        else if (name == "fail_pixels") t.fail_pixels = v;
        else if (name == "fail_ratio") t.fail_ratio = v;
        else if (name == "warn") t.warn = v;
        else if (name == "warn_relative") t.warn_relative = v;
        else if (name == "warn_pixels") t.warn_pixels = v;
        else if (name == "warn_ratio") t.warn_ratio = v;
        else if (name == "max_error") t.max_error = v;
        else if (name == "max_warn_pixels") t.max_warn_pixels = v;
        else if (name == "max_warn_ratio") t.max_warn_ratio = v;
        else
            throw py::value_error("unknown threshold '" + name +
                                  "' (expected fail, fail_relative, fail_pixels, fail_ratio, warn, warn_relative, "
                                  "warn_pixels, warn_ratio, max_error, max_warn_pixels, max_warn_ratio, perceptual)");
    }
    return t;
}

}  // namespace

void bind_check(py::module_& m) {
    m.def("compare_with_golden",
          [](const py::handle& image, const std::filesystem::path& golden, const py::dict& thresholds) {
              const RenderedImage actual = image_of(image);
              const check::Thresholds t = thresholds_of(thresholds);
              const check::GoldenKind kind = check::golden_kind_for(golden);
              if (kind == check::GoldenKind::exr && actual.radiance.empty())
                  throw py::value_error("an .exr golden compares radiance: render with radiance=True");
              if (kind == check::GoldenKind::png && actual.display.empty())
                  throw py::value_error("a .png golden compares the colour image: pass a Frame or uint8 array");
              check::Comparison c;
              {
                  py::gil_scoped_release release;
                  c = check::compare_images(check::actual_image(actual, kind), check::read_golden(golden), t, kind);
              }
              py::dict d;
              d["status"] = std::string(check::status_name(c.status));
              d["reason"] = c.reason;
              d["compared"] = c.compared;
              d["pixels"] = c.metrics.pixels;
              d["max_error"] = c.metrics.max_error;
              d["max_x"] = c.metrics.max_x, d["max_y"] = c.metrics.max_y, d["max_channel"] = c.metrics.max_channel;
              d["mean_error"] = c.metrics.mean_error;
              d["rms_error"] = c.metrics.rms_error;
              d["psnr"] = c.metrics.psnr;
              d["pixels_over_fail"] = c.metrics.pixels_over_fail;
              d["pixels_over_warn"] = c.metrics.pixels_over_warn;
              return d;
          },
          py::arg("image"), py::arg("golden"), py::arg("thresholds") = py::dict(),
          "Compares a Frame or array with a golden image by tessera check's rules; returns the status and metrics");

    m.def("write_golden",
          [](const py::handle& image, const std::filesystem::path& golden) {
              RenderedImage actual = image_of(image);
              const bool exr = check::golden_kind_for(golden) == check::GoldenKind::exr;
              if (exr && actual.radiance.empty())
                  throw py::value_error("an .exr golden holds radiance: render with radiance=True");
              if (!exr && actual.display.empty())
                  throw py::value_error("a .png golden holds the colour image: pass a Frame or uint8 array");
              py::gil_scoped_release release;
              std::filesystem::create_directories(golden.parent_path().empty() ? "." : golden.parent_path());
              write_image(actual, golden);  // a temporary file renamed into place
          },
          py::arg("image"), py::arg("golden"), "Writes a golden image (.png: colour; .exr: radiance)");

    m.def("read_image",
          [](const std::filesystem::path& path, bool channels) -> py::object {
              auto in = OIIO::ImageInput::open(path.string());
              if (!in) throw std::runtime_error(path.string() + ": cannot read image: " + OIIO::geterror());
              const OIIO::ImageSpec spec = in->spec();
              const auto fail = [&] {
                  throw std::runtime_error(path.string() + ": cannot read image: " + in->geterror());
              };
              const py::ssize_t h = spec.height, w = spec.width, n = spec.nchannels;
              if (spec.format == OIIO::TypeDesc::UINT8 && spec.channelformats.empty() && !channels) {
                  py::array_t<std::uint8_t> out({h, w, n});
                  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, out.mutable_data())) fail();
                  return out;
              }
              // Channel by channel, each in its own type: OpenImageIO would scale a uint channel into [0, 1].
              py::dict by_name;
              py::array_t<float> all({h, w, n});
              for (int c = 0; c < spec.nchannels; ++c) {
                  const bool uint = spec.channelformat(c).basetype == OIIO::TypeDesc::UINT;
                  py::array plane = uint ? py::array(py::array_t<std::uint32_t>({h, w})) : py::array(py::array_t<float>({h, w}));
                  if (!in->read_image(0, 0, c, c + 1, uint ? OIIO::TypeDesc::UINT32 : OIIO::TypeDesc::FLOAT,
                                      plane.mutable_data()))
                      fail();
                  by_name[py::str(spec.channelnames[std::size_t(c)])] = plane;
                  auto a = all.mutable_unchecked<3>();
                  for (py::ssize_t y = 0; y < h; ++y)
                      for (py::ssize_t x = 0; x < w; ++x)
                          a(y, x, c) = uint ? float(static_cast<const std::uint32_t*>(plane.data())[y * w + x])
                                            : static_cast<const float*>(plane.data())[y * w + x];
              }
              if (channels) return by_name;
              return all;
          },
          py::arg("path"), py::arg("channels") = false,
          "Reads an image file as (H, W, C): uint8 for 8-bit files, float32 otherwise (uint channels by value). "
          "channels=True returns {name: (H, W) array} in each channel's own type (uint32 for the ids).");
}

}  // namespace tessera::python
