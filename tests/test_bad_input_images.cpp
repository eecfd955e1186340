// compare's image readers: the same picture stored as grey, grey with alpha, RGB or RGBA, PNG or
// one- and three-channel EXR reads the same; a PNG's colour is not multiplied by its alpha;
// sizes beyond what is read, and what is not a regular file, are refused before any memory is
// taken; a file is read as what its name says (.png, .exr) or refused.
#include "bad_input.h"
#include "image_io.h"
#include "support.h"

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <filesystem>
#include <sys/stat.h>

namespace fs = std::filesystem;
using namespace ssgi;
using ssgi::test::BadInput;

namespace {

// Writes `values` (channels interleaved) as a file of that many channels.
void writeChannels(const std::string& path, int channels, const std::vector<float>& values,
                   OIIO::TypeDesc type) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(4, 2, channels, type);
    if (channels == 2) spec.alpha_channel = 1;
    if (channels == 4) spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1); // stored as given, not divided by alpha
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

TEST_F(BadInput, CompareReadsWhatTheFileHolds) {
    // Eight grey levels, 0/255 .. 255/255 in steps of 255/7, and alpha 128/255 (exact in 8 bits).
    const float half = 128.0f / 255.0f;
    std::vector<float> grey, greyAlpha, rgb, rgba;
    for (int i = 0; i < 8; ++i) {
        const float v = float(i * 255 / 7) / 255.0f;
        grey.push_back(v);
        greyAlpha.insert(greyAlpha.end(), {v, half});
        rgb.insert(rgb.end(), {v, v, v});
        rgba.insert(rgba.end(), {v, v, v, half});
    }
    const std::pair<std::string, std::pair<int, const std::vector<float>*>> files[] = {
        {"grey.png", {1, &grey}}, {"grey-alpha.png", {2, &greyAlpha}},
        {"rgb.png", {3, &rgb}},   {"rgba.png", {4, &rgba}},
        {"grey.exr", {1, &grey}}, {"rgb.exr", {3, &rgb}},
    };
    for (const auto& [name, content] : files) {
        SCOPED_TRACE(name);
        const std::string path = (dir_ / name).string();
        writeChannels(path, content.first, *content.second,
                      name.ends_with(".png") ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
        uint32_t w = 0, h = 0;
        const std::vector<float> read = readImage(path, w, h);
        ASSERT_EQ(read.size(), 32u);
        for (int i = 0; i < 8; ++i) {
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(read[4 * i + c], grey[i], 1e-6f) << "pixel " << i << " channel " << c;
            const bool alpha = content.first == 2 || content.first == 4;
            EXPECT_EQ(read[4 * i + 3], alpha ? half : 1.0f);
        }
    }
    // The program agrees: the same picture two ways is the same, and alpha is said.
    const std::string compare =
        (fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "compare").string();
    for (const auto& [a, b] :
         {std::pair{"grey.png", "rgb.png"}, std::pair{"grey-alpha.png", "rgba.png"},
          std::pair{"rgba.png", "rgb.png"}, std::pair{"grey.exr", "rgb.exr"}}) {
        const test::CommandResult run =
            test::runCommand(compare + " " + (dir_ / a).string() + " " + (dir_ / b).string() +
                             " --max-relmse 0 --max-diff 0");
        EXPECT_EQ(run.status, 0) << a << " " << b << "\n" << run.output;
        if (std::string(a).find("alpha") != std::string::npos) {
            EXPECT_NE(run.output.find("alpha is not applied"), std::string::npos) << run.output;
        }
    }

    // A PNG that declares 100000x100000 pixels (its IHDR, CRCs included, and no pixels):
    // refused before anything is allocated, as is a FIFO.
    std::string png = "\x89PNG\r\n\x1a\n";
    png += std::string("\0\0\0\x0dIHDR\0\x01\x86\xa0\0\x01\x86\xa0\x08\x02\0\0\0", 21);
    png += "\x27\x30\x9c\x9f";                              // the chunk's CRC-32
    png += std::string("\0\0\0\0IDAT\x35\xaf\x06\x1e", 12); // an empty IDAT: no pixels
    png += std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    const std::string huge = write("huge.png", png);
    const fs::path fifo = dir_ / "fifo.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // A file named .png is read as a PNG only, one named .exr as an OpenEXR only: an EXR named
    // .png was read as linear radiance and compared as a display image, and a damaged .png was
    // handed to every format OpenImageIO has (fuzz_image spent its time in LibRaw).
    // An EXR header of 53 bytes whose string attribute declares 1.8 GB: OpenEXR allocated that
    // before reading it (fuzz_image's out-of-memory finding); refused from its header.
    const std::string hugeAttribute = write(
        "huge-attribute.exr",
        std::string("v/1\x01\x02\0\0\0capDate\0string\0\0\0\0lineOrder\0\0\x01\0\0\0\x01\0\0\0"
                    "\x0dIHDR\0\0c",
                    53));
    fs::copy_file(dir_ / "rgb.exr", dir_ / "exr.png");
    fs::copy_file(dir_ / "rgb.png", dir_ / "png.exr");
    for (const auto& [path, message] :
         {std::pair{huge, std::string("declares 100000x100000 pixels")},
          std::pair{fifo.string(), std::string("not a regular file")},
          std::pair{(dir_ / "exr.png").string(), std::string("not a readable PNG file")},
          std::pair{(dir_ / "png.exr").string(), std::string("not a readable OpenEXR file")},
          std::pair{hugeAttribute, std::string("declares 1811939328 bytes, and 26 are left")}}) {
        const test::CommandResult run =
            test::runCommand(compare + " " + path + " " + (dir_ / "rgb.png").string());
        EXPECT_EQ(run.status, 2) << run.output;
        EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
    }
}

// What the writer writes the reader reads: a side beyond kMaxImageSide is refused by both (a
// 20000x1 PNG was written and then refused by readImage), and the largest side round-trips.
TEST_F(BadInput, ImagesWrittenAreImagesRead) {
    const std::vector<float> wide(size_t(20000) * 4, 0.5f);
    for (const char* name : {"wide.png", "wide.exr"}) {
        const std::string path = (dir_ / name).string();
        try {
            writeImage(path, 20000, 1, wide);
            ADD_FAILURE() << name << " was written";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("images of 1..16384 pixels a side are written"),
                      std::string::npos)
                << e.what();
        }
        EXPECT_FALSE(fs::exists(path));
    }
    const std::vector<float> largest(size_t(kMaxImageSide) * 4, 0.5f);
    const std::string path = (dir_ / "largest.png").string();
    writeImage(path, kMaxImageSide, 1, largest);
    uint32_t width = 0, height = 0;
    readImage(path, width, height);
    EXPECT_EQ(width, uint32_t(kMaxImageSide));
    EXPECT_EQ(height, 1u);
    // Fewer values than the size needs: refused, not read past.
    EXPECT_THROW(writeImage((dir_ / "short.png").string(), 4, 4, std::vector<float>(12)),
                 InputError);
}

