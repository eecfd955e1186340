// Shows that the leak tests/fuzz/lsan-oiio.supp suppresses is OpenImageIO's, with no code of
// ours: opens each file named with OIIO::ImageInput and reads it as floats, as readImage does.
//   clang++ -g -fsanitize=address tests/fuzz/oiio_png_leak.cpp \
//       $(pkg-config --cflags --libs OpenImageIO) -o /tmp/oiio_png_leak
//   ASAN_OPTIONS=fast_unwind_on_malloc=0 /tmp/oiio_png_leak tests/fuzz/image-seeds/damaged-idat.png
// With OpenImageIO 2.4.7 that reports a direct leak of 31 bytes allocated in
// PNGInput::PngReadCallback (its error message, skipped by libpng's longjmp). Not built by CMake.
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        auto in = OIIO::ImageInput::open(argv[i]);
        if (!in) {
            std::printf("%s: not opened: %s\n", argv[i], OIIO::geterror().c_str());
            continue;
        }
        const OIIO::ImageSpec& spec = in->spec();
        std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
        const bool read =
            in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
        std::printf("%s: %dx%d, %d channels, %s\n", argv[i], spec.width, spec.height,
                    spec.nchannels, read ? "read" : in->geterror().c_str());
    }
    return 0;
}
