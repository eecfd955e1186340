// The reference cache as a hostile user leaves it: an entry whose bytes were changed or cut
// short, a FIFO or a folder where an entry goes. Each is said on stderr, rendered again and never
// served as the ground truth; nothing hangs and no temporary is left in the cache.
#include "bad_input.h"
#include "reference/cache.h"
#include "support.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <sys/stat.h>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::reference;
using ssgi::test::BadInput;

namespace {

std::string entryFiles(const fs::path& dir) {
    std::string names;
    for (const auto& entry : fs::directory_iterator(dir))
        names += entry.path().filename().string() + " ";
    return names;
}

TEST_F(BadInput, ReferenceCacheEntriesAreVerifiedBeforeTheyAreBelieved) {
    const Scene scene = loadScene(test::sourcePath("tests/scenes/empty-box.json"));
    ReferenceOptions options;
    options.width = options.height = 8;
    options.spp = 2;
    const fs::path cache = dir_ / "cache";
    const fs::path entry = cache / (referenceKey(scene, scene.camera, options) + ".ref");
    bool hit = true;
    const ReferenceImage truth = cachedReference(scene, scene.camera, options, cache, &hit);
    EXPECT_FALSE(hit);
    ASSERT_TRUE(fs::is_regular_file(entry)) << entryFiles(cache);

    // Each way to spoil the entry, then what a request for it must get.
    const auto overwrite = [&] {
        std::fstream file(entry, std::ios::in | std::ios::out | std::ios::binary);
        file.seekp(100);
        file.write("\x7f\x7f\x7f\x7f", 4); // a pixel's bytes: a finite, wrong value
    };
    const auto cut = [&] { fs::resize_file(entry, fs::file_size(entry) - 7); };
    const auto fifo = [&] {
        fs::remove(entry);
        ASSERT_EQ(::mkfifo(entry.c_str(), 0600), 0);
    };
    const auto folder = [&] {
        fs::remove(entry);
        fs::create_directories(entry / "inside");
    };
    const std::pair<const char*, std::function<void()>> spoils[] = {
        {"checksum does not match", overwrite},
        {"were expected", cut},
        {"not a regular file", fifo},
        {"not a regular file", folder}};
    for (const auto& [damage, spoil] : spoils) {
        SCOPED_TRACE(damage);
        spoil();
        testing::internal::CaptureStderr();
        const ReferenceImage again = cachedReference(scene, scene.camera, options, cache, &hit);
        const std::string said = testing::internal::GetCapturedStderr();
        EXPECT_FALSE(hit);
        EXPECT_EQ(again.rgba, truth.rgba); // rendered again, not the damaged bytes
        EXPECT_NE(said.find("reference cache entry " + entry.string() + " is damaged"),
                  std::string::npos)
            << said;
        EXPECT_NE(said.find(damage), std::string::npos) << said;
        // The entry was replaced (or, under a folder's name, could not be; said so), and no
        // temporary was left beside it.
        if (fs::is_directory(entry)) {
            EXPECT_NE(said.find("the image is not stored"), std::string::npos) << said;
            fs::remove_all(entry);
        } else {
            EXPECT_TRUE(fs::is_regular_file(entry));
        }
        for (const auto& file : fs::directory_iterator(cache))
            EXPECT_EQ(file.path().filename().string().rfind(".", 0), std::string::npos)
                << file.path();
        if (!fs::exists(entry)) cachedReference(scene, scene.camera, options, cache, &hit);
        cachedReference(scene, scene.camera, options, cache, &hit);
        EXPECT_TRUE(hit) << "a repaired entry is served again";
    }
}

} // namespace
