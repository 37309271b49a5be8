#include "golden_compare.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "tessera/image_io.hpp"

namespace tessera::test {

GoldenResult compare_with_golden(const RenderedImage& image, const std::filesystem::path& golden_png,
                                 const std::filesystem::path& failure_dir, const std::string& name) {
    GoldenResult result;
    if (!std::filesystem::exists(golden_png)) {
        result.message = golden_png.string() + " does not exist (tools/regenerate_golden.sh makes it)";
        return result;
    }
    OIIO::ImageBuf golden(golden_png.string());
    if (!golden.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
        result.message = golden_png.string() + ": " + golden.geterror();
        return result;
    }
    const OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    OIIO::ImageBuf actual(spec, const_cast<std::uint8_t*>(image.display.data()));
    if (golden.spec().width != image.width || golden.spec().height != image.height || golden.spec().nchannels != 3) {
        result.message = "size differs: golden " + std::to_string(golden.spec().width) + "x" +
                         std::to_string(golden.spec().height) + ", rendered " + std::to_string(image.width) + "x" +
                         std::to_string(image.height);
    } else {
        const auto cmp = OIIO::ImageBufAlgo::compare(actual, golden, kGoldenFailThreshold, kGoldenWarnThreshold);
        const double pixels = double(image.width) * image.height;
        // OpenImageIO 2.4 also sets `error` when any pixel fails: only an error without failures is a real one.
        const bool comparison_error = cmp.error && cmp.nfail == 0;
        result.passed = double(cmp.nfail) <= kGoldenMaxFailFraction * pixels && cmp.maxerror <= kGoldenMaxError &&
                        double(cmp.nwarn) <= kGoldenMaxWarnFraction * pixels && !comparison_error;
        result.message = "max error " + std::to_string(cmp.maxerror * 255.0) + "/255 at (" + std::to_string(cmp.maxx) +
                         ", " + std::to_string(cmp.maxy) + "), mean error " + std::to_string(cmp.meanerror * 255.0) +
                         "/255, " + std::to_string(cmp.nfail) + " pixels over the fail threshold, " +
                         std::to_string(cmp.nwarn) + " over the warning threshold" + (comparison_error ? " (comparison error)" : "");
    }
    if (!result.passed) {
        std::filesystem::create_directories(failure_dir);
        const auto actual_path = failure_dir / (name + ".actual.png");
        const auto diff_path = failure_dir / (name + ".diff.png");
        actual.write(actual_path.string(), OIIO::TypeDesc::UINT8);
        if (golden.spec().width == image.width && golden.spec().height == image.height) {
            OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(actual, golden);
            diff = OIIO::ImageBufAlgo::mul(diff, 16.0f);  // small differences made visible
            diff.write(diff_path.string(), OIIO::TypeDesc::UINT8);
        }
        result.message += "; actual image: " + actual_path.string() + ", diff (x16): " + diff_path.string();
    }
    return result;
}

}  // namespace tessera::test