// PNG bytes: the signature, then each chunk with its length and CRC.
std::string pngFile(const std::vector<std::pair<std::string, std::string>>& chunks) {
    const auto crc32 = [](const std::string& bytes) {
        uint32_t crc = 0xffffffffu;
        for (unsigned char byte : bytes) {
            crc ^= byte;
            for (int k = 0; k < 8; ++k)
                crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
        }
        return crc ^ 0xffffffffu;
    };
    const auto bigEndian = [](uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    };
    std::string png = "\x89PNG\r\n\x1a\n";
    for (const auto& [type, data] : chunks)
        png += bigEndian(uint32_t(data.size())) + type + data + bigEndian(crc32(type + data));
    return png;
}

// A 128-byte PNG declaring 16384x16384 RGBA pixels (a legal size) with one stored deflate block
// of 60 zero bytes: refused from its header within a second, by compare and by the glTF
// loader (it took 27 s and 7.4 GB to refuse, 8.7 s under a 4 GB limit).
TEST_F(BadInput, APngTooSmallForItsSizeIsRefusedFromItsHeader) {
    const auto bigEndian = [](uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    };
    const std::string header =
        bigEndian(16384) + bigEndian(16384) + std::string("\x08\x06\0\0\0", 5);
    std::string zlib = std::string("\x78\x01\x01\x3c\x00\xc3\xff", 7) + std::string(60, '\0');
    zlib += bigEndian(60u << 16 | 1u); // adler32 of 60 zeros: a = 1, b = 60
    const std::string png = pngFile({{"IHDR", header}, {"IDAT", zlib}, {"IEND", ""}});
    ASSERT_EQ(png.size(), 128u);
    const std::string path = write("huge.png", png);

    const auto start = std::chrono::steady_clock::now();
    uint32_t width = 0, height = 0;
    try {
        readImage(path, width, height);
        ADD_FAILURE() << "read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(path + ": a PNG of 16384x16384 pixels (1073741824 "
                                                    "bytes decoded), which its 128 bytes cannot "
                                                    "hold"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);

    // compare, under a 4 GB address-space limit as the report had it: exit 2 naming the file.
    const std::string compare =
        (fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "compare").string();
    const test::CommandResult run =
        test::runCommand("ulimit -v 4000000; " + compare + " " + path + " " + path);
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find("error: " + path + ": a PNG of 16384x16384 pixels"),
              std::string::npos)
        << run.output;

    // The same bytes as a glTF's texture.
    nlohmann::json gltf = test::meshJson(test::kTriangle.size(), 3);
    gltf["buffers"][0]["uri"] = "mesh.bin";
    write("mesh.bin", test::meshBytes(test::kTriangle, {0, 1, 2}));
    gltf["images"] = {{{"uri", "huge.png"}}};
    gltf["textures"] = {{{"source", 0}}};
    const auto loadStart = std::chrono::steady_clock::now();
    EXPECT_NE(loadError(write("texture.gltf", gltf.dump()))
                  .find("image 0 is a PNG of 16384x16384 pixels (1073741824 bytes decoded), "
                        "which its 128 bytes cannot hold"),
              std::string::npos);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count(),
              1.0);
}

} // namespace
